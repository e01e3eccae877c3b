#version 330 core
// Paper 3 (Oh & Jung 2004), section 3 "GPU processing", eq. 2: the inner product each pixel of a
// product pass takes.
// Oh & Jung 2004, section 3, eq. 2: the inner product W_i . X_j that every pixel (i, j) of the
// matrix-product passes takes, stepping along row i of texture W and column j of texture X with
// nearest-texel lookups, summed in order k = k_begin .. k_end - 1 onto `sum`. Shared by
// glsl/mlp/product.frag and glsl/mlp/product_accumulate.frag.
// Compiled after: #define PERIOD_FP24 0, glsl/mlp/fp24.glsl

uniform sampler2D u_w; // N wide, M high, R32F: texel (k, i) = w_ik
uniform sampler2D u_x; // L wide, N high, R32F: texel (j, k) = x_kj
uniform int u_n;       // N, the inputs of the layer

// region: inner-product
float inner_product(float w_row, float x_column, int k_begin, int k_end, float sum) {
    float dk = 1.0 / float(u_n);
    for (int k = k_begin; k < k_end; ++k) {
        float s = (float(k) + 0.5) * dk; // the centre of the kth texel along the inner product
        // each fetched value, the product and the running sum are results of the pipeline, so
        // each is rounded in the R300's precision when PERIOD_FP24 is 1 (glsl/mlp/fp24.glsl)
        float w = R24(texture(u_w, vec2(s, w_row)).r);
        float x = R24(texture(u_x, vec2(x_column, s)).r);
        sum = R24(sum + R24(w * x));
    }
    return sum;
}
// endregion
