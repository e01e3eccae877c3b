#version 430 core
// The reduction ladder, compute rung 1 (lesson 10; Harris's kernel 1): interleaved addressing
// with a divergent branch. A work group of 256 invocations loads 256 values into shared
// memory and adds them in a tree: at step s, invocation t with t % (2s) == 0 adds the value s
// places up. The active invocations are scattered over every subgroup (a warp in CUDA), so
// every subgroup runs the branch with most of its lanes idle, and % is a slow instruction.

layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Input { float b_input[]; };
layout(std430, binding = 1) writeonly buffer Output { float b_output[]; };

uniform uint u_count; // values in the input

shared float s_sum[256];

void main() {
    uint t = gl_LocalInvocationID.x;
    uint i = gl_WorkGroupID.x * 256u + t;
    // Load one value each; past the end, the sum's identity.
    s_sum[t] = i < u_count ? b_input[i] : 0.0;
    barrier();
    for (uint s = 1u; s < 256u; s *= 2u) {
        // The divergent branch: every (2s)-th invocation works.
        if (t % (2u * s) == 0u) {
            s_sum[t] += s_sum[t + s];
        }
        barrier();
    }
    if (t == 0u) b_output[gl_WorkGroupID.x] = s_sum[0];
}
