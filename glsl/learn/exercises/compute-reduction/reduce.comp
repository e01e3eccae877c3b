#version 430 core
// Lesson 10, a reduction in work-group shared memory: the ping-pong reduction of the
// fragment pipeline (lesson 3; paper 4, section 3.3) as a compute shader, the way the CUDA
// lecture writes it. A work group of 128 invocations loads 256 values (two each), adds them
// pairwise in on-chip shared memory, halving the stride with a barrier between steps, and
// writes one partial result. One pass shrinks the data 256-fold (a 2x2 fragment pass: 4).
// Each value is kept as (sum, max): two reductions at once.

layout(local_size_x = 128) in;

layout(std430, binding = 0) readonly buffer Input { vec2 b_input[]; };
layout(std430, binding = 1) writeonly buffer Output { vec2 b_output[]; };

uniform uint u_count; // values in the input

shared vec2 s_partial[128];

// Past the end: the identity of each operation (0 for the sum, the lowest float for max).
vec2 fetch(uint i) {
    return i < u_count ? b_input[i] : vec2(0.0, -3.402823e38);
}

vec2 combine(vec2 a, vec2 b) {
    return vec2(a.x + b.x, max(a.y, b.y));
}

void main() {
    uint local = gl_LocalInvocationID.x;
    uint first = gl_WorkGroupID.x * 256u + local;
    // Load: each invocation combines two values into shared memory.
    s_partial[local] = combine(fetch(first), fetch(first + 128u));
    barrier();
    // The tree: half the invocations fold the upper half onto the lower, until one is left.
    for (uint stride = 64u; stride > 0u; stride >>= 1) {
        if (local < stride) {
            // EXERCISE: the step of the tree is missing. As written nothing is folded, so
            // each group's result is only what its first invocation loaded.
        }
        barrier();
    }
    // One partial result per work group; the next pass reduces those.
    if (local == 0u) {
        b_output[gl_WorkGroupID.x] = s_partial[0];
    }
}
