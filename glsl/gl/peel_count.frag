#version 330 core
// Building block: depth peeling (glsl/gl/peel.glsl, paper 4 section 3.2), counting the layers
// per pixel (the selftest's check of peeling).
// Compiled after: glsl/gl/peel.glsl
// Marks the pixels a peeled layer covers (to count layers per pixel).

out vec4 o_covered;

void main() {
    peel_discard();
    o_covered = vec4(1.0);
}
