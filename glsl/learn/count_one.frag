#version 330 core
// Lesson 5: each point's fragment is a count of one; additive blending sums the counts of
// every point that lands on the same bin (without blending, the last one would overwrite).

out float o_count;

void main() {
    o_count = 1.0;
}
