#version 430 core
// Lesson 8, the compute counterpart of the reduced readback: stream compaction. Every
// non-zero element is appended to a list through an atomic counter; the CPU reads the count
// and exactly that many entries (src/collide/compute_overlap.rs does this for paper 1).

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Data { vec4 b_data[]; };
layout(std430, binding = 1) writeonly buffer Indices { uint b_indices[]; };
layout(std430, binding = 2) writeonly buffer Values { vec4 b_values[]; };
layout(binding = 0, offset = 0) uniform atomic_uint c_found;

uniform uint u_count;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    vec4 v = b_data[i];
    // Only what is there is written: its slot in the list comes from the counter.
    if (any(notEqual(v, vec4(0.0)))) {
        uint slot = atomicCounterIncrement(c_found);
        b_indices[slot] = i;
        b_values[slot] = v;
    }
}
