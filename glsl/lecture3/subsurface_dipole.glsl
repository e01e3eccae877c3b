// Lecture 3, subsurface scattering on the light hierarchy (after Ki & Oh's hierarchical
// translucent rendering, reconstructed): the dipole diffusion profile of Jensen et al. 2001 as
// the gathers' kernel (subsurface.rs, Dipole, is the same on the CPU).
// Part of the gathers (vpl_gather_tree.frag, vpl_gather_brute.frag), after vpl_common.glsl; the
// program sets KERNEL to pick one of the three kernels (0 VPL irradiance, 1 the subsurface
// dipole, 2 directional sky light); this is kernel 1.
#if KERNEL == 1

uniform vec3 u_sigma_tr;    // sqrt(3 sigma_a sigma_t'), per channel
uniform vec3 u_alpha_prime; // sigma_s' / sigma_t'
uniform vec3 u_z_r;         // depth of the real source, 1 / sigma_t'
uniform vec3 u_z_v;         // height of the virtual source, z_r (1 + 4A/3)

// One pole of the dipole: z (sigma_tr d + 1) exp(-sigma_tr d) / d^3, d = sqrt(r^2 + z^2).
vec3 pole(float r, vec3 z) {
    vec3 d = sqrt(vec3(r * r) + z * z);
    vec3 s = u_sigma_tr * d;
    return z * (s + 1.0) * exp(-s) / (d * d * d);
}

// R_d(r) = alpha' / (4 pi) (real pole + virtual pole), times the sample's (or cluster's) power.
vec3 light_from(vec3 x, vec3 n, vec3 light_position, vec3 light_normal, vec3 flux) {
    float r = distance(x, light_position);
    return flux * (u_alpha_prime / (4.0 * PI) * (pole(r, u_z_r) + pole(r, u_z_v)));
}

// The criterion's distance: between the receiver and the cluster's centre.
float light_distance(vec3 x, vec3 n, vec3 light_position) {
    return distance(x, light_position);
}

#endif
