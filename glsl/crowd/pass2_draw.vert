#version 330 core
// Paper 2 (Kang & Han 2006), section 2 "Pixel Shader-Based Skinning", pass 2: drawing from the
// vertex buffer pass 1 filled.
// Pass 2 of Kang & Han 2006: draw a character from the vertex buffer that pass 1 filled
// (render-to-VBO). The vertices are already skinned and in world coordinates.

layout(location = 0) in vec4 a_position;
layout(location = 1) in vec4 a_normal;

uniform mat4 u_view_projection;

out vec3 v_normal;

// region: pass2-main
void main() {
    v_normal = a_normal.xyz;
    gl_Position = u_view_projection * vec4(a_position.xyz, 1.0);
}
// endregion
