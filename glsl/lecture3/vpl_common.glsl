#version 330 core
// Lecture 3, "hierarchical quadtree search" for indirect light (Ki & Oh 2008, the light
// hierarchy): what the brute-force and the hierarchical gathers share.
// What the light gathers share: the receiver from the G-buffer and the light hierarchy as three
// atlases (one texelFetch per node of any level). What a light gives a receiver is the kernel
// compiled after this file (vpl_kernel.glsl, subsurface_dipole.glsl or environment_kernel.glsl).

uniform sampler2D u_receiver_position; // xyz, covered
uniform sampler2D u_receiver_normal;
uniform sampler2D u_cluster_position;  // atlases: xyz, radius
uniform sampler2D u_cluster_normal;    //          xyz (flux-weighted mean), weight
uniform sampler2D u_cluster_flux;      //          rgb, count
uniform int u_level_x[16];             // where each level starts in the atlases
uniform int u_level_y[16];

out vec4 o_gathered; // irradiance rgb, nodes visited

const float PI = 3.14159265358979;
ivec2 atlas_node(int level, ivec2 node) {
    return ivec2(u_level_x[level], u_level_y[level]) + node;
}
