#version 330 core
// Paper 1 (Zhang & Kim 2007), Fig. 1 and Fig. 6(a): the snapshots of the colliding models
// (shading).
// Flat shading from the screen-space derivatives of the position (no normals needed);
// lines (u_lit = 0) keep their colour.

in vec3 v_colour;
in vec3 v_position;
uniform bool u_lit;
uniform vec3 u_light; // direction towards the light, world space
out vec4 o_colour;

void main() {
    float shade = 1.0;
    if (u_lit) {
        vec3 n = normalize(cross(dFdx(v_position), dFdy(v_position)));
        shade = 0.35 + 0.65 * abs(dot(n, u_light));
    }
    o_colour = vec4(v_colour * shade, 1.0);
}
