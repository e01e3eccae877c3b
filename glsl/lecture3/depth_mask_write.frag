#version 330 core
// Lecture 3, debugging tip "remove `if` with the depth buffer": pass 1, the mask into depth.
// The cheap first pass of the depth-masked version: the mask test, once per pixel, written
// into the depth buffer: depth 0 where the pixel is active, 1 where it is not. Nothing else.

uniform sampler2D u_mask;
uniform float u_fraction;

void main() {
    bool on = texelFetch(u_mask, ivec2(gl_FragCoord.xy), 0).r < u_fraction;
    gl_FragDepth = on ? 0.0 : 1.0;
}
