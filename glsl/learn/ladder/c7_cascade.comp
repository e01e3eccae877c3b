#version 430 core
// The reduction ladder, compute rung 7 (lesson 10; Harris's kernel 7): several values per
// invocation (algorithm cascading). The one change from rung 6: far fewer groups are
// dispatched (the host asks for one per 8192 values), and each invocation first adds up its
// share of the input in a loop, two values per turn, striding by the whole dispatch's width,
// before the same unrolled tree. The tree's barriers and shared-memory traffic are paid once
// per 8192 values instead of once per 512, and the sequential adds hide the loads' latency.

#define GROUP 256u

layout(local_size_x = GROUP) in;

layout(std430, binding = 0) readonly buffer Input { float b_input[]; };
layout(std430, binding = 1) writeonly buffer Output { float b_output[]; };

uniform uint u_count; // values in the input

shared float s_sum[GROUP];

#define STEP(S) if (GROUP > uint(S)) { if (t < uint(S)) { s_sum[t] += s_sum[t + uint(S)]; } barrier(); }

void main() {
    uint t = gl_LocalInvocationID.x;
    // The whole dispatch's width: the stride of the loop (a grid-stride loop in CUDA).
    uint width = gl_NumWorkGroups.x * (2u * GROUP);
    float sum = 0.0;
    for (uint i = gl_WorkGroupID.x * (2u * GROUP) + t; i < u_count; i += width) {
        sum += b_input[i];
        if (i + GROUP < u_count) sum += b_input[i + GROUP];
    }
    s_sum[t] = sum;
    barrier();
    STEP(256) STEP(128) STEP(64) STEP(32) STEP(16) STEP(8) STEP(4) STEP(2) STEP(1)
    if (t == 0u) b_output[gl_WorkGroupID.x] = s_sum[0];
}
