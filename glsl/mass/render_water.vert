#version 330 core
// The still water of the buoyancy frames: one large quad at z = water_level.
uniform mat4 view_projection;
uniform float water_level;
uniform float extent;
void main()
{
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    gl_Position = view_projection * vec4(corner * extent, water_level, 1.0);
}
