#version 330 core
// Points at positions that a previous pass rendered into a texture and a PBO copied into
// this vertex buffer.
layout(location = 0) in vec4 a_position;

void main() {
    gl_Position = a_position;
    gl_PointSize = 1.0;
}
