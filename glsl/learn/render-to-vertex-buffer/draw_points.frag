#version 330 core
// Lesson 9, pass 2: write each point's height.

in float v_height;
out vec4 o_height;

void main() {
    o_height = vec4(v_height, 0.0, 0.0, 1.0);
}
