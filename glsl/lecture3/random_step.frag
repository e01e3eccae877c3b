#version 330 core
// Lecture 3, "generating random numbers into a texture": one step of every texel's generator.
// Random numbers into a texture: each texel holds the state of its own generator (four
// 32-bit words in an RGBA32UI texel) and one pass advances every generator by one step,
// reading the state texture and writing the other (ping-pong), with the number drawn written
// into a float texture beside it. The generator is the hybrid Tausworthe of Howes & Thomas
// (GPU Gems 3, ch. 37, 2007): three Tausworthe steps and an LCG, xored; it uses nothing but
// 32-bit integer operations, so the CPU reproduces it bit for bit.

uniform usampler2D u_state;

layout(location = 0) out uvec4 o_state;
layout(location = 1) out float o_value;

uint taus_step(uint z, int s1, int s2, int s3, uint m) {
    uint b = ((z << s1) ^ z) >> s2;
    return ((z & m) << s3) ^ b;
}

void main() {
    uvec4 z = texelFetch(u_state, ivec2(gl_FragCoord.xy), 0);
    z.x = taus_step(z.x, 13, 19, 12, 4294967294u);
    z.y = taus_step(z.y, 2, 25, 4, 4294967288u);
    z.z = taus_step(z.z, 3, 11, 17, 4294967280u);
    z.w = 1664525u * z.w + 1013904223u;
    o_state = z;
    // The top 24 bits as a float in [0, 1): exact in fp32.
    o_value = float((z.x ^ z.y ^ z.z ^ z.w) >> 8) * (1.0 / 16777216.0);
}
