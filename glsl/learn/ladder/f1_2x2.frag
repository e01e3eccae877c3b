#version 330 core
// The reduction ladder, fragment rung 1 (lesson 10): the 2x2 pass of lesson 3, one channel.
// Each output texel adds the 2x2 block below it, so a pass quarters the array and n values
// take about log4 n passes, each a full draw with a texture between passes.

uniform sampler2D u_level; // the level below: partial sums in red
uniform ivec2 u_size;      // its size in texels

out float o_sum;

// A texel of the level below; past its edge (odd sizes) the sum's identity, 0.
float fetch(ivec2 p) {
    if (any(greaterThanEqual(p, u_size))) return 0.0;
    return texelFetch(u_level, p, 0).r;
}

void main() {
    ivec2 base = ivec2(gl_FragCoord.xy) * 2;
    o_sum = (fetch(base) + fetch(base + ivec2(1, 0)))
          + (fetch(base + ivec2(0, 1)) + fetch(base + ivec2(1, 1)));
}
