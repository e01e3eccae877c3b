#version 430 core
// The reduction ladder, compute rung 5 (lesson 10; Harris's kernel 5): the last warp unrolled.
// The one change from rung 4: the loop stops when 32 values are left, and the last six steps
// (strides 32 down to 1) are written out, with no loop counter, compare or jump between them.
// Harris also drops those steps' barriers and the `t < s` test, because a CUDA warp of 32
// threads runs in lock step. GLSL promises no lock step (a subgroup's size and scheduling are
// the driver's; llvmpipe runs a group's invocations as CPU loops), so here every step keeps
// its `t < s` test and its barrier(); the subgroup additions of GL_KHR_shader_subgroup would be
// the portable way to drop them, where a context has that extension.

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
    // The loop, while more than a warp's worth of values is left.
    for (uint s = 128u; s > 32u; s >>= 1) {
        if (t < s) {
            s_sum[t] += s_sum[t + s];
        }
        barrier();
    }
    // The last warp's six steps, written out.
    STEP(32) STEP(16) STEP(8) STEP(4) STEP(2) STEP(1)
    if (t == 0u) b_output[gl_WorkGroupID.x] = s_sum[0];
}
