#version 330 core
// Lecture 3, "hierarchical quadtree search" for indirect light (Ki & Oh 2008, the light
// hierarchy): what the brute-force and the hierarchical gathers share.
// What the light gathers share: the receiver from the G-buffer, the light hierarchy as three
// atlases (one texelFetch per node of any level), and the irradiance a VPL or a cluster of
// VPLs gives a receiver (light.rs has the same formula on the CPU).

uniform sampler2D u_receiver_position; // xyz, covered
uniform sampler2D u_receiver_normal;
uniform sampler2D u_cluster_position;  // atlases: xyz, radius
uniform sampler2D u_cluster_normal;    //          xyz (flux-weighted mean), weight
uniform sampler2D u_cluster_flux;      //          rgb, count
uniform int u_level_x[16];             // where each level starts in the atlases
uniform int u_level_y[16];
uniform float u_min_distance;          // distances are clamped to this (the usual VPL bias)

out vec4 o_gathered; // irradiance rgb, nodes visited

const float PI = 3.14159265358979;

// E = flux cos_l cos_r / (pi max(d, d_min)^2), cos_l = max(0, -n_l . w) with the cluster's
// mean normal, cos_r = max(0, n . w), w the unit direction from receiver to light.
vec3 irradiance(vec3 x, vec3 n, vec3 light_position, vec3 light_normal, vec3 flux) {
    vec3 to_light = light_position - x;
    float d2 = dot(to_light, to_light);
    if (d2 < 1e-12) return vec3(0.0);
    float d = sqrt(d2);
    vec3 w = to_light / d;
    float cos_r = max(dot(n, w), 0.0);
    float cos_l = max(-dot(light_normal, w), 0.0);
    return flux * (cos_l * cos_r / (PI * max(d2, u_min_distance * u_min_distance)));
}

ivec2 atlas_node(int level, ivec2 node) {
    return ivec2(u_level_x[level], u_level_y[level]) + node;
}
