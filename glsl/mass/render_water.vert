#version 330 core
// Paper 4 (Kim, Kim, Ko & Terzopoulos 2006), section 5.3 "Simulation example" (Fig. 9): the still
// water.
// The still water of the buoyancy frames: one large quad at z = u_water_level.
uniform mat4 u_view_projection;
uniform float u_water_level;
uniform float u_extent;
void main()
{
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    gl_Position = u_view_projection * vec4(corner * u_extent, u_water_level, 1.0);
}
