// Depth peeling [paper 4, section 3.2] around the integrands of section 3.1, with the
// fluid-surface test of section 5.2. Compiled after cg_ports/mass_integrands.frag and the
// GL layer's peel snippet (glsl/gl/peel.glsl: peel_discard() against T_d(k-1)).
// Compiled after: glsl/mass/peel_prelude.frag, cg_ports/mass_integrands.frag, glsl/gl/peel.glsl
#undef main

// T_dw: depth of the fluid surface (cleared to 0, "no water", for whole bodies).
uniform sampler2D u_water_depth;

// Pass 1's faces-down mark is the paper's stencil bit: two-sided stencil writes 1 where
// the kept fragment is a back face (n_z < 0, seen from above) and 0 where it is a front
// face (src/mass/peel.rs), so this shader writes no mark of its own.

void main()
{
    // Peel away everything up to the previous layer.
    peel_discard();
    // Passes 1..n of 5.2: fragments above the fluid surface are discarded.
    if (gl_FragCoord.z < texelFetch(u_water_depth, ivec2(gl_FragCoord.xy), 0).r) discard;
    integrands();
}
