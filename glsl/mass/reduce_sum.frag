#version 330 core
// Summation reduction [paper 4, section 3.3, Fig. 2] of the integrand targets at once
// (MRT): each output texel is the sum of a FAN_IN x FAN_IN block of each input. Both sizes
// are compiled in (src/mass/reduce.rs makes one program per fan-in): TARGETS is 3 for the
// ten integrals of eq. 4 and 6, 1 for eq. 4's four (a buoyancy step); a constant FAN_IN
// lets the compiler unroll the block loops.
// Texels past the input's size count as zero, so any size reduces; tiles of a
// power-of-two side stay aligned (a 32x32 tile is one texel after an 8x8 and a 4x4 pass).
// Compiled after: #define TARGETS 3, #define FAN_IN 8
uniform sampler2D u_source0;
layout(location = 0) out vec4 o_sum0;
#if TARGETS == 3
uniform sampler2D u_source1;
uniform sampler2D u_source2;
layout(location = 1) out vec4 o_sum1;
layout(location = 2) out vec4 o_sum2;
#endif
uniform ivec2 u_source_size;

// The sum of the block whose lower-left texel is `corner`; texels outside the input are
// skipped (tested only for a block that reaches past the input's edge).
vec4 block_sum(sampler2D source, ivec2 corner)
{
    vec4 s = vec4(0.0);
    if (all(lessThanEqual(corner + ivec2(FAN_IN), u_source_size))) {
        for (int dy = 0; dy < FAN_IN; ++dy) {
            for (int dx = 0; dx < FAN_IN; ++dx) {
                s += texelFetch(source, corner + ivec2(dx, dy), 0);
            }
        }
        return s;
    }
    for (int dy = 0; dy < FAN_IN; ++dy) {
        for (int dx = 0; dx < FAN_IN; ++dx) {
            ivec2 texel = corner + ivec2(dx, dy);
            if (all(lessThan(texel, u_source_size))) s += texelFetch(source, texel, 0);
        }
    }
    return s;
}

// region: reduce-sum
void main()
{
    // Output texel (x, y) covers input texels FAN_IN (x, y) .. FAN_IN (x, y) + FAN_IN - 1.
    ivec2 corner = FAN_IN * ivec2(gl_FragCoord.xy);
    // The integrand targets, reduced in the same pass (one per render target).
    o_sum0 = block_sum(u_source0, corner);
#if TARGETS == 3
    o_sum1 = block_sum(u_source1, corner);
    o_sum2 = block_sum(u_source2, corner);
#endif
}
// endregion
