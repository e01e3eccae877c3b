#version 330 core
// CULLIDE's visibility passes only use depth and occlusion queries; no colour is kept.

out vec4 o_colour;

void main() {
    o_colour = vec4(1.0);
}
