// Lecture 3, debugging tip "remove `if` with the depth buffer": the work both versions share.
// The expensive per-pixel work of the "remove `if` with the depth buffer" tip, shared by
// the branching shader and the depth-masked one: a sum of u_iterations sines,
// f(x, y) = sum_k sin(2 pi fract(k u) + v) / k, u = (x + 0.5) / width, v = 2 pi (y + 0.5) /
// height. With power-of-two sizes k u is exact in fp32, so the CPU evaluates the same terms.
// No #version line: each shader that includes this file gives its own (330, or 420 for the
// variant that counts its runs).

uniform int u_iterations;
uniform vec2 u_size; // the target, pixels

out float o_value;

const float TAU = 6.28318530717959;

float expensive(vec2 pixel) {
    float u = (pixel.x + 0.5) / u_size.x;
    float v = TAU * (pixel.y + 0.5) / u_size.y;
    float sum = 0.0;
    for (int k = 1; k <= u_iterations; ++k) {
        sum += sin(TAU * fract(float(k) * u) + v) / float(k);
    }
    return sum;
}
