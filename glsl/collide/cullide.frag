#version 330 core
// Paper 1 (Zhang & Kim 2007), section 7.4.2 "CULLIDE": the method it is compared with, its
// visibility passes.
// CULLIDE's visibility passes only use depth and occlusion queries; no colour is kept.

out vec4 o_colour;

void main() {
    o_colour = vec4(1.0);
}
