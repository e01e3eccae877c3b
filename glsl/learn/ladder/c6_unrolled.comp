#version 430 core
// The reduction ladder, compute rung 6 (lesson 10; Harris's kernel 6): the tree unrolled
// completely. The one change from rung 5: the group size is a constant the compiler knows
// (Harris makes it a C++ template parameter; here a #define), so the loop of the first steps is
// written out too, each step behind a test on that constant that the compiler resolves: a
// group of 256 compiles to its eight steps and nothing else. In GLSL `local_size_x` is always
// a constant, so a compiler may have unrolled rung 5's loop already: the difference this rung
// makes is the compiler's to take or leave. Every barrier stays, as in rung 5: Harris drops
// those of the last warp, but GLSL promises no lock step.

#define GROUP 256u

layout(local_size_x = GROUP) in;

layout(std430, binding = 0) readonly buffer Input { float b_input[]; };
layout(std430, binding = 1) writeonly buffer Output { float b_output[]; };

uniform uint u_count; // values in the input

shared float s_sum[GROUP];

float fetch(uint i) {
    return i < u_count ? b_input[i] : 0.0;
}

// One step at a constant stride, compiled only when the group is larger than the stride.
#define STEP(S) if (GROUP > uint(S)) { if (t < uint(S)) { s_sum[t] += s_sum[t + uint(S)]; } barrier(); }

void main() {
    uint t = gl_LocalInvocationID.x;
    uint i = gl_WorkGroupID.x * (2u * GROUP) + t;
    s_sum[t] = fetch(i) + fetch(i + GROUP);
    barrier();
    STEP(256) STEP(128) STEP(64) STEP(32) STEP(16) STEP(8) STEP(4) STEP(2) STEP(1)
    if (t == 0u) b_output[gl_WorkGroupID.x] = s_sum[0];
}
