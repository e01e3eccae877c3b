#version 330 core
// Paper 1 (Zhang & Kim 2007), section 5.3.1 "Hierarchical Readback", the reduced readback:
// encoding P0 into P1'.
// Reduced readback, encoding (Sec. 5.3.1): texel (x, y) of P1' holds the 64 bits of the 8x8
// block at (8x, 8y) of P0, 16 per channel: channel c has rows 2c and 2c+1 of the block, bit
// 8 (b - 2c) + a for texel (8x+a, 8y+b). Each channel stays an exact integer in a float.

uniform sampler2D u_level; // P0
out vec4 o_mask;

void main() {
    ivec2 size = textureSize(u_level, 0);
    ivec2 base = ivec2(gl_FragCoord.xy) * 8;
    ivec4 m = ivec4(0);
    for (int b = 0; b < 8; b++) {
        int row = 0;
        for (int a = 0; a < 8; a++) {
            ivec2 p = base + ivec2(a, b);
            if (p.x >= size.x || p.y >= size.y) continue;
            float v = texelFetch(u_level, p, 0).r;
            // A mark that is not a number is passed on as it is, never taken for a CAP:
            // the readback reports it (P0 holds 0 or 1 unless something went wrong).
            if (isnan(v) || isinf(v)) { o_mask = vec4(v); return; }
            if (v != 0.0) row |= 1 << a;
        }
        m[b / 2] |= row << (8 * (b % 2));
    }
    o_mask = vec4(m);
}
