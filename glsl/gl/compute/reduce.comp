#version 430 core
// Building block: reduction in work-group shared memory, the compute formulation of
// glsl/gl/reduce.frag (paper 4's compute path; the bridge to lecture 5).
// One pass of a reduction in work-group shared memory: each group of 256 invocations loads
// 512 values of one segment (two each), combines them in a tree of halving strides in shared
// memory, and writes one partial result. Segment y's n values give ceil(n / 512) partials;
// passes repeat until one value per segment remains. Values past a segment's end contribute
// the operation's identity.

layout(local_size_x = 256) in;

layout(std430, binding = 0) readonly buffer Input { vec4 b_input[]; };
layout(std430, binding = 1) writeonly buffer Output { vec4 b_output[]; };

uniform uint u_count;    // values per segment in the input
uniform int u_op;        // 0: sum, 1: min, 2: max
uniform bool u_nonzero;  // first pass of OR / count: each component becomes (x != 0)
// A pass too large for one dispatch (the renderer's work-group limit per axis) is split into
// several: this dispatch's first partial and first segment, and the pass's number of
// partials per segment.
uniform uint u_first_group;
uniform uint u_first_segment;
uniform uint u_groups;

shared vec4 s_values[256];

vec4 identity() {
    if (u_op == 0) return vec4(0.0);
    if (u_op == 1) return vec4(3.402823e38);
    return vec4(-3.402823e38);
}

vec4 combine(vec4 a, vec4 b) {
    if (u_op == 0) return a + b;
    if (u_op == 1) return min(a, b);
    return max(a, b);
}

vec4 fetch(uint segment, uint i) {
    if (i >= u_count) return identity();
    vec4 v = b_input[segment * u_count + i];
    return u_nonzero ? vec4(notEqual(v, vec4(0.0))) : v;
}

void main() {
    uint local = gl_LocalInvocationID.x;
    uint group = u_first_group + gl_WorkGroupID.x;
    uint segment = u_first_segment + gl_WorkGroupID.y;
    uint first = group * 512u + local;
    s_values[local] = combine(fetch(segment, first), fetch(segment, first + 256u));
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1) {
        if (local < stride) {
            s_values[local] = combine(s_values[local], s_values[local + stride]);
        }
        barrier();
    }
    if (local == 0u) {
        b_output[segment * u_groups + group] = s_values[0];
    }
}
