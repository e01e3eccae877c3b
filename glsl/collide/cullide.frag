#version 330 core
// CULLIDE's visibility passes only use depth and occlusion queries; no colour is kept.

out vec4 color;

void main() {
    color = vec4(1.0);
}
