#version 330 core
// Lecture 3, "hierarchical quadtree search" for indirect light (Ki & Oh 2008, the light
// hierarchy): the receivers, one per pixel.
// The receivers: what the camera sees, one surface point per pixel (position, normal,
// albedo); w = 1 marks covered pixels.

in vec3 v_position;
in vec3 v_normal;
in vec3 v_albedo;

layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_albedo;

void main() {
    o_position = vec4(v_position, 1.0);
    o_normal = vec4(normalize(v_normal), 0.0);
    o_albedo = vec4(v_albedo, 1.0);
}
