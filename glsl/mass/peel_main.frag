// Depth peeling [paper 4, section 3.2] around the integrands of section 3.1, with the
// fluid-surface test of section 5.2. Compiled after cg_ports/mass_integrands.frag and the
// GL layer's peel snippet (glsl/gl/peel.glsl: peel_discard() against T_d(k-1)).
#undef main

// T_dw: depth of the fluid surface (cleared to 0, "no water", for whole bodies).
uniform sampler2D u_water_depth;

// The paper's stencil bit of pass 1, as a colour: 1 where the surface faces down.
layout(location = 3) out float o_faces_down;

void main()
{
    // Peel away everything up to the previous layer.
    peel_discard();
    // Passes 1..n of 5.2: fragments above the fluid surface are discarded.
    if (gl_FragCoord.z < texelFetch(u_water_depth, ivec2(gl_FragCoord.xy), 0).r) discard;
    integrands();
    o_faces_down = n_z < 0.0 ? 1.0 : 0.0;
}
