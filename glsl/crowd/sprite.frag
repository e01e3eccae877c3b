#version 330 core
// Paper 2 (Kang & Han 2006), section 3 "Implementation and Result", LOD: the sprites of the far
// field.
// An impostor texel: the captured character where alpha is set, nothing elsewhere.

in vec2 v_uv;

uniform sampler2D u_atlas;

layout(location = 0) out vec4 o_colour;

void main() {
    vec4 c = texture(u_atlas, v_uv);
    if (c.a < 0.5) {
        discard;
    }
    o_colour = vec4(c.rgb, 1.0);
}
