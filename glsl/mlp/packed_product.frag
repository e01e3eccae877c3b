#version 330 core
// The packed variant of the matrix product (not in the paper; its faster sibling): four
// values per RGBA texel and a 4 x 4 block of outputs per fragment, written to four render
// targets. Per step of four inputs it makes eight texture fetches for 64 multiply-adds,
// where the faithful pass makes two fetches per multiply-add.
//
// Layouts (k' = k / 4, i' = i / 4, j' = j / 4, c = j mod 4):
//   W:   N/4 wide, M high (M padded to 4):  texel (k', i)  = w_i,4k'..4k'+3
//   X_c: L/4 wide, N/4 high:                texel (j', k') = x_4k'..4k'+3, 4j'+c
//   out o_c, L/4 wide, M/4 high:            texel (j', i') = m_4i'..4i'+3, 4j'+c
// so the outputs are laid out exactly like the next layer's X_c.

uniform sampler2D u_w;
uniform sampler2D u_x0;
uniform sampler2D u_x1;
uniform sampler2D u_x2;
uniform sampler2D u_x3;
uniform int u_n4; // N/4 (N padded with zero weights)

in float v_w_row;    // i' + 1/2 (glsl/mlp/product.vert)
in float v_x_column; // j' + 1/2

layout(location = 0) out vec4 o_0;
layout(location = 1) out vec4 o_1;
layout(location = 2) out vec4 o_2;
layout(location = 3) out vec4 o_3;

void main() {
    int i = 4 * int(v_w_row);
    int j = int(v_x_column);
    vec4 sum0 = vec4(0.0), sum1 = vec4(0.0), sum2 = vec4(0.0), sum3 = vec4(0.0);
    for (int k = 0; k < u_n4; ++k) {
        // columns of w are the rows W_i .. W_i+3 (four inputs each), so x * w = (W_i+q . x)_q
        mat4 w = mat4(texelFetch(u_w, ivec2(k, i), 0), texelFetch(u_w, ivec2(k, i + 1), 0),
                      texelFetch(u_w, ivec2(k, i + 2), 0), texelFetch(u_w, ivec2(k, i + 3), 0));
        sum0 += texelFetch(u_x0, ivec2(j, k), 0) * w;
        sum1 += texelFetch(u_x1, ivec2(j, k), 0) * w;
        sum2 += texelFetch(u_x2, ivec2(j, k), 0) * w;
        sum3 += texelFetch(u_x3, ivec2(j, k), 0) * w;
    }
    o_0 = sum0;
    o_1 = sum1;
    o_2 = sum2;
    o_3 = sum3;
}
