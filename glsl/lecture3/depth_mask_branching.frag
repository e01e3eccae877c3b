#version 330 core
// Lecture 3, debugging tip "remove `if` with the depth buffer": the version with the `if`.
// Compiled after: glsl/lecture3/depth_mask_common.glsl
// The branching shader: every pixel runs it and tests its mask value; the expensive sum runs
// only where the test passes, 0 elsewhere. (Fragment stage: depth_mask_common.glsl, then
// this file.)

uniform sampler2D u_mask;
uniform float u_fraction; // pixels with mask < fraction are active

void main() {
    vec2 pixel = floor(gl_FragCoord.xy);
    if (texelFetch(u_mask, ivec2(pixel), 0).r < u_fraction) {
        o_value = expensive(pixel);
    } else {
        o_value = 0.0;
    }
}
