#version 330 core
// Paper 4, section 5.2, pass 1 (and passes 2..n, and the fluid patch): "the integrands in
// equation (4)", sgn(n_z) xz, sgn(n_z) yz, sgn(n_z) z^2 and sgn(n_z) z, and no others: the
// submerged volume and its centre of buoyancy are all a buoyancy step needs. The section
// 3.1 listing's first render target alone (cg_ports/mass_integrands.frag writes this same
// value into FragData[0]), so one render target instead of three.
// In the pipeline glsl/mass/peel_prelude.frag comes first and renames main() to
// integrands(), as it does for the listing.
layout(location = 0) out vec4 FragData[1];

// homogeneous coordinate of a point on the surface
in vec4 p;
// z component of the surface normal
in float n_z;

void main(void)
{
    // (rx, ry, rz, V): sgn(n_z) z times (x, y, z, 1), the listing's first line.
    float c = sign(n_z) * p.z;
    FragData[0] = c * p;
}
