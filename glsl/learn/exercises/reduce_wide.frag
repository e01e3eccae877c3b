#version 330 core
// Lesson 3, a wider fan-in (exercise): each output texel combines the u_fan x u_fan block below
// it, so each pass divides both sides by u_fan and n x n values take ceil(log_fan n) passes:
// fewer passes, more reads per fragment. Red carries the sum, green the maximum.

uniform sampler2D u_level; // the level below: red = partial sums, green = partial maxima
uniform ivec2 u_size;      // its size in texels
uniform int u_fan;         // the block's side

out vec4 o_result;

void main() {
    ivec2 base = ivec2(gl_FragCoord.xy) * u_fan;
    // Start from the identities: 0 for the sum, the lowest float for the maximum.
    float sum = 0.0;
    float largest = -3.402823e38;
    // EXERCISE: this reads only the 2x2 corner of each block; make it read the whole block
    // (4x4 in this lesson).
    for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) {
            ivec2 p = base + ivec2(i, j);
            if (any(greaterThanEqual(p, u_size))) continue;
            vec2 v = texelFetch(u_level, p, 0).rg;
            sum += v.x;
            largest = max(largest, v.y);
        }
    }
    o_result = vec4(sum, largest, 0.0, 0.0);
}
