#version 330 core
// Oh & Jung 2004, section 3: the full-screen rectangle of the bias + sigmoid pass. The
// coordinate into texture W x X follows the position; the bias is the same along a row, so
// the bias texture is one-dimensional and its coordinate is the vertical position.

uniform vec4 u_rect;     // x0, y0, x1, y1 in pixels (set by Pass::draw_rect)
uniform vec2 u_viewport;

out vec2 v_product; // texel (j, i) of texture W x X (+ 1/2 at the pixel centre)
out float v_bias;   // texel i of the bias texture

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 pixel = mix(u_rect.xy, u_rect.zw, corner);
    v_product = pixel;
    v_bias = pixel.y;
    gl_Position = vec4(pixel / u_viewport * 2.0 - 1.0, 0.0, 1.0);
}
