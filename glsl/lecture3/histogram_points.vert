#version 330 core
// Lecture 3, debugging tip "simplify code with alpha blending": one point per value into its bin.
// Histogram by additive blending: one point per value, from a vertex buffer of values (and
// weights: 1 for a count). The point lands on the pixel of its bin in a bins x 1 target;
// values outside [lo, hi) are sent outside the clip volume. The fragment shader writes the
// weight and the blending unit adds it to what the bin holds.

layout(location = 0) in float a_value;
layout(location = 1) in float a_weight;

uniform float u_lo;
uniform float u_scale; // bins / (hi - lo), computed once in fp32 (the CPU uses the same)
uniform int u_bins;

out float v_weight;

void main() {
    float t = (a_value - u_lo) * u_scale;
    v_weight = a_weight;
    gl_PointSize = 1.0;
    if (!(t >= 0.0 && t < float(u_bins))) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside: clipped
        return;
    }
    gl_Position = vec4((floor(t) + 0.5) / float(u_bins) * 2.0 - 1.0, 0.0, 0.0, 1.0);
}
