#version 330 core
// Paper 4 (Kim, Kim, Ko & Terzopoulos 2006), section 5.3 "Simulation example" (Fig. 9): the bodies
// in the frames.
// Frames of the buoyancy scene [paper 4, Fig. 9]: a body, flat-shaded by its face normals.
layout(location = 0) in vec3 a_position;     // body frame
layout(location = 1) in vec3 a_face_normal;  // body frame
uniform mat4 u_model;
uniform mat4 u_view_projection;
out vec3 v_normal;
out float v_height;
void main()
{
    vec4 world = u_model * vec4(a_position, 1.0);
    v_normal = mat3(u_model) * a_face_normal;
    v_height = world.z;
    gl_Position = u_view_projection * world;
}
