#version 330 core
// Paper 4 (Kim, Kim, Ko & Terzopoulos 2006), section 5.3 "Simulation example" (Fig. 10): the force
// arrows.
// The force arrows of Fig. 10: line segments in world coordinates.
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_projection;
void main()
{
    gl_Position = u_view_projection * vec4(a_position, 1.0);
}
