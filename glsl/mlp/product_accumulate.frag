// Paper 3 (Oh & Jung 2004), section 3 "GPU processing", eq. 2: the product's later passes.
// Compiled after: #define PERIOD_FP24 0, glsl/mlp/fp24.glsl, glsl/mlp/inner_product.frag
// Oh & Jung 2004, section 3: "the number of rendering passes required for matrix
// multiplication depends on the capability of the GPU". Every pass after the first reads the
// running sum of the passes before it from their render target (ping-pong: a 2004 board could
// not blend float targets) and carries on with the next inputs k_begin .. k_end - 1, so the
// terms are summed in the same order as in one pass.

uniform sampler2D u_partial; // W x X over the inputs of the earlier passes, L wide, M high
uniform int u_k_begin;
uniform int u_k_end;

in float v_w_row;
in float v_x_column;

layout(location = 0) out float o_product;

void main() {
    float sum = texelFetch(u_partial, ivec2(gl_FragCoord.xy), 0).r;
    o_product = inner_product(v_w_row, v_x_column, u_k_begin, u_k_end, sum);
}
