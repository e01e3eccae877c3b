#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006): the
// image pyramid, one level from the level below.
// One level of a max (or min) image pyramid from the level below: each node keeps the
// extreme of its four children. The texture's readable levels are narrowed to the level
// below, so texelFetch level 0 reads it. A side that is already 1 repeats its one child.

uniform sampler2D u_below;
uniform ivec2 u_below_size;
uniform int u_op; // 0: max, 1: min

out float o_value;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) * 2;
    ivec2 q = min(p + 1, u_below_size - 1);
    float a = texelFetch(u_below, p, 0).r;
    float b = texelFetch(u_below, ivec2(q.x, p.y), 0).r;
    float c = texelFetch(u_below, ivec2(p.x, q.y), 0).r;
    float d = texelFetch(u_below, q, 0).r;
    o_value = u_op == 0 ? max(max(a, b), max(c, d)) : min(min(a, b), min(c, d));
}
