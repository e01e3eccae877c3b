#version 330 core
// Lesson 9, pass 1 of render-to-vertex-buffer (paper 2, section 2: pass 1 skins one vertex
// per texel into a render target, which becomes the vertex buffer of pass 2). Here each
// texel (i, j) of an N x N target computes one vertex of a height field: x and y on the
// grid, z the height, w = 1. RGBA32F, as paper 2 chose for accuracy.

uniform int u_n; // grid side: N x N vertices
out vec4 o_position;

void main() {
    // This texel's grid coordinates, 0..1 at the texel centres.
    vec2 uv = gl_FragCoord.xy / float(u_n);
    // The surface: z = 0.25 sin(6u) cos(4v) over x, y in -1..1.
    float height = 0.25 * sin(6.0 * uv.x) * cos(4.0 * uv.y);
    o_position = vec4(uv * 2.0 - 1.0, height, 1.0);
}
