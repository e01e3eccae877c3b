#version 330 core
// Lecture 1: pairwise triangle tests with the triangles in textures, a reconstruction of
// Choi, Kim & Kim 2006 (lecture1-sources.md, section 3). One fragment per triangle pair:
// pixel (column j, row i) of the tile tests triangle u_first.x + i of A against triangle
// u_first.y + j of B. Each triangle is three RGBA32F texels (xyz a corner, w its welded vertex
// id). The fragment writes 1 to P0 when the pair may intersect (pair_filter.glsl: box reject,
// then paper 1's exact test with fp32-filtered signs) and discards it otherwise; the readback
// is paper 1's hierarchical one, and the CPU confirms each reported pair with paper 1's exact
// predicate.
// Compiled after: glsl/lecture1/pair_filter.glsl

uniform sampler2D u_tri_a;
uniform sampler2D u_tri_b;
uniform int u_per_row_a; // triangles per texture row
uniform int u_per_row_b;
uniform ivec2 u_first;   // first triangle of A (rows) and of B (columns) in this tile
uniform ivec2 u_count;   // triangles in A and in B
uniform int u_self;      // 1: A and B are one model (pairs i < j, neighbours skipped)

out vec4 color;

// ---- Fetching: triangle t's corner c, and its welded vertex id in w.
vec4 corner(sampler2D tris, int per_row, int t, int c) {
    return texelFetch(tris, ivec2(3 * (t % per_row) + c, t / per_row), 0);
}

// region: pair-test-main
void main() {
    int i = u_first.x + int(gl_FragCoord.y);
    int j = u_first.y + int(gl_FragCoord.x);
    // Past the end of a model (the last tile), or not above the diagonal of one model.
    if (i >= u_count.x || j >= u_count.y || (u_self == 1 && i >= j))
        discard;
    bool hit = pair_may_intersect(
        corner(u_tri_a, u_per_row_a, i, 0), corner(u_tri_a, u_per_row_a, i, 1),
        corner(u_tri_a, u_per_row_a, i, 2), corner(u_tri_b, u_per_row_b, j, 0),
        corner(u_tri_b, u_per_row_b, j, 1), corner(u_tri_b, u_per_row_b, j, 2), u_self == 1);
    if (!hit)
        discard;
    color = vec4(1.0, 0.0, 0.0, 0.0);
}
// endregion
