#version 330 core
// Paper 3 (Oh & Jung 2004), section 3 "GPU processing", eq. 3: the rectangle of the bias and
// sigmoid pass.
// Oh & Jung 2004, section 3: the full-screen rectangle of the bias + sigmoid pass. The
// coordinate into texture W x X follows the position ("the upper left vertex has the texture
// coordinate (0,0) ... the upper right vertex (1,0)"); the bias is the same along a row, so
// the bias texture is one-dimensional and its coordinate is the vertical position.

uniform vec4 u_rect;     // x0, y0, x1, y1 in pixels (set by Pass::draw_rect)
uniform vec2 u_viewport; // output size: L x M pixels

out vec2 v_product; // (s, t) in texture W x X
out float v_bias;   // s in the bias texture

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 pixel = mix(u_rect.xy, u_rect.zw, corner);
    vec2 st = pixel / u_viewport;
    v_product = st;
    v_bias = st.y;
    gl_Position = vec4(st * 2.0 - 1.0, 0.0, 1.0);
}
