#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006):
// level 0 of the pyramid, the bounds of each bilinear patch.
// Level 0 of the displacement map's pyramid: for each bilinear patch, the extreme of its
// four corner samples (a bilinear patch takes its extremes at its corners). Texels past the
// last patch (the padding to a power of two) get the operation's identity.

uniform sampler2D u_heights; // the height map, one sample per texel
uniform ivec2 u_patches;     // (width - 1, height - 1)
uniform int u_op;            // 0: max, 1: min

out float o_value;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (any(greaterThanEqual(p, u_patches))) {
        o_value = u_op == 0 ? -3.4028235e38 : 3.4028235e38;
        return;
    }
    float a = texelFetch(u_heights, p, 0).r;
    float b = texelFetch(u_heights, p + ivec2(1, 0), 0).r;
    float c = texelFetch(u_heights, p + ivec2(0, 1), 0).r;
    float d = texelFetch(u_heights, p + ivec2(1, 1), 0).r;
    o_value = u_op == 0 ? max(max(a, b), max(c, d)) : min(min(a, b), min(c, d));
}
