// Lecture 3, "hierarchical quadtree search" for indirect light (Ki & Oh 2008, the light
// hierarchy): the hierarchical search (tree traversal) of the lights.
// Compiled after: glsl/lecture3/vpl_common.glsl, #define KERNEL 0, glsl/lecture3/vpl_kernel.glsl
// Compiled after: glsl/lecture3/subsurface_dipole.glsl, glsl/lecture3/environment_kernel.glsl
// Hierarchical search of the light hierarchy [Ki & Oh 2008, reconstructed from the
// abstract]: a quadtree traversal from the root; a cluster is used as one light when it is
// small as seen from the receiver (radius < theta x distance, a solid-angle criterion; the
// kernel says what the distance is) and, with normal-aware clustering, its normals agree (the
// flux-weighted mean normal is at least u_min_coherence long), else its four children are
// visited; single VPLs are always used. Clusters without flux are skipped. The traversal
// needs no stack: nodes are numbered in Morton order per level, and "next" climbs while the
// node is its parent's last child. (The fragment stage is vpl_common.glsl, the program's
// #define KERNEL, the three kernel files (one kept by KERNEL), then this file.)

uniform int u_top;      // the root's level (the VPL image is 2^top a side)
uniform float u_theta;  // 0: every VPL individually
uniform float u_min_coherence; // normal-aware clustering: a cluster is one light only when its
                               // mean normal is at least this long (0: the fixed merge)

// The (x, y) of Morton index i: its even bits are x, its odd bits y.
int compact_bits(int v) {
    v &= 0x55555555;
    v = (v | (v >> 1)) & 0x33333333;
    v = (v | (v >> 2)) & 0x0f0f0f0f;
    v = (v | (v >> 4)) & 0x00ff00ff;
    v = (v | (v >> 8)) & 0x0000ffff;
    return v;
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 receiver = texelFetch(u_receiver_position, pixel, 0);
    vec3 n = texelFetch(u_receiver_normal, pixel, 0).xyz;
    // (A receiver has a unit normal; testing it keeps the normal read for kernels without it.)
    if (receiver.w == 0.0 || dot(n, n) == 0.0) discard;
    vec3 x = receiver.xyz;
    vec3 sum = vec3(0.0);
    int visited = 0;
    int level = u_top;
    int index = 0;
    while (true) {
        visited += 1;
        ivec2 at = atlas_node(level, ivec2(compact_bits(index), compact_bits(index >> 1)));
        vec4 normal_weight = texelFetch(u_cluster_normal, at, 0);
        bool next = true;
        if (normal_weight.w > 0.0) {
            vec4 position_radius = texelFetch(u_cluster_position, at, 0);
            float d = light_distance(x, n, position_radius.xyz);
            bool coherent = length(normal_weight.xyz) >= u_min_coherence;
            if (level == 0 || (position_radius.w < u_theta * d && coherent)) {
                vec3 flux = texelFetch(u_cluster_flux, at, 0).rgb;
                sum += light_from(x, n, position_radius.xyz, normal_weight.xyz, flux);
            } else {
                level -= 1; // descend to the first child
                index *= 4;
                next = false;
            }
        }
        if (next) {
            while (level < u_top && (index & 3) == 3) {
                index >>= 2;
                level += 1;
            }
            if (level == u_top) break;
            index += 1;
        }
    }
    o_gathered = vec4(sum, float(visited));
}
