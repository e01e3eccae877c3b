#version 330 core
// Frames of the buoyancy scene [paper 4, Fig. 9]: a body, flat-shaded by its face normals.
layout(location = 0) in vec3 position;     // body frame
layout(location = 1) in vec3 face_normal;  // body frame
uniform mat4 model;
uniform mat4 view_projection;
out vec3 normal;
out float height;
void main()
{
    vec4 world = model * vec4(position, 1.0);
    normal = mat3(model) * face_normal;
    height = world.z;
    gl_Position = view_projection * world;
}
