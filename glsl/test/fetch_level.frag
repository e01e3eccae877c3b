#version 330 core
// Test of a building block: texelFetch from a mipmap level (lecture 3's pyramids).
// Reads texel (x, y) of mipmap level u_level with texelFetch (an image pyramid's lookups).
uniform sampler2D u_texture;
uniform int u_level;
out vec4 o_value;

void main() {
    o_value = vec4(texelFetch(u_texture, ivec2(gl_FragCoord.xy), u_level).r);
}
