#version 330 core
// Building block: the rectangle of every full-target pass (papers 1-4 and lecture 3).
// A pixel-exact rectangle without vertex buffers: four corners of a triangle strip made
// from gl_VertexID. A fragment is produced exactly for the pixels whose centres lie inside
// [x0, x1) x [y0, y1), the GPGPU "one fragment per output element".

uniform vec4 u_rect;     // x0, y0, x1, y1 in pixels, relative to the viewport
uniform vec2 u_viewport; // viewport size in pixels
out vec2 v_uv;           // 0..1 across the rectangle

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 pixel = mix(u_rect.xy, u_rect.zw, corner);
    v_uv = corner;
    gl_Position = vec4(pixel / u_viewport * 2.0 - 1.0, 0.0, 1.0);
}
