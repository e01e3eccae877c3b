#version 430 core
// Lesson 5, compute counterpart: the same histogram with atomicAdd on a storage buffer of
// counts. Any invocation may write any element; the atomic does the read-modify-write that
// the blending unit does for points.

layout(local_size_x = 64) in;

uniform uint u_count;
uniform int u_bins;

layout(std430, binding = 0) readonly buffer Values { float b_values[]; };
layout(std430, binding = 1) buffer Counts { uint b_counts[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    // The bin as the vertex shader computes it.
    float bin = min(floor(b_values[i] * float(u_bins)), float(u_bins - 1));
    atomicAdd(b_counts[int(bin)], 1u);
}
