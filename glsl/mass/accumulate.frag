#version 330 core
// Accumulation over peels [paper 4, section 3.3]: adds the integrand targets of one peel
// into the running sums (the pass blends with ADD). On the first peel it also keeps the
// faces-down mark that the water patch of section 5.2 needs. Pixels the peel did not
// reach (depth still at the cleared 1.0) are discarded, so the peel's colour targets never
// need clearing: what an earlier peel or body left there is never read (a multiply by
// zero would still read it, and 0 * inf is NaN).
uniform sampler2D peel_depth;
uniform sampler2D peel0;
uniform sampler2D peel1;
uniform sampler2D peel2;
uniform sampler2D peel_faces_down;
uniform bool first_peel;
layout(location = 0) out vec4 sum0;
layout(location = 1) out vec4 sum1;
layout(location = 2) out vec4 sum2;
layout(location = 3) out float first_peel_faces_down;

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (texelFetch(peel_depth, pixel, 0).r >= 1.0) discard;
    sum0 = texelFetch(peel0, pixel, 0);
    sum1 = texelFetch(peel1, pixel, 0);
    sum2 = texelFetch(peel2, pixel, 0);
    first_peel_faces_down = first_peel ? texelFetch(peel_faces_down, pixel, 0).r : 0.0;
}
