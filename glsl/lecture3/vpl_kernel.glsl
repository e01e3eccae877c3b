// Lecture 3, "hierarchical quadtree search" for indirect light (Ki & Oh 2008, the light
// hierarchy): what a VPL or a cluster of VPLs gives a receiver (light.rs, VplKernel, is the same
// on the CPU).
// Part of the gathers (vpl_gather_tree.frag, vpl_gather_brute.frag), after vpl_common.glsl; the
// program sets KERNEL to pick one of the three kernels (0 VPL irradiance, 1 the subsurface
// dipole, 2 directional sky light); this is kernel 0.
#if KERNEL == 0

uniform float u_min_distance; // distances are clamped to this (the usual VPL bias)

// E = flux cos_l cos_r / (pi max(d, d_min)^2), cos_l = max(0, -n_l . w) with the cluster's
// mean normal, cos_r = max(0, n . w), w the unit direction from receiver to light.
vec3 light_from(vec3 x, vec3 n, vec3 light_position, vec3 light_normal, vec3 flux) {
    vec3 to_light = light_position - x;
    float d2 = dot(to_light, to_light);
    if (d2 < 1e-12) return vec3(0.0);
    float d = sqrt(d2);
    vec3 w = to_light / d;
    float cos_r = max(dot(n, w), 0.0);
    float cos_l = max(-dot(light_normal, w), 0.0);
    return flux * (cos_l * cos_r / (PI * max(d2, u_min_distance * u_min_distance)));
}

// The criterion's distance: between the receiver and the cluster's centre.
float light_distance(vec3 x, vec3 n, vec3 light_position) {
    return distance(x, light_position);
}

#endif
