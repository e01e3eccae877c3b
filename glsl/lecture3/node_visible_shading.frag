#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006):
// one level of the shading pyramid the minification prefilter shades with, drawn for each view
// straight into its place in the atlas (reconstructed; src/lecture3/displacement/visible_shading.rs).
// Compiled after: glsl/lecture3/displace_normal.glsl
// For each node of the level: the mean over the patches it covers of each patch's facets, at
// the centres of its four quarters (the midpoint rule): the facet's area projected toward the
// eye per unit of grid area, max(g . v, 0) with g = n / n_z, and that weight times the facet's
// lit cosine. The traversal divides one by the other. One pass per level read, from the height
// map itself: no level below is drawn or copied.

uniform sampler2D u_heights; // the height map, one sample per texel
uniform ivec2 u_patches;     // (width - 1, height - 1)
uniform vec3 u_eye;          // the camera, world
uniform int u_level;         // the level drawn: nodes 2^level patches wide
uniform ivec2 u_offset;      // where the level starts in the atlas

out vec4 o_value;            // (weight, weight x lit cosine, 0, 0), means over the node

// The weight and weighted lit cosine of the facet at local st of the patch with corners h at
// grid cell p.
vec2 facet(vec4 h, ivec2 p, vec2 st) {
    vec3 n = patch_normal(h, st, 1.0);
    float z = mix(mix(h.x, h.y, st.x), mix(h.z, h.w, st.x), st.y);
    vec3 world = vec3(vec2(p) + st, z) / u_world_to_grid;
    vec3 v = normalize(u_eye - world);
    float w = max(dot(n / n.z, v), 0.0);
    return vec2(w, w * max(dot(n, light_direction()), 0.0));
}

// The mean of patch p's four facets.
vec2 patch_value(ivec2 p) {
    vec4 h = vec4(texelFetch(u_heights, p, 0).r, texelFetch(u_heights, p + ivec2(1, 0), 0).r,
                  texelFetch(u_heights, p + ivec2(0, 1), 0).r,
                  texelFetch(u_heights, p + ivec2(1, 1), 0).r);
    vec2 sum = (facet(h, p, vec2(0.25, 0.25)) + facet(h, p, vec2(0.75, 0.25)))
             + (facet(h, p, vec2(0.25, 0.75)) + facet(h, p, vec2(0.75, 0.75)));
    return 0.25 * sum;
}

void main() {
    ivec2 node = ivec2(gl_FragCoord.xy) - u_offset;
    // The patches the node covers, cut at the map's edge (nodes past it cover none: 0).
    ivec2 first = node << u_level;
    ivec2 last = min(first + (1 << u_level), u_patches);
    if (any(greaterThanEqual(first, u_patches))) {
        o_value = vec4(0.0);
        return;
    }
    vec2 sum = vec2(0.0);
    for (int y = first.y; y < last.y; ++y) {
        for (int x = first.x; x < last.x; ++x) {
            sum += patch_value(ivec2(x, y));
        }
    }
    o_value = vec4(sum / float((last.x - first.x) * (last.y - first.y)), 0.0, 0.0);
}
