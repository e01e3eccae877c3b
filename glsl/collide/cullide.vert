#version 330 core
// Paper 1 (Zhang & Kim 2007), section 7.4.2 "CULLIDE": the method it is compared with, its
// orthographic views.
// CULLIDE's orthographic views (Govindaraju et al. 2003): the model seen along one axis,
// the view volume being the overlap of the two models' boxes (no collision lies outside).

layout(location = 0) in vec3 a_position;
uniform mat4 u_mvp;

void main() {
    gl_Position = u_mvp * vec4(a_position, 1.0);
}
