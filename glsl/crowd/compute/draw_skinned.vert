#version 430 core
// Paper 2 (Kang & Han 2006), section 2 "Pixel Shader-Based Skinning", the drawing pass, in the
// compute formulation (then and now).
// The drawing pass of the compute formulation: one instanced draw for all characters, each
// instance fetching its skinned vertices from the storage buffer the compute pass wrote
// (the shared index buffer gives gl_VertexID).

struct SkinnedVertex {
    vec4 position;
    vec4 normal;
};
layout(std430, binding = 2) readonly buffer Skinned { SkinnedVertex b_skinned[]; };

uniform mat4 u_view_projection;
uniform uint u_vertices;

out vec3 v_normal;

void main() {
    // Instance c, vertex v: entry c * vertices + v of the skinned buffer (as the compute pass
    // wrote it).
    SkinnedVertex s = b_skinned[uint(gl_InstanceID) * u_vertices + uint(gl_VertexID)];
    v_normal = s.normal.xyz;
    gl_Position = u_view_projection * vec4(s.position.xyz, 1.0);
}
