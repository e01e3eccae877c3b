#version 420 core
// Test of a building block: atomic counters bound for draws (the count of fragment-shader runs
// that lecture 3's depth-mask claim is judged on).
// A test shader for the GL layer's atomic counters bound for draws: each run adds one to the
// counter at binding 0, after the depth test (asked for early, as a shader with a side effect
// must), and writes white.

layout(early_fragment_tests) in;
layout(binding = 0, offset = 0) uniform atomic_uint u_runs;

out vec4 o_colour;

void main() {
    atomicCounterIncrement(u_runs);
    o_colour = vec4(1.0);
}
