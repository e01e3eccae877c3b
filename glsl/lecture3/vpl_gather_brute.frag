// Lecture 3, "hierarchical quadtree search" for indirect light (Ki & Oh 2008, the light
// hierarchy): the brute-force gather it is compared with.
// Compiled after: glsl/lecture3/vpl_common.glsl, #define KERNEL 0, glsl/lecture3/vpl_kernel.glsl
// Compiled after: glsl/lecture3/subsurface_dipole.glsl, glsl/lecture3/environment_kernel.glsl
// The brute-force gather the hierarchy is compared with: every VPL of level 0 summed.
// (The fragment stage is vpl_common.glsl, the program's #define KERNEL, the three kernel
// files (one kept by KERNEL), then this file.)

uniform int u_size; // the VPL image's side

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 receiver = texelFetch(u_receiver_position, pixel, 0);
    vec3 n = texelFetch(u_receiver_normal, pixel, 0).xyz;
    // (A receiver has a unit normal; testing it keeps the normal read for kernels without it.)
    if (receiver.w == 0.0 || dot(n, n) == 0.0) discard;
    vec3 x = receiver.xyz;
    vec3 sum = vec3(0.0);
    for (int j = 0; j < u_size; ++j) {
        for (int i = 0; i < u_size; ++i) {
            ivec2 at = atlas_node(0, ivec2(i, j));
            vec4 normal_weight = texelFetch(u_cluster_normal, at, 0);
            if (normal_weight.w > 0.0) {
                vec3 p = texelFetch(u_cluster_position, at, 0).xyz;
                vec3 flux = texelFetch(u_cluster_flux, at, 0).rgb;
                sum += light_from(x, n, p, normal_weight.xyz, flux);
            }
        }
    }
    o_gathered = vec4(sum, float(u_size * u_size));
}
