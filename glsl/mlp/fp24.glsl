// Paper 3 (Oh & Jung 2004), section 4 (the ATI RADEON 9700 PRO of Table 1): the period
// precision of the board's fragment pipeline, 24-bit floats, emulated in fp32.
// Compiled after: #define PERIOD_FP24 0
// The R300 computed every fragment-shader value as a 24-bit float: a sign, a 7-bit exponent
// and a 16-bit stored mantissa. `fp24(x)` rounds an fp32 value to that format; the CPU model of
// the same rounding is src/mlp/fp24.rs, which a test checks this function against bit for bit.
// Choices (the board's own behaviour at the edges is not documented publicly):
// - round to nearest, ties to even, on the 16 kept mantissa bits;
// - exponent range of an IEEE-like format with bias 63: normal values 2^-62 .. (2 - 2^-16) 2^63;
// - no denormals: a result below 2^-62 after rounding is flushed to a zero of its sign;
// - a result above the largest value after rounding is an infinity of its sign; infinities and
//   NaNs pass through unchanged.
// `R24(x)` is what the paper-3 shaders wrap around each intermediate result: fp24(x) when the
// program defines PERIOD_FP24 1 (`--period`), the bare expression when it defines 0, so the
// fp32 passes compile to exactly the code they had before.

#ifndef PERIOD_FP24
#error "define PERIOD_FP24 0 (fp32) or 1 (the R300's 24-bit floats) before glsl/mlp/fp24.glsl"
#endif

// Bit patterns of fp32 values (sign cleared) at the edges of the 24-bit format.
const uint FP24_DROPPED_BITS = 7u;                      // 23 fp32 mantissa bits - 16 kept
const uint FP24_MAX_BITS = (190u << 23) | (0xFFFFu << 7); // (2 - 2^-16) 2^63: exponent 63 + 127
const uint FP24_MIN_BITS = 65u << 23;                     // 2^-62: exponent -62 + 127
const uint FP32_INFINITY_BITS = 0x7F800000u;

float fp24(float x) {
    uint bits = floatBitsToUint(x);
    uint sign = bits & 0x80000000u;
    uint magnitude = bits & 0x7FFFFFFFu;
    // infinities and NaNs are kept as they are
    if (magnitude >= FP32_INFINITY_BITS) {
        return x;
    }
    // round to nearest even: add just under half of the dropped unit, plus one when the kept
    // part is odd, then clear the dropped bits (a carry into the exponent is correct rounding)
    uint odd = (magnitude >> FP24_DROPPED_BITS) & 1u;
    uint half_unit = (1u << (FP24_DROPPED_BITS - 1u)) - 1u + odd;
    uint rounded = (magnitude + half_unit) & ~((1u << FP24_DROPPED_BITS) - 1u);
    // the 7-bit exponent: overflow to infinity, underflow (no denormals) to zero
    if (rounded > FP24_MAX_BITS) {
        return uintBitsToFloat(sign | FP32_INFINITY_BITS);
    }
    if (rounded < FP24_MIN_BITS) {
        return uintBitsToFloat(sign);
    }
    return uintBitsToFloat(sign | rounded);
}

#if PERIOD_FP24
#define R24(x) fp24(x)
#else
#define R24(x) (x)
#endif
