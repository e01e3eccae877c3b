#version 330 core
// Paper 2 (Kang & Han 2006), section 3 "Implementation and Result", LOD: the sprites of the far
// field.
// Sprites for the far field (Kang & Han 2006, section 3 LOD; the tutorial's "hundreds of
// thousands with sprite LOD"): a quad standing upright at each character, turned towards
// the eye about the vertical axis, showing the atlas tile of the nearest captured view
// direction (column) and animation phase (row). Corners come from gl_VertexID.

layout(location = 0) in vec4 a_sprite; // bounding-sphere centre (world), radius
layout(location = 1) in vec2 a_tile;   // atlas column and row

uniform mat4 u_view_projection;
uniform vec3 u_eye;
uniform vec2 u_tiles; // columns, rows of the atlas

out vec2 v_uv;

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec3 to_eye = u_eye - a_sprite.xyz;
    to_eye.y = 0.0;
    vec3 right = normalize(cross(vec3(0.0, 1.0, 0.0), to_eye + vec3(1e-6, 0.0, 0.0)));
    vec2 offset = (corner * 2.0 - 1.0) * a_sprite.w;
    vec3 p = a_sprite.xyz + offset.x * right + vec3(0.0, offset.y, 0.0);
    v_uv = (a_tile + corner) / u_tiles;
    gl_Position = u_view_projection * vec4(p, 1.0);
}
