// Lecture 3, environment light on the light hierarchy (Ki & Oh 2008 name it among the
// hierarchy's uses; reconstructed): directional lights from a lat-long sky as the gathers'
// kernel (environment.rs, DirectionalKernel, is the same on the CPU).
// Compiled after: glsl/lecture3/vpl_common.glsl

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
