#version 330 core
// Paper 1 (Zhang & Kim 2007), Fig. 1 and Fig. 6(a): the snapshots of the colliding models (the
// view).
// Fig. 1 / Fig. 6(a) snapshot: the two models and the boxes of their colliding AABB pairs,
// seen from an oblique orthographic view. One colour per vertex.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_colour;
uniform mat4 u_mvp;
out vec3 v_colour;
out vec3 v_position;

void main() {
    v_colour = a_colour;
    v_position = a_position;
    gl_Position = u_mvp * vec4(a_position, 1.0);
}
