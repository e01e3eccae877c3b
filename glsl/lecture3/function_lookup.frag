// Lecture 3, "storing a function in a texture": the function read from the texture.
// Compiled after: glsl/lecture3/function_common.glsl
// The function looked up in a 1D texture with linear filtering, K times per pixel. Texel i
// holds f(lo + i (hi - lo) / (n - 1)); x maps to the coordinate (0.5 + t (n - 1)) / n,
// t = (x - lo) / (hi - lo), so that the table's end points are hit exactly and the filter
// interpolates linearly between neighbouring texel centres. (Fragment stage:
// function_common.glsl, then this file.)

uniform sampler1D u_table;
uniform float u_texels; // n

void main() {
    int s0 = first_sample();
    float sum = 0.0;
    for (int j = 0; j < u_per_pixel; ++j) {
        float t = (sample_x(s0 + j) - u_lo) / (u_hi - u_lo);
        sum += texture(u_table, (0.5 + t * (u_texels - 1.0)) / u_texels).r;
    }
    o_sum = sum;
}
