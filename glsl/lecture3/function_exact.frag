// Lecture 3, "storing a function in a texture": the function computed in the shader.
// Compiled after: glsl/lecture3/function_common.glsl
// The function computed in the shader, K times per pixel. (Fragment stage:
// function_common.glsl, then this file.)

void main() {
    int s0 = first_sample();
    float sum = 0.0;
    for (int j = 0; j < u_per_pixel; ++j) {
        float x = sample_x(s0 + j);
        sum += u_function == 0 ? sigmoid(x) : square_wave(x);
    }
    o_sum = sum;
}
