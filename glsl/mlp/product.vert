#version 330 core
// Paper 3 (Oh & Jung 2004), section 3 "GPU processing", Fig. 1: the rectangle of the matrix
// product.
// Oh & Jung 2004, section 3 and Fig. 1 (Moravanszky's method): the rectangle that covers the
// output texture W x X. Each vertex carries two texture coordinates, the row of texture W and
// the column of texture X that meet at its corner ("the upper left vertex will have the
// texture coordinates of the first row of texture W and the first column of texture X"), so
// after interpolation every pixel (i, j) holds the ith row of W and the jth column of X. The
// corners come from gl_VertexID and the rectangle uniforms that Pass::draw_rect sets.

uniform vec4 u_rect;     // x0, y0, x1, y1 in pixels of the output
uniform vec2 u_viewport; // output size: L x M pixels

out float v_w_row;       // t of row i of texture W: (i + 1/2) / M at the pixel centre
out float v_x_column;    // s of column j of texture X: (j + 1/2) / L

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 pixel = mix(u_rect.xy, u_rect.zw, corner);
    vec2 st = pixel / u_viewport;
    v_w_row = st.y;    // output row i: output node i
    v_x_column = st.x; // output column j: input vector j
    gl_Position = vec4(st * 2.0 - 1.0, 0.0, 1.0);
}
