#version 330 core
// Test of a building block: a pyramid level from the one below (lecture 3's pyramids).
// One level of a test pyramid: each texel is the sum of the 2x2 texels below it plus 1000,
// read with texelFetch from the texture's base level (the level below, by its level range).
uniform sampler2D u_below;
out vec4 o_value;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) * 2;
    float s = texelFetch(u_below, p, 0).r + texelFetch(u_below, p + ivec2(1, 0), 0).r
            + texelFetch(u_below, p + ivec2(0, 1), 0).r + texelFetch(u_below, p + ivec2(1, 1), 0).r;
    o_value = vec4(s + 1000.0);
}
