#version 330 core
// Paper 3 (Oh & Jung 2004), section 3 "GPU processing", eq. 3: the bias and sigmoid pass.
// Oh & Jung 2004, section 3, eq. 3: "the pixel shader adds two textures and performs a
// sigmoid operation": r_ij = 1 / (1 + e^-(m_ij + b_i)). An identity layer skips the sigmoid.
// Compiled after: #define PERIOD_FP24 0, glsl/mlp/fp24.glsl
// Each intermediate result is wrapped in R24: rounded to the R300's 24-bit floats when the
// program defines PERIOD_FP24 1, unchanged (the fp32 pass) when it defines 0.

uniform sampler2D u_product; // texture W x X: L wide, M high, R32F
uniform sampler1D u_bias;    // M texels, R32F: texel i = b_i
uniform bool u_sigmoid;      // false: identity activation

in vec2 v_product;
in float v_bias;

layout(location = 0) out float o_result; // R, L wide, M high: the next layer's texture X

// region: bias-sigmoid
void main() {
    float m = R24(R24(texture(u_product, v_product).r) + R24(texture(u_bias, v_bias).r));
    o_result = u_sigmoid ? R24(1.0 / R24(1.0 + R24(exp(-m)))) : m;
}
// endregion
