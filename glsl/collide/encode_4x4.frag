#version 330 core
// Paper 1 (Zhang & Kim 2007), section 5.3.1 "Hierarchical Readback": encoding P_i into P_(i+1).
// Hierarchical readback, encoding (Sec. 5.3.1): texel (x, y) of P_{i+1} holds the mask of
// the non-zero texels of the 4x4 block at (4x, 4y) of P_i, bit 4b + a for texel (4x+a, 4y+b).
// 16 bits is an exact integer in a float, so the mask survives the float render target.

uniform sampler2D u_level; // P_i
out vec4 o_mask;

// region: encode-4x4
void main() {
    ivec2 size = textureSize(u_level, 0);
    ivec2 base = ivec2(gl_FragCoord.xy) * 4;
    int m = 0;
    for (int b = 0; b < 4; b++) {
        for (int a = 0; a < 4; a++) {
            ivec2 p = base + ivec2(a, b);
            if (p.x >= size.x || p.y >= size.y) continue;
            float v = texelFetch(u_level, p, 0).r;
            // A mark that is not a number is passed on as it is, never taken for a CAP:
            // the readback reports it (P0 holds 0 or 1 unless something went wrong).
            if (isnan(v) || isinf(v)) { o_mask = vec4(v); return; }
            if (v != 0.0) m |= 1 << (4 * b + a);
        }
    }
    o_mask = vec4(float(m), 0.0, 0.0, 0.0);
}
// endregion
