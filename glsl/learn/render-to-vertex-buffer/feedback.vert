#version 330 core
// Lesson 9, the same vertices by transform feedback (OpenGL 3.0, after the papers): the
// vertex shader computes each vertex from gl_VertexID and its output is captured into a
// buffer, nothing rasterized. No render target, no pixel buffer, no copy.

uniform int u_n;
out vec4 v_position; // captured, interleaved, into the feedback buffer

void main() {
    // Vertex k is grid texel (k mod N, k div N), as pass 1 lays them out row by row.
    ivec2 texel = ivec2(gl_VertexID % u_n, gl_VertexID / u_n);
    vec2 uv = (vec2(texel) + 0.5) / float(u_n);
    float height = 0.25 * sin(6.0 * uv.x) * cos(4.0 * uv.y);
    v_position = vec4(uv * 2.0 - 1.0, height, 1.0);
}
