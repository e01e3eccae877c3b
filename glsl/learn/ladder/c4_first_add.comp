#version 430 core
// The reduction ladder, compute rung 4 (lesson 10; Harris's kernel 4): the first add during
// the global load. The one change from rung 3: each invocation loads two values, 256 apart,
// and adds them before they reach shared memory, so a group covers 512 values, half as many
// groups run, and no invocation is idle in the first step.

layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Input { float b_input[]; };
layout(std430, binding = 1) writeonly buffer Output { float b_output[]; };

uniform uint u_count; // values in the input

shared float s_sum[256];

float fetch(uint i) {
    return i < u_count ? b_input[i] : 0.0;
}

void main() {
    uint t = gl_LocalInvocationID.x;
    uint i = gl_WorkGroupID.x * 512u + t;
    // The first add, during the load.
    s_sum[t] = fetch(i) + fetch(i + 256u);
    barrier();
    for (uint s = 128u; s > 0u; s >>= 1) {
        if (t < s) {
            s_sum[t] += s_sum[t + s];
        }
        barrier();
    }
    if (t == 0u) b_output[gl_WorkGroupID.x] = s_sum[0];
}
