#version 330 core
// Paper 4, section 3.1 step 1: render the geometry with an orthographic projection onto
// the xy plane. Each vertex carries its triangle's normal, so n_z is the face's.

layout(location = 0) in vec3 position;     // body frame
layout(location = 1) in vec3 face_normal;  // body frame

uniform mat4 model;         // body frame -> world
uniform vec3 frame_center;  // world point at the framing centre
uniform mat4 projection;    // framing-relative -> clip (Framing::projection)

// homogeneous coordinate of the surface point, relative to the framing centre
out vec4 p;
// z component of the surface normal
out float n_z;

void main()
{
    vec3 world = (model * vec4(position, 1.0)).xyz;
    p = vec4(world - frame_center, 1.0);
    n_z = (mat3(model) * face_normal).z;
    gl_Position = projection * p;
}
