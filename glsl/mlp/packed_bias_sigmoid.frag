#version 330 core
// Eq. 3 on the packed layout (glsl/mlp/packed_product.frag): four products per texel in four
// render targets, the bias four per texel along the rows.

uniform sampler2D u_product0;
uniform sampler2D u_product1;
uniform sampler2D u_product2;
uniform sampler2D u_product3;
uniform sampler1D u_bias; // M/4 texels, RGBA32F: texel i' = b_4i'..4i'+3
uniform bool u_sigmoid;

in vec2 v_product; // texel (j', i') (glsl/mlp/bias_sigmoid.vert)
in float v_bias;   // texel i'

layout(location = 0) out vec4 o_0;
layout(location = 1) out vec4 o_1;
layout(location = 2) out vec4 o_2;
layout(location = 3) out vec4 o_3;

vec4 activate(vec4 m) {
    return u_sigmoid ? 1.0 / (1.0 + exp(-m)) : m;
}

void main() {
    ivec2 texel = ivec2(v_product);
    vec4 b = texelFetch(u_bias, int(v_bias), 0);
    o_0 = activate(texelFetch(u_product0, texel, 0) + b);
    o_1 = activate(texelFetch(u_product1, texel, 0) + b);
    o_2 = activate(texelFetch(u_product2, texel, 0) + b);
    o_3 = activate(texelFetch(u_product3, texel, 0) + b);
}
