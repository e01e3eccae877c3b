#version 330 core
// Test of a building block: integer textures (lecture 3's random numbers).
// An integer pass: each texel of an RGBA32UI texture becomes its xor with its own position
// and a rotation of its words.
uniform usampler2D u_state;
out uvec4 o_state;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uvec4 s = texelFetch(u_state, p, 0);
    o_state = s.yzwx ^ uvec4(uint(p.x), uint(p.y), 0xdeadbeefu, s.x << 3);
}
