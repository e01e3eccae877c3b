#version 330 core
// The single line of the stream update (Sec. 6): across the whole 1D render target, from its
// left edge to its right edge at mid-height, one fragment per AABB of the stream.

void main() {
    gl_Position = vec4(gl_VertexID == 0 ? -1.0 : 1.0, 0.0, 0.0, 1.0);
}
