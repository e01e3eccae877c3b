#version 330 core
// Test of a building block: vertex texture fetch (paper 4's water pass reads its tiles in
// the vertex shader; the GeForce 7800 GTX read only 1-, 3- and 4-component 32-bit float
// textures there).
// Point i lands on pixel i of a one-row target, carrying texel i of u_values as its colour.
uniform sampler2D u_values;
uniform float u_width;
out vec4 v_value;

void main() {
    v_value = texelFetch(u_values, ivec2(gl_VertexID, 0), 0);
    // The centre of pixel gl_VertexID in clip space.
    float x = (float(gl_VertexID) + 0.5) / u_width * 2.0 - 1.0;
    gl_Position = vec4(x, 0.0, 0.0, 1.0);
    gl_PointSize = 1.0;
}
