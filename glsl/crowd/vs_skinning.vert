#version 330 core
// Paper 2 (Kang & Han 2006), section 3 "Implementation and Result", Table 1 "VS": the vertex-
// shader skinning it is compared with.
// Compiled after: #define BONES 24, #define BATCH 2
// The baseline Kang & Han 2006 compare with (Table 1, "VS"): linear blend skinning in the
// vertex shader with the bone matrices in uniforms (constant registers). The uniform space
// holds BATCH characters' matrices at a time (BATCH and BONES are defined by the program
// that includes this file), so one instanced draw skins BATCH characters and
// gl_InstanceID picks the character.

layout(location = 0) in vec4 a_position;    // bind pose, w = 1
layout(location = 1) in vec4 a_normal;      // bind pose, w = 0
layout(location = 2) in vec4 a_bone_index;  // up to 4 bone indices, as floats
layout(location = 3) in vec4 a_bone_weight; // their weights

// Three rows per bone matrix: [3 * (character * BONES + bone) + row].
uniform vec4 u_bone_rows[3 * BONES * BATCH];
uniform mat4 u_view_projection;

out vec3 v_normal;

void main() {
    int base = gl_InstanceID * BONES;
    vec3 position = vec3(0.0);
    vec3 normal = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        int row = 3 * (base + int(a_bone_index[i]));
        vec4 r0 = u_bone_rows[row];
        vec4 r1 = u_bone_rows[row + 1];
        vec4 r2 = u_bone_rows[row + 2];
        position += a_bone_weight[i] * vec3(dot(r0, a_position), dot(r1, a_position), dot(r2, a_position));
        normal += a_bone_weight[i] *
            vec3(dot(r0.xyz, a_normal.xyz), dot(r1.xyz, a_normal.xyz), dot(r2.xyz, a_normal.xyz));
    }
    v_normal = normalize(normal);
    gl_Position = u_view_projection * vec4(position, 1.0);
}
