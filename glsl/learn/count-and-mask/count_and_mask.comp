#version 430 core
// Lesson 6, the compute counterpart: in a compute shader the condition is an `if` again and
// the count an atomic counter (what replaced the occlusion query and the stencil mask; see
// src/collide/compute_overlap.rs). One invocation per element.

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Values { float b_values[]; };
layout(std430, binding = 1) readonly buffer Valid { float b_valid[]; };
layout(std430, binding = 2) writeonly buffer Result { float b_result[]; };
layout(binding = 0, offset = 0) uniform atomic_uint c_above; // values above the threshold
layout(binding = 0, offset = 4) uniform atomic_uint c_ran;   // elements where the work ran

uniform uint u_count;      // elements
uniform float u_threshold;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    float value = b_values[i];
    // The count of the occlusion-query pass.
    if (value > u_threshold) atomicCounterIncrement(c_above);
    // The work where both masks are open (real slot, value above), -1 elsewhere.
    bool run = b_valid[i] > 0.5 && value > u_threshold;
    if (run) atomicCounterIncrement(c_ran);
    b_result[i] = run ? sqrt(value) : -1.0;
}
