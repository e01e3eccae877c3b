#version 330 core
// Paper 3 (Oh & Jung 2004), section 3 "GPU processing", eq. 3 on the packed variant (ours).
// Eq. 3 on the packed layout (glsl/mlp/packed_product.frag): four products per texel in four
// render targets, the bias four per texel along the rows.

uniform sampler2D u_product0;
uniform sampler2D u_product1;
uniform sampler2D u_product2;
uniform sampler2D u_product3;
uniform sampler1D u_bias; // M/4 texels, RGBA32F: texel i' = b_4i'..4i'+3
uniform bool u_sigmoid;
uniform vec2 u_viewport;  // L/4 x M/4 (set by Pass::draw_rect)

in vec2 v_texel; // (j' + 1/2, i' + 1/2), glsl/mlp/packed.vert

layout(location = 0) out vec4 o_0;
layout(location = 1) out vec4 o_1;
layout(location = 2) out vec4 o_2;
layout(location = 3) out vec4 o_3;

vec4 activate(vec4 m) {
    return u_sigmoid ? 1.0 / (1.0 + exp(-m)) : m;
}

void main() {
    vec2 st = v_texel / u_viewport;
    vec4 b = texture(u_bias, st.y);
    o_0 = activate(texture(u_product0, st) + b);
    o_1 = activate(texture(u_product1, st) + b);
    o_2 = activate(texture(u_product2, st) + b);
    o_3 = activate(texture(u_product3, st) + b);
}
