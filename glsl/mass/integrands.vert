#version 330 core
// Paper 4, section 3.1 step 1: render the geometry with an orthographic projection onto
// the xy plane. Each vertex carries the sign of the z component of its triangle's world
// normal (the mesh is stored once per facing, see mass::integrands::Soup): all the
// listing's sign(n_z) needs.

layout(location = 0) in vec3 a_position;  // body frame
layout(location = 1) in float a_face_n_z; // +1 or -1, world frame

uniform mat4 u_model;         // body frame -> world
uniform vec3 u_frame_center;  // world point at the framing centre
uniform mat4 u_projection;    // framing-relative -> clip (Framing::projection)

// homogeneous coordinate of the surface point, relative to the framing centre
out vec4 p;
// z component of the surface normal (its sign: all the listing uses)
out float n_z;

void main()
{
    vec3 world = (u_model * vec4(a_position, 1.0)).xyz;
    p = vec4(world - u_frame_center, 1.0);
    n_z = a_face_n_z;
    gl_Position = u_projection * p;
}
