#version 430 core
// Lecture 1: pairwise triangle tests as one compute pass (then and now), the counterpart of
// pair_test.frag (a reconstruction of Choi, Kim & Kim 2006, lecture1-sources.md, section 3).
// Invocation (x = j, y = i) tests triangle i of A against triangle j of B with the same
// filter (pair_filter.glsl: neighbours skipped, box reject, paper 1's exact test with
// fp32-filtered signs). A pair that may intersect takes the next slot of the pair list from
// an atomic counter: no pair texture, no tiles, no occlusion count and no hierarchical
// readback; the CPU reads the count and exactly that many pairs, then confirms each.
// Compiled after: glsl/lecture1/pair_filter.glsl

layout(local_size_x = 16, local_size_y = 16) in;

// ---- Inputs: three vec4 per triangle (xyz a corner, w its welded vertex id).
layout(std430, binding = 0) readonly buffer TrianglesA { vec4 b_tri_a[]; };
layout(std430, binding = 1) readonly buffer TrianglesB { vec4 b_tri_b[]; };
layout(std430, binding = 2) writeonly buffer Pairs { uvec2 b_pairs[]; };
layout(binding = 0, offset = 0) uniform atomic_uint u_pair_count;

uniform uint u_count_a;
uniform uint u_count_b;
uniform int u_self;       // 1: A and B are one model (pairs i < j, neighbours skipped)
uniform uint u_capacity;  // pairs the list holds; the count goes on past it

void main() {
    uint i = gl_GlobalInvocationID.y;
    uint j = gl_GlobalInvocationID.x;
    // Past the end of a model, or not above the diagonal of one model.
    if (i >= u_count_a || j >= u_count_b || (u_self == 1 && i >= j)) return;
    bool hit = pair_may_intersect(b_tri_a[3u * i], b_tri_a[3u * i + 1u], b_tri_a[3u * i + 2u],
                                  b_tri_b[3u * j], b_tri_b[3u * j + 1u], b_tri_b[3u * j + 2u],
                                  u_self == 1);
    if (!hit) return;
    // ---- Append (i, j) to the list.
    uint slot = atomicCounterIncrement(u_pair_count);
    if (slot < u_capacity) {
        b_pairs[slot] = uvec2(i, j);
    }
}
