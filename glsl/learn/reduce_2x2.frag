#version 330 core
// Lesson 3, reduction level by level (2x2): each output texel combines the 2x2 block of the
// level below it covers, so each pass halves both sides and n x n values take ceil(log2 n)
// passes. Red carries the sum, green the maximum: two reductions in one ladder.

uniform sampler2D u_level; // the level below: red = partial sums, green = partial maxima
uniform ivec2 u_size;      // its size in texels

out vec4 o_result;

// A texel of the level below; past its edge (odd sizes) the identities: 0 for the sum, the
// lowest float for the maximum.
vec2 fetch(ivec2 p) {
    if (any(greaterThanEqual(p, u_size))) return vec2(0.0, -3.402823e38);
    return texelFetch(u_level, p, 0).rg;
}

void main() {
    // The block this texel covers starts at twice its index.
    ivec2 base = ivec2(gl_FragCoord.xy) * 2;
    vec2 a = fetch(base);
    vec2 b = fetch(base + ivec2(1, 0));
    vec2 c = fetch(base + ivec2(0, 1));
    vec2 d = fetch(base + ivec2(1, 1));
    // Sum and maximum of the four.
    o_result = vec4(((a.x + b.x) + c.x) + d.x, max(max(a.y, b.y), max(c.y, d.y)), 0.0, 0.0);
}
