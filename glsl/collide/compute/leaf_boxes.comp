#version 430 core
// Paper 1 (Zhang & Kim 2007), section 6 "Stream Update", as a compute pass (the then-and-now
// formulation).
// Stream update as a compute pass: one invocation per real leaf takes the min and max of its
// own vertices, gathered through the leaf's vertex list (no vertex texture column, no virtual
// slots, no render target).

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Positions { vec4 b_positions[]; };
// Leaf k's vertices are b_vertex_index[b_leaf_start[k] .. b_leaf_start[k + 1]].
layout(std430, binding = 1) readonly buffer LeafStart { uint b_leaf_start[]; };
layout(std430, binding = 2) readonly buffer VertexIndex { uint b_vertex_index[]; };
// Box k: b_boxes[2k] the minimum corner, b_boxes[2k + 1] the maximum.
layout(std430, binding = 3) writeonly buffer Boxes { vec4 b_boxes[]; };

uniform uint u_leaves;

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= u_leaves) return;
    uint first = b_leaf_start[k];
    uint end = b_leaf_start[k + 1u];
    vec3 lower = b_positions[b_vertex_index[first]].xyz;
    vec3 upper = lower;
    for (uint i = first + 1u; i < end; i++) {
        vec3 p = b_positions[b_vertex_index[i]].xyz;
        lower = min(lower, p);
        upper = max(upper, p);
    }
    b_boxes[2u * k] = vec4(lower, 1.0);
    b_boxes[2u * k + 1u] = vec4(upper, 1.0);
}
