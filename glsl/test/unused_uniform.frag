#version 330 core
// Test of a building block: uniforms the compiler removes (Program::set).
// One colour, and a uniform that is declared but never read: compilers remove it (its
// location is -1), some drivers sooner than others. Setting it must still be allowed.
uniform vec4 u_colour;
uniform float u_never_read;
out vec4 o_colour;

void main() {
    o_colour = u_colour;
}
