#version 330 core
// Summation reduction [paper 4, section 3.3, Fig. 2] of the three integrand targets at
// once (MRT): each output texel is the sum of a u_fan_in x u_fan_in block of each input.
// Texels past the input's size count as zero, so any size reduces; tiles of a
// power-of-two side stay aligned (a 32x32 tile is one texel after an 8x8 and a 4x4 pass).
uniform sampler2D u_source0;
uniform sampler2D u_source1;
uniform sampler2D u_source2;
uniform ivec2 u_source_size;
uniform int u_fan_in;
layout(location = 0) out vec4 o_sum0;
layout(location = 1) out vec4 o_sum1;
layout(location = 2) out vec4 o_sum2;

// The sum of the block whose lower-left texel is `corner`, texels outside the input skipped.
vec4 block_sum(sampler2D source, ivec2 corner)
{
    vec4 s = vec4(0.0);
    for (int dy = 0; dy < u_fan_in; ++dy) {
        for (int dx = 0; dx < u_fan_in; ++dx) {
            ivec2 texel = corner + ivec2(dx, dy);
            if (all(lessThan(texel, u_source_size))) s += texelFetch(source, texel, 0);
        }
    }
    return s;
}

void main()
{
    // Output texel (x, y) covers input texels fan_in (x, y) .. fan_in (x, y) + fan_in - 1.
    ivec2 corner = u_fan_in * ivec2(gl_FragCoord.xy);
    // The three integrand targets, reduced in the same pass (one per render target).
    o_sum0 = block_sum(u_source0, corner);
    o_sum1 = block_sum(u_source1, corner);
    o_sum2 = block_sum(u_source2, corner);
}
