#version 430 core
// Paper 2 (Kang & Han 2006), section 2 "Pixel Shader-Based Skinning", the skinning pass as a
// compute shader (then and now).
// Linear blend skinning as a compute pass: invocation (v, c) skins vertex v of character c
// and writes it straight into the storage buffer that the drawing pass reads as its vertex
// data. The formula is pass 1's (glsl/crowd/pass1_skinning.frag); what is gone is the
// render target, the copy through a pixel buffer, and the float-encoded bone indices.

layout(local_size_x = 64) in;

struct BindVertex {
    vec4 position;  // w = 1
    vec4 normal;    // w = 0
    uvec4 bones;    // up to 4 bone indices
    vec4 weights;   // their weights, summing to one
};
struct SkinnedVertex {
    vec4 position;
    vec4 normal;
};

layout(std430, binding = 0) readonly buffer Mesh { BindVertex b_mesh[]; };
// Row r of bone b of character c: b_bone_rows[(c * u_bones + b) * 3 + r] (Fig. 1-(b)'s rows).
layout(std430, binding = 1) readonly buffer BoneRows { vec4 b_bone_rows[]; };
// Vertex v of character c at c * u_vertices + v.
layout(std430, binding = 2) writeonly buffer Skinned { SkinnedVertex b_skinned[]; };

uniform uint u_vertices;    // m
uniform uint u_bones;       // bones per character
uniform uint u_characters;  // n

void main() {
    uint v = gl_GlobalInvocationID.x;
    uint c = gl_GlobalInvocationID.y;
    if (v >= u_vertices || c >= u_characters) return;
    BindVertex bind = b_mesh[v];
    vec3 position = vec3(0.0);
    vec3 normal = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        uint row = (c * u_bones + bind.bones[i]) * 3u;
        vec4 r0 = b_bone_rows[row];
        vec4 r1 = b_bone_rows[row + 1u];
        vec4 r2 = b_bone_rows[row + 2u];
        float w = bind.weights[i];
        position += w * vec3(dot(r0, bind.position), dot(r1, bind.position), dot(r2, bind.position));
        normal += w * vec3(dot(r0.xyz, bind.normal.xyz), dot(r1.xyz, bind.normal.xyz),
                           dot(r2.xyz, bind.normal.xyz));
    }
    b_skinned[c * u_vertices + v] = SkinnedVertex(vec4(position, 1.0), vec4(normalize(normal), 0.0));
}
