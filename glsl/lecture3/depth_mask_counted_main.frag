// Lecture 3, debugging tip "remove `if` with the depth buffer": the counting pass's main.
// Compiled after: glsl/lecture3/depth_mask_counted.frag, glsl/lecture3/depth_mask_common.glsl
// The body of the counting variant (see depth_mask_counted.frag): one count per run, then
// the same expensive sum as depth_mask_masked.frag.

void main() {
    atomicCounterIncrement(u_runs);
    o_value = expensive(floor(gl_FragCoord.xy));
}
