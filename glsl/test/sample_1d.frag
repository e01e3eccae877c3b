#version 330 core
// Samples a 1D texture with its filter at texture coordinate u_x[i] for output pixel i.
uniform sampler1D u_table;
uniform float u_x[8];
out vec4 o_value;

void main() {
    o_value = texture(u_table, u_x[int(gl_FragCoord.x)]);
}
