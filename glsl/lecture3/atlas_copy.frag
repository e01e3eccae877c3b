#version 330 core
// Lecture 3, "the image pyramid and pyramidal displacement mapping" (Oh, Ki & Lee, VRST 2006): the
// pyramid atlas, one level copied into its place.
// Copies one mipmap level of a pyramid into its place in the pyramid atlas (the viewport is
// that place). The level is the same for the whole pass.

uniform sampler2D u_pyramid;
uniform int u_level;
uniform ivec2 u_offset; // where the level starts in the atlas

out vec4 o_value;

void main() {
    o_value = texelFetch(u_pyramid, ivec2(gl_FragCoord.xy) - u_offset, u_level);
}
