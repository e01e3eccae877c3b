#version 430 core
// Test of a building block: stream compaction with an atomic counter (the compute formulation of
// paper 1's readback).
// Stream compaction with an atomic counter: every invocation whose value passes the test
// takes the next free slot of the output and writes its index there.

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Values { uint b_values[]; };
layout(std430, binding = 1) writeonly buffer Kept { uint b_kept[]; };
layout(binding = 0, offset = 0) uniform atomic_uint u_kept;

uniform uint u_count;
uniform uint u_divisor;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count || b_values[i] % u_divisor != 0u) return;
    b_kept[atomicCounterIncrement(u_kept)] = i;
}
