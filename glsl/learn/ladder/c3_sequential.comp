#version 430 core
// The reduction ladder, compute rung 3 (lesson 10; Harris's kernel 3): sequential addressing.
// The one change from rung 2: the stride starts at half the group and halves, and invocation t
// adds the value s places up. Neighbouring invocations read neighbouring words: no bank
// conflicts, the working invocations still packed. Half of them idle from the first step.

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
    // Sequential addressing: fold the upper half onto the lower, halving the stride.
    for (uint s = 128u; s > 0u; s >>= 1) {
        if (t < s) {
            s_sum[t] += s_sum[t + s];
        }
        barrier();
    }
    if (t == 0u) b_output[gl_WorkGroupID.x] = s_sum[0];
}
