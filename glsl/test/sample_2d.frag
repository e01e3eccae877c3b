#version 330 core
// Test of a building block: float textures read with their filter (the period GPU's limits:
// the GeForce 7800 GTX filtered 16-bit float textures only).
// Samples a 2D texture with its filter at texture coordinate u_uv[i] for output pixel i.
uniform sampler2D u_source;
uniform vec2 u_uv[8];
out vec4 o_value;

void main() {
    o_value = texture(u_source, u_uv[int(gl_FragCoord.x)]);
}
