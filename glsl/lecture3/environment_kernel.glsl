// Lecture 3, environment light on the light hierarchy (Ki & Oh 2008 name it among the
// hierarchy's uses; reconstructed): directional lights from a lat-long sky as the gathers'
// kernel (environment.rs, DirectionalKernel, is the same on the CPU).
// Part of the gathers (vpl_gather_tree.frag, vpl_gather_brute.frag), after vpl_common.glsl; the
// program sets KERNEL to pick one of the three kernels (0 VPL irradiance, 1 the subsurface
// dipole, 2 directional sky light); this is kernel 2.
#if KERNEL == 2

// A light's "position" is its direction (a cluster's: the flux-weighted mean direction, shorter
// than 1); it gives flux max(n . c, 0), visibility ignored.
vec3 light_from(vec3 x, vec3 n, vec3 light_position, vec3 light_normal, vec3 flux) {
    return flux * max(dot(n, light_position), 0.0);
}

// The criterion's distance: how far the direction is from the receiver's horizon, |n . c|;
// radius < theta |n . c| with theta <= 1 keeps the whole cluster on one side of it.
float light_distance(vec3 x, vec3 n, vec3 light_position) {
    return abs(dot(n, light_position));
}

#endif
