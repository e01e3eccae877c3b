// Paper 4 (Kim, Kim, Ko & Terzopoulos 2006), section 3.1 "Shader implementation": the printed
// fragment shader.
// Port of the fragment shader listed in section 3.1 of Kim, Kim, Ko & Terzopoulos,
// "Fast GPU computation of the mass properties of a general shape and its application to
// buoyancy simulation", The Visual Computer 22(8), 2006: the integrands of eq. 4 and 6.
// Ported from GLSL 1.10 to GLSL 330 line for line: `varying` becomes `in`, and the
// built-in gl_FragData[i] (gone from the core profile) becomes the output array FragData[i]
// bound to render targets 0, 1, 2. The listing's closing brace, lost in print, is restored.
// Compiled on its own it is a complete shader; in the pipeline glsl/mass/peel_prelude.frag
// comes first and renames this main() to integrands(), so that the peel test of section 3.2
// (glsl/mass/peel_main.frag) can run before it.
#version 330 core
layout(location = 0) out vec4 FragData[3];

// homogeneous coordinate of a point on the surface
in vec4 p;
// z component of the surface normal
in float n_z;
void main(void)
{
 float c = sign(n_z) * p.z;
 // (rx, ry, rz, V)
 FragData[0] = c * p;
 // (Ixx, Ixy, Ixz, .)
 FragData[1] = p.x * FragData[0];
 // (Iyy, Iyz, Izz, .)
 FragData[2] = c * vec4(p.y * p.y, p.y * p.z, p.z * p.z, 0);
}
