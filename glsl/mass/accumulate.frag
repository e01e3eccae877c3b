#version 330 core
// Accumulation over peels [paper 4, section 3.3]: adds the integrand targets of one peel
// into the running sums (the pass blends with ADD).
uniform sampler2D peel0;
uniform sampler2D peel1;
uniform sampler2D peel2;
layout(location = 0) out vec4 sum0;
layout(location = 1) out vec4 sum1;
layout(location = 2) out vec4 sum2;

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    sum0 = texelFetch(peel0, pixel, 0);
    sum1 = texelFetch(peel1, pixel, 0);
    sum2 = texelFetch(peel2, pixel, 0);
}
