// The body of the counting variant (see depth_mask_counted.frag): one count per run, then
// the same expensive sum as depth_mask_masked.frag.

void main() {
    atomicCounterIncrement(u_runs);
    o_value = expensive(floor(gl_FragCoord.xy));
}
