// Paper 3 (Oh & Jung 2004), section 3 "GPU processing", eq. 2: the matrix product's first (or
// only) pass.
// Compiled after: #define PERIOD_FP24 0, glsl/mlp/fp24.glsl, glsl/mlp/inner_product.frag
// Oh & Jung 2004, section 3, eq. 2: the pixel shader of the matrix product's first (or only)
// rendering pass. Pixel (i, j) sums the terms k_begin .. k_end - 1 of W_i . X_j
// (glsl/mlp/inner_product.frag); with the whole range 0 .. N it is the product in one pass.

uniform int u_k_begin; // the first input of this pass
uniform int u_k_end;   // one past the last

in float v_w_row;
in float v_x_column;

layout(location = 0) out float o_product; // texture W x X, L wide, M high

// region: product-main
void main() {
    o_product = inner_product(v_w_row, v_x_column, u_k_begin, u_k_end, 0.0);
}
// endregion
