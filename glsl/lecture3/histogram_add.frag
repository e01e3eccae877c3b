#version 330 core
// Lecture 3, debugging tip "simplify code with alpha blending": the histogram by additive
// blending.
// The fragment of one value: its weight, added to its bin by the blending unit.
in float v_weight;
out float o_weight;

void main() {
    o_weight = v_weight;
}
