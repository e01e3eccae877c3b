#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006):
// the minification prefilter (reconstructed; src/lecture3/displacement/prefilter.rs).
// Compiled after: glsl/lecture3/pixel_ray.glsl, glsl/lecture3/displace_normal.glsl
// Compiled after: glsl/lecture3/displace_common.glsl
// Where a pixel's footprint covers many patches the traversal stops at a node the footprint
// covers: no wider than it, and no wider across the ray, its height range seen from the side
// included (a node with tall thin walls is not covered, as the rays that pass it see the walls'
// sides and tops, not their mean). There it meets a prefiltered surface: one bilinear patch
// per node, its corners the mean of the height samples about each corner (four nodes of the
// mean pyramid), clamped under the node's bound so that the max pyramid still bounds it. Every
// hit of such a pixel is shaded at the level of its footprint with the facets facing the eye
// (the shading pyramid, bilinear between node centres).

uniform sampler2D u_bounds;   // max pyramid of the patch bounds, as an atlas
uniform sampler2D u_lows;     // min pyramid of the patch bounds (patch minima), same layout
uniform int u_level_x[16];    // where each level starts in the atlas
uniform int u_level_y[16];
uniform int u_prefilter;      // 0: trace the finest patches; 1: stop at the footprint's level
uniform float u_footprint;    // the pixel's footprint in patches per unit of ray parameter
uniform sampler2D u_means;    // mean pyramid of the height samples, as an atlas
uniform int u_mean_x[16];     // where each of its levels starts in the atlas
uniform int u_mean_y[16];
uniform sampler2D u_shading;  // per node the mean projected-area weight toward the eye and
                              // the mean weighted lit cosine (rg), as an atlas laid out as
                              // the bound pyramid's (u_level_x, u_level_y)

// The stop level of a ray entering the box at t_in: the coarsest level <= top whose nodes,
// 2^L patches wide, are no wider than the footprint there.
int stop_level(float t_in, int top) {
    if (u_prefilter == 0) return 0;
    float footprint = t_in * u_footprint;
    int level = 0;
    for (int k = 1; k <= top; ++k) {
        if (float(1 << k) <= footprint) level = k;
    }
    return level;
}

// Whether the footprint covers node `node` of `level`, for a ray entering the box at t_in: the
// node's extent on the plane perpendicular to the ray (its width foreshortened by the ray's
// elevation, plus its height range seen from the side, in patches) no wider than the footprint
// there; its width across the ray (the level) is no wider either, as level <= stop says.
bool covers(Ray r, ivec2 node, int level, float t_in) {
    ivec2 at = ivec2(u_level_x[level], u_level_y[level]) + node;
    float range = texelFetch(u_bounds, at, 0).r - texelFetch(u_lows, at, 0).r;
    float sin_e = abs(r.d.z / u_world_to_grid.z); // the world ray is a unit vector
    float cos_e = sqrt(max(1.0 - sin_e * sin_e, 0.0));
    float relief = range * u_world_to_grid.x / u_world_to_grid.z;
    return float(1 << level) * sin_e + relief * cos_e <= t_in * u_footprint;
}

// Mean pyramid node m of `level`, clamped to the nodes that cover height samples.
float mean_node(ivec2 m, int level) {
    ivec2 valid = (u_patches + (1 << level)) >> level; // ceil(samples / 2^level)
    m = clamp(m, ivec2(0), valid - 1);
    return texelFetch(u_means, ivec2(u_mean_x[level], u_mean_y[level]) + m, 0).r;
}

// The prefiltered height at node corner c of `level`: the mean of the four nodes touching it.
float coarse_corner(ivec2 c, int level) {
    return 0.25 * ((mean_node(c - ivec2(1, 1), level) + mean_node(c - ivec2(0, 1), level))
                 + (mean_node(c - ivec2(1, 0), level) + mean_node(c, level)));
}

// The corners (h00, h10, h01, h11) of node `node`'s prefiltered patch, under its bound.
vec4 prefiltered_corners(ivec2 node, int level, float bound) {
    vec4 h = vec4(coarse_corner(node, level), coarse_corner(node + ivec2(1, 0), level),
                  coarse_corner(node + ivec2(0, 1), level), coarse_corner(node + ivec2(1, 1), level));
    return min(h, vec4(bound));
}

// Shading pyramid node m of `level`, clamped to the nodes that cover patches.
vec2 shading_node(ivec2 m, int level) {
    ivec2 valid = (u_patches + ((1 << level) - 1)) >> level; // ceil(patches / 2^level)
    m = clamp(m, ivec2(0), valid - 1);
    return texelFetch(u_shading, ivec2(u_level_x[level], u_level_y[level]) + m, 0).rg;
}

// The effective normal at grid point g on `level`: the shading pyramid's (weight, weighted lit
// cosine) interpolated bilinearly between node centres (node n's centre at (n + 1/2) 2^level),
// constant beyond the outer centres; the light's direction times their ratio, the visible
// facets' mean lit cosine (0 where none faces the eye).
vec3 prefiltered_normal(vec2 g, int level) {
    vec2 p = g / float(1 << level) - 0.5;
    ivec2 n = ivec2(floor(p));
    vec2 f = p - vec2(n);
    vec2 bottom = mix(shading_node(n, level), shading_node(n + ivec2(1, 0), level), f.x);
    vec2 top = mix(shading_node(n + ivec2(0, 1), level), shading_node(n + ivec2(1, 1), level), f.x);
    vec2 ws = mix(bottom, top, f.y);
    return (ws.x > 0.0 ? ws.y / ws.x : 0.0) * light_direction();
}
