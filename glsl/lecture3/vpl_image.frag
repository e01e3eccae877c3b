#version 330 core
// Lecture 3, "hierarchical quadtree search" for indirect light (Ki & Oh 2008, the light
// hierarchy): virtual point lights stored in images.
// Virtual point lights into images: the scene seen from the spot light (a reflective shadow
// map); every texel is a VPL at the surface it sees, with the flux that surface reflects:
// albedo x intensity x the texel's solid angle, dw = (2t/N)^2 / (1 + |ndc|^2 t^2)^(3/2) for a
// square frustum of half-extent t = tan(fov / 2). Texels that see nothing stay cleared: no
// flux, weight 0.

in vec3 v_position;
in vec3 v_normal;
in vec3 v_albedo;

uniform vec3 u_intensity;    // per steradian
uniform float u_half_extent; // tan(fov / 2)
uniform float u_size;        // N, the image's side

layout(location = 0) out vec4 o_position; // xyz, bounding radius (0 for one VPL)
layout(location = 1) out vec4 o_normal;   // xyz, weight (the flux's r + g + b)
layout(location = 2) out vec4 o_flux;     // rgb, number of VPLs

void main() {
    vec2 ndc = gl_FragCoord.xy / u_size * 2.0 - 1.0;
    float t = u_half_extent;
    float r2 = 1.0 + dot(ndc, ndc) * t * t;
    float side = 2.0 * t / u_size;
    float solid_angle = side * side / (r2 * sqrt(r2));
    vec3 flux = v_albedo * u_intensity * solid_angle;
    o_position = vec4(v_position, 0.0);
    o_normal = vec4(normalize(v_normal), flux.r + flux.g + flux.b);
    o_flux = vec4(flux, 1.0);
}
