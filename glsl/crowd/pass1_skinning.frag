#version 330 core
// Paper 2 (Kang & Han 2006), section 2 "Pixel Shader-Based Skinning", pass 1: skinning into a
// render-target texture.
// Pass 1 of Kang & Han 2006 (section 2, Fig. 1-2): linear blend skinning in a pixel shader.
// The render target holds n characters x m vertices: a column is a character, a row a
// vertex index, so every fragment of a row fetches the same vertex texels (cached after
// the first character) and only the bone matrices differ along the row. Rows hold at most
// u_row_characters characters (the vertex buffer's stride limit, see render_to_vbo.rs);
// further characters continue in another block of m rows below.
// Output 0: the skinned position (world coordinates, w = 1); output 1: the skinned normal.

uniform sampler1D u_position;    // m texels: bind-pose position, w = 1
uniform sampler1D u_normal;      // m texels: bind-pose normal, w = 0
uniform sampler1D u_bone_index;  // m texels: up to 4 bone indices, stored as floats
uniform sampler1D u_bone_weight; // m texels: their weights, summing to one
// Fig. 1-(b): each row of the 3x4 bone matrix in its own texture; texel (bone, character).
uniform sampler2D u_row0;
uniform sampler2D u_row1;
uniform sampler2D u_row2;
uniform int u_vertices;       // m
uniform int u_row_characters; // characters per row

layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;

// region: pass1-main
void main() {
    int block = int(gl_FragCoord.y) / u_vertices;
    int v = int(gl_FragCoord.y) - block * u_vertices;            // vertex index
    int c = block * u_row_characters + int(gl_FragCoord.x);      // character
    vec4 p = texelFetch(u_position, v, 0);
    vec3 n = texelFetch(u_normal, v, 0).xyz;
    vec4 index = texelFetch(u_bone_index, v, 0);
    vec4 weight = texelFetch(u_bone_weight, v, 0);
    vec3 position = vec3(0.0);
    vec3 normal = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        ivec2 bone = ivec2(int(index[i]), c);
        vec4 r0 = texelFetch(u_row0, bone, 0);
        vec4 r1 = texelFetch(u_row1, bone, 0);
        vec4 r2 = texelFetch(u_row2, bone, 0);
        position += weight[i] * vec3(dot(r0, p), dot(r1, p), dot(r2, p));
        normal += weight[i] * vec3(dot(r0.xyz, n), dot(r1.xyz, n), dot(r2.xyz, n));
    }
    o_position = vec4(position, 1.0);
    o_normal = vec4(normalize(normal), 0.0);
}
// endregion
