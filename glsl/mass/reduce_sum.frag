#version 330 core
// Summation reduction [paper 4, section 3.3, Fig. 2] of the three integrand targets at
// once (MRT): each output texel is the sum of a 2x2 block of each input. Texels past the
// input's size count as zero, so any size reduces; tiles of a power-of-two side stay
// aligned (a 32x32 tile is one texel after five passes).
uniform sampler2D source0;
uniform sampler2D source1;
uniform sampler2D source2;
uniform ivec2 source_size;
layout(location = 0) out vec4 sum0;
layout(location = 1) out vec4 sum1;
layout(location = 2) out vec4 sum2;

vec4 block_sum(sampler2D source, ivec2 corner)
{
    vec4 s = vec4(0.0);
    for (int dy = 0; dy < 2; ++dy) {
        for (int dx = 0; dx < 2; ++dx) {
            ivec2 texel = corner + ivec2(dx, dy);
            if (all(lessThan(texel, source_size))) s += texelFetch(source, texel, 0);
        }
    }
    return s;
}

void main()
{
    ivec2 corner = 2 * ivec2(gl_FragCoord.xy);
    sum0 = block_sum(source0, corner);
    sum1 = block_sum(source1, corner);
    sum2 = block_sum(source2, corner);
}
