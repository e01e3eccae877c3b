#version 330 core
// Paper 1 (Zhang & Kim 2007), section 5.2 "Streaming AABB Overlap Tests", step 1 "Stream Pairing".
// The rectangle of all AABB pairs of one tile (Sec. 5.2, Fig. 5): row i is slot i of S^X,
// column j slot j of S^Y. uvA runs up the rows and is the same in every column, so the 1D
// textures of X texture the rectangle periodically in the vertical direction; uvB runs along
// the columns for Y. Corners come from gl_VertexID (no vertex buffer), as in glsl/gl/rect.vert.

uniform vec4 u_rect;     // x0, y0, x1, y1 in pixels
uniform vec2 u_viewport; // viewport size in pixels
out float uvA;           // TEXCOORD0 of paper Table I
out float uvB;           // TEXCOORD1

// region: stream-pairing
void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 pixel = mix(u_rect.xy, u_rect.zw, corner);
    uvA = corner.y;
    uvB = corner.x;
    gl_Position = vec4(pixel / u_viewport * 2.0 - 1.0, 0.0, 1.0);
}
// endregion
