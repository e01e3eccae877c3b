#version 330 core
// Paper 1 (Zhang & Kim 2007), section 6 "Stream Update": the line drawn across the 1D render
// target.
// The single line of the stream update (Sec. 6): across the whole 1D render target at
// mid-height, one fragment per AABB of the stream. It runs half a pixel past both edges, so
// that the first and last pixels are covered whether the rasterizer clips the line at the
// viewport or draws it in a guard band.

uniform float u_pad; // half a pixel in clip coordinates: 1 / width

void main() {
    float x = gl_VertexID == 0 ? -1.0 - u_pad : 1.0 + u_pad;
    gl_Position = vec4(x, 0.0, 0.0, 1.0);
}
