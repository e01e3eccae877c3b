#version 330 core
// Marks the pixels a peeled layer covers (to count layers per pixel).

out vec4 o_covered;

void main() {
    peel_discard();
    o_covered = vec4(1.0);
}
