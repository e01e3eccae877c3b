#version 330 core
// Reads texel (x, y) of mipmap level u_level with texelFetch (an image pyramid's lookups).
uniform sampler2D u_texture;
uniform int u_level;
out vec4 o_value;

void main() {
    o_value = vec4(texelFetch(u_texture, ivec2(gl_FragCoord.xy), u_level).r);
}
