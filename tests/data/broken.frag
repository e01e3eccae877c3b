#version 330 core
// A shader with a syntax error on line 6, for the error-report test.
out vec4 o_color;

void main() {
    o_color = vec4(1.0) +;
}
