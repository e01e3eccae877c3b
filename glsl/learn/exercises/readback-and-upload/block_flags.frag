#version 330 core
// Lesson 8, a small reduced readback (paper 1, section 5.3.1: the hierarchical readback
// encodes P0 into small levels so the CPU reads only the blocks that hold something). One
// output texel per BLOCK x BLOCK block of the input: 1 if any texel of the block is not
// zero, else 0. The CPU reads these flags, then only the flagged blocks.

uniform sampler2D u_data; // the full array (RGBA32F)
uniform int u_block;      // block side in texels
out vec4 o_flag;

void main() {
    ivec2 corner = ivec2(gl_FragCoord.xy) * u_block;
    float any_set = 0.0;
    // EXERCISE: visit every texel of the block (u_block x u_block from `corner`). As written
    // only the corner texel is looked at, so most blocks that hold data are never read.
    vec4 v = texelFetch(u_data, corner, 0);
    if (any(notEqual(v, vec4(0.0)))) any_set = 1.0;
    o_flag = vec4(any_set, 0.0, 0.0, 1.0);
}
