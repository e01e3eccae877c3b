#version 330 core
// Paper 4, section 3.1: the listing's interface (the three render targets, the surface point
// p and the sign of n_z) with its arithmetic taken out, every target written with a
// constant. Not a step of the paper and no integrals: the floor against which the `mass`
// command times the same peeling passes, so that its output can say what the integrands'
// arithmetic costs on the renderer and what the passes themselves cost (src/cli/mass.rs).
layout(location = 0) out vec4 FragData[3];

in vec4 p;
in float n_z;

void main(void)
{
 FragData[0] = vec4(1.0);
 FragData[1] = vec4(1.0);
 FragData[2] = vec4(1.0);
}
