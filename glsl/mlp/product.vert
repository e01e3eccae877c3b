#version 330 core
// Oh & Jung 2004, section 3 and Fig. 1 (Moravanszky's method): the rectangle that covers the
// output texture W x X. Each vertex carries two texture coordinates, the row of texture W and
// the column of texture X that meet at its corner, so that after interpolation every pixel
// (i, j) holds "the ith row of W and the jth column of X". The corners come from gl_VertexID
// and the rectangle uniforms that Pass::draw_rect sets (as in glsl/gl/rect.vert).

uniform vec4 u_rect;     // x0, y0, x1, y1 in pixels of the output
uniform vec2 u_viewport; // output size in pixels

out float v_w_row;       // row i of texture W, in texels (i + 1/2 at the pixel centre)
out float v_x_column;    // column j of texture X, in texels (j + 1/2)

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 pixel = mix(u_rect.xy, u_rect.zw, corner);
    v_w_row = pixel.y;    // output row i: output node i
    v_x_column = pixel.x; // output column j: input vector j
    gl_Position = vec4(pixel / u_viewport * 2.0 - 1.0, 0.0, 1.0);
}
