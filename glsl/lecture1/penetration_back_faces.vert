#version 330 core
// Lecture 1, penetration depth (Kim, Otaduy, Lin & Manocha, SCA 2002), the closest-point query
// by rasterization (a reconstruction: lecture1-sources.md, section 1): the vertex stage.
// Every Minkowski sum's triangles go through one cube face's 90° view from the origin; each
// vertex carries its sum's range of face planes, which the fragment stage reads.

// A vertex of a sum, in the unit frame (coordinates within [-1, 1]).
layout(location = 0) in vec3 a_position;
// The sum's planes: first index and count in the plane texture.
layout(location = 1) in ivec2 a_planes;

// The face's view and perspective (x = right·p, y = up·p, w = forward·p).
uniform mat4 u_view_projection;

flat out ivec2 v_planes;

void main() {
    v_planes = a_planes;
    gl_Position = u_view_projection * vec4(a_position, 1.0);
}
