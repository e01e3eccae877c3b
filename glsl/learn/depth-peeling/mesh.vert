#version 330 core
// Lesson 7, depth peeling: the mesh seen from above by an orthographic camera (paper 4,
// section 3.2 projects the body along one axis the same way).

layout(location = 0) in vec3 a_position;
uniform mat4 u_mvp; // the box around the mesh onto the view: top nearest

void main() {
    gl_Position = u_mvp * vec4(a_position, 1.0);
}
