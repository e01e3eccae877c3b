#version 330 core
// Oh & Jung 2004, section 3, eq. 2: the pixel shader of the matrix product. Pixel (i, j)
// computes the inner product W_i . X_j, stepping along row i of texture W and column j of
// texture X with nearest-texel lookups, summed in order k = 1..N.

uniform sampler2D u_w; // N wide, M high, R32F: texel (k, i) = w_ik
uniform sampler2D u_x; // L wide, N high, R32F: texel (j, k) = x_kj
uniform int u_n;       // N, the inputs of the layer

in float v_w_row;
in float v_x_column;

layout(location = 0) out float o_product; // texture W x X, L wide, M high

void main() {
    float dk = 1.0 / float(u_n);
    float sum = 0.0;
    for (int k = 0; k < u_n; ++k) {
        float s = (float(k) + 0.5) * dk; // the centre of the kth texel along the inner product
        sum += texture(u_w, vec2(s, v_w_row)).r * texture(u_x, vec2(v_x_column, s)).r;
    }
    o_product = sum;
}
