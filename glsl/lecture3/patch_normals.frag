#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006):
// level 0 of the normal pyramid the minification prefilter shades with (reconstructed;
// src/lecture3/displacement/normals.rs).
// Compiled after: glsl/lecture3/displace_normal.glsl
// For each bilinear patch, the mean of its unit normals (world): the average of the normals
// at the centres of its four quarters (the midpoint rule). The mean is not normalised: its
// length, under 1 where the patch bends, is what the mean pyramid above averages on.
// Texels past the last patch (the padding to a power of two) get 0, which the mean pyramid
// weights by nothing.

uniform sampler2D u_heights; // the height map, one sample per texel
uniform ivec2 u_patches;     // (width - 1, height - 1)

out vec4 o_value;            // the mean unit normal, xyz; w = 0

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (any(greaterThanEqual(p, u_patches))) {
        o_value = vec4(0.0);
        return;
    }
    vec4 h = vec4(texelFetch(u_heights, p, 0).r, texelFetch(u_heights, p + ivec2(1, 0), 0).r,
                  texelFetch(u_heights, p + ivec2(0, 1), 0).r,
                  texelFetch(u_heights, p + ivec2(1, 1), 0).r);
    vec3 sum = (patch_normal(h, vec2(0.25, 0.25), 1.0) + patch_normal(h, vec2(0.75, 0.25), 1.0))
             + (patch_normal(h, vec2(0.25, 0.75), 1.0) + patch_normal(h, vec2(0.75, 0.75), 1.0));
    o_value = vec4(0.25 * sum, 0.0);
}
