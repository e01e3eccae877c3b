#version 330 core
// Test of a building block: render to a vertex buffer through a PBO (paper 2's pass 2).
// Points at positions that a previous pass rendered into a texture and a PBO copied into
// this vertex buffer.
layout(location = 0) in vec4 a_position;

void main() {
    gl_Position = a_position;
    gl_PointSize = 1.0;
}
