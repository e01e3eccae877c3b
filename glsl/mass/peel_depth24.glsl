// Depth peeling against a 24-bit depth buffer [paper 4, section 3.2, on its own GPU]: the
// GeForce 7800 GTX had no float depth, so T_d(k) was a DEPTH24_STENCIL8 texture, a whole
// number of steps of 2^-24 of the depth range. Same interface as glsl/gl/peel.glsl, which
// it replaces under the period profile (src/mass/peel_depth.rs): call peel_discard() first.
//
// The fragment is compared with the previous layer at the buffer's own 24 bits, as a shadow
// compare with a one-step bias did: it is kept only when its depth, counted in whole steps
// (rounded down), lies beyond the step T_d(k-1) holds. Compared unquantised (as the fp32
// snippet does), a fragment whose depth the buffer rounded down would be behind its own
// stored depth and be peeled again; rounding down here keeps it out whether the driver
// rounds to nearest or truncates. Two surfaces in the same step cannot be told apart:
// the nearer is peeled and the other is lost with it.

uniform sampler2D u_peel_depth; // T_d(k-1): 24-bit depth read as s / (2^24 - 1)
uniform int u_peel_layer;       // 0 for the first layer, which peels nothing

// Steps of a 24-bit depth buffer over [0, 1].
const float DEPTH_STEPS = 16777215.0;

void peel_discard() {
    if (u_peel_layer == 0) return;
    // The stored step s, exactly: s / (2^24 - 1) scaled back lands within a fraction of s
    // (on s itself above 2^23, where adding 0.5 first would round to the even neighbour).
    float stored = round(texelFetch(u_peel_depth, ivec2(gl_FragCoord.xy), 0).r * DEPTH_STEPS);
    // This fragment's step, rounded down: never beyond the step the buffer stored for it.
    float step = floor(gl_FragCoord.z * DEPTH_STEPS);
    if (step <= stored) discard;
}
