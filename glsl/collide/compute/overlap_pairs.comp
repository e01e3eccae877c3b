#version 430 core
// Paper 1 (Zhang & Kim 2007), section 5.2 step 2 "Elementary AABB Overlap Test" and 5.3 "Stream
// Reduction", as one compute pass (then and now).
// The AABB overlap test over all leaf pairs, with stream compaction: invocation (i, j) tests
// leaf i of X against leaf j of Y and, when the boxes overlap, takes the next slot of the
// pair list from an atomic counter and writes (i, j) there. The list comes back as it is:
// no occlusion count, no P0 image, no hierarchical readback to find the set pixels.

layout(local_size_x = 16, local_size_y = 16) in;

layout(std430, binding = 0) readonly buffer BoxesX { vec4 b_boxes_x[]; };
layout(std430, binding = 1) readonly buffer BoxesY { vec4 b_boxes_y[]; };
layout(std430, binding = 2) writeonly buffer Pairs { uvec2 b_pairs[]; };
layout(binding = 0, offset = 0) uniform atomic_uint u_pair_count;

uniform uint u_leaves_x;
uniform uint u_leaves_y;
uniform uint u_capacity;  // pairs the list holds; the count goes on past it

void main() {
    uint i = gl_GlobalInvocationID.y;
    uint j = gl_GlobalInvocationID.x;
    if (i >= u_leaves_x || j >= u_leaves_y) return;
    vec3 min_x = b_boxes_x[2u * i].xyz;
    vec3 max_x = b_boxes_x[2u * i + 1u].xyz;
    vec3 min_y = b_boxes_y[2u * j].xyz;
    vec3 max_y = b_boxes_y[2u * j + 1u].xyz;
    // Closed boxes: touching counts as overlapping (Table I's interval test).
    if (any(greaterThan(min_x, max_y)) || any(lessThan(max_x, min_y))) return;
    uint slot = atomicCounterIncrement(u_pair_count);
    if (slot < u_capacity) {
        b_pairs[slot] = uvec2(i, j);
    }
}
