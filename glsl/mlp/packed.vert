#version 330 core
// Paper 3 (Oh & Jung 2004), section 3 "GPU processing", the packed variant (ours): its rectangle.
// The rectangle of the packed passes (glsl/mlp/packed_product.frag): it covers the L/4 x M/4
// output, and each pixel receives its texel position (j', i') = (input-vector block, output
// block row).

uniform vec4 u_rect;     // x0, y0, x1, y1 in pixels (set by Pass::draw_rect)
uniform vec2 u_viewport;

out vec2 v_texel; // (j' + 1/2, i' + 1/2)

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 pixel = mix(u_rect.xy, u_rect.zw, corner);
    v_texel = pixel;
    gl_Position = vec4(pixel / u_viewport * 2.0 - 1.0, 0.0, 1.0);
}
