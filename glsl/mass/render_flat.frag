#version 330 core
// One colour (the water, with alpha; the force arrows).
uniform vec4 color;
out vec4 frag;
void main()
{
    frag = color;
}
