#version 330 core
// The fragment of one value: its weight, added to its bin by the blending unit.
in float v_weight;
out float o_weight;

void main() {
    o_weight = v_weight;
}
