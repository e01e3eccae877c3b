#version 330 core
// The vertex shader of depth peeling: an orthographic view, and an optional clip plane
// (paper 4's fluid surface: only what lies below it is peeled).

layout(location = 0) in vec3 a_position;

uniform mat4 u_mvp;
uniform vec4 u_clip_plane; // keeps points p with dot(u_clip_plane, vec4(p, 1)) >= 0

out vec3 v_position;

void main() {
    v_position = a_position;
    gl_Position = u_mvp * vec4(a_position, 1.0);
    gl_ClipDistance[0] = dot(u_clip_plane, vec4(a_position, 1.0));
}
