#version 330 core
// Lesson 0, a texture is an array: copy texel (i, j) of a R32F texture into the target, one
// fragment per texel. The target's format decides what is kept: the value is rounded to it
// when the fragment is written (RGBA8: clamped to [0, 1], 256 steps; R16F: 11 significant
// bits; R32F: all 24).

uniform sampler2D u_input;

out vec4 o_value;

void main() {
    // The fragment's pixel is the array index: gl_FragCoord is its centre (i + 0.5, j + 0.5).
    ivec2 index = ivec2(gl_FragCoord.xy);
    // texelFetch reads one texel by integer index: no filtering, no coordinates.
    float value = texelFetch(u_input, index, 0).r;
    // Every channel gets the value, so an RGBA8 target keeps it in red as R16F and R32F do.
    o_value = vec4(value);
}
