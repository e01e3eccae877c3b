#version 430 core
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
    SkinnedVertex s = b_skinned[uint(gl_InstanceID) * u_vertices + uint(gl_VertexID)];
    v_normal = s.normal.xyz;
    gl_Position = u_view_projection * vec4(s.position.xyz, 1.0);
}
