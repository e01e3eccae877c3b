#version 330 core
// The reduction ladder, fragment rungs 2 and up (lesson 10): the one change is a wider fan-in.
// Each output texel adds the u_fan x u_fan block below it (4x4, 8x8, 16x16), so a pass divides
// the array by u_fan^2: fewer passes (fewer draws, fewer textures written and read again),
// more reads in each fragment.

uniform sampler2D u_level; // the level below: partial sums in red
uniform ivec2 u_size;      // its size in texels
uniform int u_fan;         // the block's side

out float o_sum;

void main() {
    ivec2 base = ivec2(gl_FragCoord.xy) * u_fan;
    // The block, clipped at the level's edge (odd sizes): texels past it add nothing.
    ivec2 end = min(base + ivec2(u_fan), u_size);
    float sum = 0.0;
    for (int y = base.y; y < end.y; ++y) {
        for (int x = base.x; x < end.x; ++x) {
            sum += texelFetch(u_level, ivec2(x, y), 0).r;
        }
    }
    o_sum = sum;
}
