// Depth peeling [paper 4, section 3.2] around the integrands of section 3.1, with the
// fluid-surface test of section 5.2. Compiled after cg_ports/mass_integrands.frag and the
// GL layer's peel snippet (glsl/gl/peel.glsl: peel_discard() against T_d(k-1)).
// Compiled after: glsl/mass/peel_prelude.frag, cg_ports/mass_integrands.frag, glsl/gl/peel.glsl
#undef main

// T_dw: depth of the fluid surface (cleared to 0, "no water", for whole bodies).
uniform sampler2D u_water_depth;
// What gl_FrontFacing means on this renderer (src/gl/facing.rs): +1 the rasterizer's facing,
// -1 its opposite, 0 nothing usable (then every fragment counts by its n_z alone).
uniform float u_facing_sign;

// Pass 1's faces-down mark is the paper's stencil bit: two-sided stencil writes 1 where
// the kept fragment is a back face (n_z < 0, seen from above) and 0 where it is a front
// face (src/mass/peel.rs), so this shader writes no mark of its own.

// region: peel-main
void main()
{
    // Peel away everything up to the previous layer.
    peel_discard();
    // Passes 1..n of 5.2: fragments above the fluid surface are discarded.
    if (gl_FragCoord.z < texelFetch(u_water_depth, ivec2(gl_FragCoord.xy), 0).r) discard;
    integrands();
    // A sliver the rasterizer turned over (its vertices snapped to the sub-pixel grid) faces
    // the other way than its n_z, and overlaps its neighbours there: counted with the facing
    // it was drawn with, the fold it makes with them adds up to nothing, as in the snapped
    // closed surface every pixel's layers alternate in and out. (The integrands are linear in
    // sign(n_z).)
    // gl_FrontFacing is read through ?: only: softpipe's compares unequal to a true bool.
    float drawn_facing = gl_FrontFacing ? u_facing_sign : -u_facing_sign;
    if (drawn_facing * n_z < 0.0) {
        for (int i = 0; i < FragData.length(); ++i) FragData[i] = -FragData[i];
    }
}
// endregion
