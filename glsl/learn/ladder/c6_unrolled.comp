#version 430 core
// The reduction ladder, compute rung 5 (lesson 10; Harris's kernels 5 and 6): the tree
// unrolled. The one change from rung 4: the group size is a constant known when the shader is
// compiled, so the eight steps are written out, with no loop counter, no compare and no jump
// between them. Harris also drops the barriers of the last six steps, trusting that a CUDA
// warp of 32 runs in lock step; GLSL promises no such thing (a subgroup's size and lock step
// are the driver's), so every step here keeps its barrier(). Subgroup additions
// (GL_KHR_shader_subgroup) are the portable way to drop them, but OpenGL 4.3 does not have
// them and llvmpipe need not offer them.

layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Input { float b_input[]; };
layout(std430, binding = 1) writeonly buffer Output { float b_output[]; };

uniform uint u_count; // values in the input

shared float s_sum[256];

float fetch(uint i) {
    return i < u_count ? b_input[i] : 0.0;
}

// One step of the tree at a constant stride; barrier() stays outside the branch, where
// every invocation of the group reaches it.
#define STEP(S) if (t < uint(S)) { s_sum[t] += s_sum[t + uint(S)]; } barrier();

void main() {
    uint t = gl_LocalInvocationID.x;
    uint i = gl_WorkGroupID.x * 512u + t;
    s_sum[t] = fetch(i) + fetch(i + 256u);
    barrier();
    STEP(128) STEP(64) STEP(32) STEP(16) STEP(8) STEP(4) STEP(2) STEP(1)
    if (t == 0u) b_output[gl_WorkGroupID.x] = s_sum[0];
}
