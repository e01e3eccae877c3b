#version 330 core
// Lesson 6, the work pass: the computation without any `if`. Whether it runs at a pixel is
// decided before it, by the depth or the stencil test; an occlusion query around it counts
// the pixels where it ran.

uniform sampler2D u_values;
out vec4 o_result;

void main() {
    // The "expensive" work: here a square root, the same in every pixel where it runs.
    float value = texelFetch(u_values, ivec2(gl_FragCoord.xy), 0).r;
    o_result = vec4(sqrt(value), 0.0, 0.0, 1.0);
}
