#version 330 core
// Lesson 6, an `if` removed by the depth test (lecture 3's tip, as in
// src/lecture3/depth_mask.rs): this cheap pass writes the condition into the depth buffer.
// The work pass is then drawn at depth 0.5 with the test LESS, so it runs only where this
// pass left 1.0 (far: open) and never where it left 0.0 (near: closed).

uniform sampler2D u_values;
uniform float u_threshold; // the work runs where the value is above it

void main() {
    float value = texelFetch(u_values, ivec2(gl_FragCoord.xy), 0).r;
    // Open (1.0) where the condition holds, closed (0.0) where it does not.
    gl_FragDepth = value > u_threshold ? 1.0 : 0.0;
}
