#version 330 core
// Paper 4 (Kim, Kim, Ko & Terzopoulos 2006), section 5.3 "Simulation example" (Fig. 9-10): the
// water and the force arrows in the frames.
// One colour (the water, with alpha; the force arrows).
uniform vec4 u_colour;
out vec4 o_colour;
void main()
{
    o_colour = u_colour;
}
