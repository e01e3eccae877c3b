#version 330 core
// Lecture 1, continuous collision for an avatar (Kim, Redon, Lin, Manocha & Templeman 2007):
// the GPU query on the swept surfaces, CULLIDE-style (Govindaraju et al. 2003), a
// reconstruction. The closed hulls around each link's swept capsule bound and around each
// nearby environment triangle, seen along one axis by an orthographic view.

layout(location = 0) in vec3 a_position;
// The view along x, y or z: the image over the overlap of the two sets' boxes, the depth
// over everything drawn (so that no far side of a hull is clipped away).
uniform mat4 u_mvp;

void main() {
    gl_Position = u_mvp * vec4(a_position, 1.0);
}
