#version 330 core
// Paper 4, section 3.1 step 1: render the geometry with an orthographic projection onto
// the xy plane. The CPU poses each body, applies its framing's orthographic projection and
// places it in its tile of the target (mass::integrands::Soup), so that one draw serves
// every body of a batch. Each vertex carries the sign of the z component of its
// triangle's world normal (each posed body is stored once per facing): all the listing's
// sign(n_z) needs.

layout(location = 0) in vec3 a_clip;       // clip position in the whole target
layout(location = 1) in float a_face_n_z;  // +1 or -1, world frame
layout(location = 2) in vec3 a_p;          // world position relative to the framing centre

// homogeneous coordinate of the surface point, relative to the framing centre
out vec4 p;
// z component of the surface normal (its sign: all the listing uses)
out float n_z;

void main()
{
    p = vec4(a_p, 1.0);
    n_z = a_face_n_z;
    gl_Position = vec4(a_clip, 1.0);
}
