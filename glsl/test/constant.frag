#version 330 core
// Test of a building block: one colour everywhere (the GL layer's tests).
// Writes one colour everywhere it is drawn.
uniform vec4 u_colour;
out vec4 o_colour;

void main() {
    o_colour = u_colour;
}
