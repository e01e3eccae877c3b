#version 330 core
// Test of a building block: 1D textures and their filter (paper 1's AABB textures, lecture 3's
// function texture).
// Samples a 1D texture with its filter at texture coordinate u_x[i] for output pixel i.
uniform sampler1D u_table;
uniform float u_x[8];
out vec4 o_value;

void main() {
    o_value = texture(u_table, u_x[int(gl_FragCoord.x)]);
}
