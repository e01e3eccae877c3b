#version 430 core
// The reduction ladder, compute rung 2 (lesson 10; Harris's kernel 2): interleaved addressing
// with a strided index. The one change from rung 1: invocation t works on index 2 s t, so the
// working invocations are the first 256 / (2s), packed together: whole subgroups work or
// idle, no divergence and no %. The price: neighbouring invocations now touch shared memory
// 2s apart, which lands many of them in the same bank (bank conflicts).

layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Input { float b_input[]; };
layout(std430, binding = 1) writeonly buffer Output { float b_output[]; };

uniform uint u_count; // values in the input

shared float s_sum[256];

void main() {
    uint t = gl_LocalInvocationID.x;
    uint i = gl_WorkGroupID.x * 256u + t;
    s_sum[t] = i < u_count ? b_input[i] : 0.0;
    barrier();
    for (uint s = 1u; s < 256u; s *= 2u) {
        // The strided index: the first invocations do the work.
        uint index = 2u * s * t;
        if (index < 256u) {
            s_sum[index] += s_sum[index + s];
        }
        barrier();
    }
    if (t == 0u) b_output[gl_WorkGroupID.x] = s_sum[0];
}
