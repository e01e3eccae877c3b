#version 330 core
// Lecture 3, "hierarchical quadtree search" for indirect light (Ki & Oh 2008, the light
// hierarchy): the scene, seen from the light or the camera.
// The room of the light-hierarchy scene, seen from the spot light or from the camera.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_albedo;

uniform mat4 u_view_projection;

out vec3 v_position;
out vec3 v_normal;
out vec3 v_albedo;

void main() {
    v_position = a_position;
    v_normal = a_normal;
    v_albedo = a_albedo;
    gl_Position = u_view_projection * vec4(a_position, 1.0);
}
