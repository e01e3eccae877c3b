#version 330 core
// Paper 3 (Oh & Jung 2004), section 4 (the ATI RADEON 9700 PRO of Table 1): a pass that rounds
// every texel to the board's 24-bit floats, so that a test can hold the shaders' rounding
// against the CPU model of it (src/mlp/fp24.rs).
// Compiled after: #define PERIOD_FP24 1, glsl/mlp/fp24.glsl

uniform sampler2D u_values; // R32F: the fp32 values to round

layout(location = 0) out float o_rounded; // R32F, the same size: each texel's fp24(value)

void main() {
    // one fragment per texel; texelFetch reads the stored fp32 bits as they are
    o_rounded = fp24(texelFetch(u_values, ivec2(gl_FragCoord.xy), 0).r);
}
