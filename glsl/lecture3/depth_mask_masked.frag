#version 330 core
// Lecture 3, debugging tip "remove `if` with the depth buffer": pass 2, the sum without `if`.
// Compiled after: glsl/lecture3/depth_mask_common.glsl
// The second pass of the depth-masked version: the expensive sum with no `if`. It is drawn at
// depth 0.5 with the depth test GREATER, so only active pixels (depth 0) pass; since the
// shader writes no depth and never discards, the test can run before it (early depth test),
// and masked pixels never run it. (Fragment stage: depth_mask_common.glsl, then this file.)

void main() {
    o_value = expensive(floor(gl_FragCoord.xy));
}
