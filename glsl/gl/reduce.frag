#version 330 core
// Building block: ping-pong reduction, 2x2 per pass, the shape of paper 4's summation (section
// 3.3, whose three-target copy is glsl/mass/reduce_sum.frag) and of lecture 3's pyramids; run
// by the selftest and the building-blocks bench.
// One pass of a ping-pong reduction: each output texel combines the 2x2 block of input
// texels it covers, so n texels take ceil(log2 n) passes. Texels past the input's edge (odd
// sizes) contribute the operation's identity.

uniform sampler2D u_input;
uniform ivec2 u_input_size;
uniform int u_op;        // 0: sum, 1: min, 2: max
uniform bool u_nonzero;  // first pass of OR / count: each component becomes (x != 0)

out vec4 o_result;

vec4 identity() {
    if (u_op == 0) return vec4(0.0);
    if (u_op == 1) return vec4(3.402823e38);
    return vec4(-3.402823e38);
}

vec4 fetch(ivec2 p) {
    if (any(greaterThanEqual(p, u_input_size))) return identity();
    vec4 v = texelFetch(u_input, p, 0);
    return u_nonzero ? vec4(notEqual(v, vec4(0.0))) : v;
}

vec4 combine(vec4 a, vec4 b) {
    if (u_op == 0) return a + b;
    if (u_op == 1) return min(a, b);
    return max(a, b);
}

void main() {
    ivec2 base = ivec2(gl_FragCoord.xy) * 2;
    vec4 r = combine(fetch(base), fetch(base + ivec2(1, 0)));
    r = combine(r, fetch(base + ivec2(0, 1)));
    o_result = combine(r, fetch(base + ivec2(1, 1)));
}
