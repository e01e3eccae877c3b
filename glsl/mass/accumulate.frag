#version 330 core
// Accumulation over peels [paper 4, section 3.3]: adds the integrand targets of one peel
// into the running sums (the pass blends with ADD). Pixels the peel did not
// reach (depth still at the cleared 1.0) are discarded, so the peel's colour targets never
// need clearing: what an earlier peel or body left there is never read (a multiply by
// zero would still read it, and 0 * inf is NaN). TARGETS (compiled in) is 3 for the ten
// integrals of eq. 4 and 6, 1 for eq. 4's four.
// Compiled after: #define TARGETS 3
uniform sampler2D u_peel_depth;
uniform sampler2D u_peel0;
layout(location = 0) out vec4 o_sum0;
#if TARGETS == 3
uniform sampler2D u_peel1;
uniform sampler2D u_peel2;
layout(location = 1) out vec4 o_sum1;
layout(location = 2) out vec4 o_sum2;
#endif

// region: accumulate
void main()
{
    // Only pixels this peel reached; their targets are added by the blend.
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (texelFetch(u_peel_depth, pixel, 0).r >= 1.0) discard;
    o_sum0 = texelFetch(u_peel0, pixel, 0);
#if TARGETS == 3
    o_sum1 = texelFetch(u_peel1, pixel, 0);
    o_sum2 = texelFetch(u_peel2, pixel, 0);
#endif
}
// endregion
