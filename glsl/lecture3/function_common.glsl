#version 330 core
// Lecture 3, "storing a function in a texture": what the exact and the lookup passes share.
// A function in a texture: what the exact and the lookup passes share. Pixel p evaluates
// samples s = p K .. p K + K - 1 of `u_total` (K = u_per_pixel), at x_s = lo + (hi - lo)
// (s + 0.5) / total; with total a power of two below 2^23 every x_s is exact in fp32, so the
// CPU evaluates the very same points. The pass writes the sum of its K values.

uniform int u_function;   // 0: sigmoid, 1: band-limited square wave
uniform float u_lo;
uniform float u_hi;
uniform int u_per_pixel;  // K
uniform float u_total;    // samples in the whole pass
uniform int u_width;      // the target's width in pixels

out float o_sum;

const float TAU = 6.28318530717959;

// Paper 3's sigmoid (eq. 3).
float sigmoid(float x) {
    return 1.0 / (1.0 + exp(-x));
}

// A square wave of period 1 from its first 16 odd harmonics, (4 / pi) sum sin(2 pi n x) / n:
// 16 sines per value, the costly function. The phase is taken modulo 1 before the sine, so
// that fp32 keeps it exact for x_s (see above) instead of rounding an argument up to 195.
float square_wave(float x) {
    float sum = 0.0;
    for (int k = 0; k < 16; ++k) {
        float n = float(2 * k + 1);
        sum += sin(TAU * fract(n * x)) / n;
    }
    return sum * (4.0 / 3.14159265358979);
}

float sample_x(int s) {
    return u_lo + (u_hi - u_lo) * ((float(s) + 0.5) / u_total);
}

int first_sample() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    return (p.y * u_width + p.x) * u_per_pixel;
}
