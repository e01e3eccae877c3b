#version 330 core
// Paper 2 (Kang & Han 2006), section 3 "Implementation and Result": the shading both skinning
// methods share.
// Shading shared by both skinning methods (and the impostor capture), so that they render
// the same image: one directional light plus ambient, two-sided.

in vec3 v_normal;

uniform vec3 u_colour;
uniform vec3 u_light; // unit vector towards the light

layout(location = 0) out vec4 o_colour;

void main() {
    vec3 n = normalize(v_normal);
    float diffuse = abs(dot(n, u_light));
    o_colour = vec4(u_colour * (0.3 + 0.7 * diffuse), 1.0);
}
