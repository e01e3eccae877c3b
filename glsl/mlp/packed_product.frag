#version 330 core
// Paper 3 (Oh & Jung 2004), section 3 "GPU processing", eq. 2 on the packed variant (ours).
// The packed variant of the matrix product (not in the paper; its faster sibling): four
// values per RGBA texel and a 4 x 4 block of outputs per fragment, written to four render
// targets. Per step of four inputs it makes eight texture lookups for 64 multiply-adds,
// where the faithful pass makes two lookups per multiply-add.
//
// Layouts (k' = k / 4, i' = i / 4, j' = j / 4, c = j mod 4):
//   W:   N/4 wide, M high (M padded to 4):  texel (k', i)  = w_i,4k'..4k'+3
//   X_c: L/4 wide, N/4 high:                texel (j', k') = x_4k'..4k'+3, 4j'+c
//   o_c: L/4 wide, M/4 high:                texel (j', i') = m_4i'..4i'+3, 4j'+c
// so the outputs are laid out exactly like the next layer's X_c.

uniform sampler2D u_w;
uniform sampler2D u_x0;
uniform sampler2D u_x1;
uniform sampler2D u_x2;
uniform sampler2D u_x3;
uniform int u_n4;       // N/4 (N padded with zero weights)
uniform vec2 u_w_texel; // 1 / size of W, for nearest lookups at texel centres
uniform vec2 u_x_texel; // 1 / size of X_c

in vec2 v_texel; // (j' + 1/2, i' + 1/2), glsl/mlp/packed.vert

layout(location = 0) out vec4 o_0;
layout(location = 1) out vec4 o_1;
layout(location = 2) out vec4 o_2;
layout(location = 3) out vec4 o_3;

void main() {
    float w_row = (4.0 * floor(v_texel.y) + 0.5) * u_w_texel.y; // row 4i' of W
    float x_column = v_texel.x * u_x_texel.x;                     // column j' of X_c
    vec4 sum0 = vec4(0.0), sum1 = vec4(0.0), sum2 = vec4(0.0), sum3 = vec4(0.0);
    for (int k = 0; k < u_n4; ++k) {
        float s = (float(k) + 0.5) * u_w_texel.x; // texel k' of a row of W
        float t = (float(k) + 0.5) * u_x_texel.y; // texel k' of a column of X_c
        // columns of w are the rows W_4i' .. W_4i'+3 (four inputs each): x * w = (W_i . x)_i
        mat4 w = mat4(texture(u_w, vec2(s, w_row)),
                      texture(u_w, vec2(s, w_row + u_w_texel.y)),
                      texture(u_w, vec2(s, w_row + 2.0 * u_w_texel.y)),
                      texture(u_w, vec2(s, w_row + 3.0 * u_w_texel.y)));
        sum0 += texture(u_x0, vec2(x_column, t)) * w;
        sum1 += texture(u_x1, vec2(x_column, t)) * w;
        sum2 += texture(u_x2, vec2(x_column, t)) * w;
        sum3 += texture(u_x3, vec2(x_column, t)) * w;
    }
    o_0 = sum0;
    o_1 = sum1;
    o_2 = sum2;
    o_3 = sum3;
}
