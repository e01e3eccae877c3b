#version 330 core
// Oh & Jung 2004, section 3, eq. 2: the pixel shader of the matrix product. Pixel (i, j)
// computes the inner product W_i . X_j of row i of texture W and column j of texture X,
// summed in order k = 1..N.

uniform sampler2D u_w; // N wide, M high, R32F: texel (k, i) = w_ik
uniform sampler2D u_x; // L wide, N high, R32F: texel (j, k) = x_kj
uniform int u_n;       // N, the inputs of the layer

in float v_w_row;
in float v_x_column;

layout(location = 0) out float o_product; // texture W x X, L wide, M high

void main() {
    int i = int(v_w_row);
    int j = int(v_x_column);
    float sum = 0.0;
    for (int k = 0; k < u_n; ++k) {
        sum += texelFetch(u_w, ivec2(k, i), 0).r * texelFetch(u_x, ivec2(j, k), 0).r;
    }
    o_product = sum;
}
