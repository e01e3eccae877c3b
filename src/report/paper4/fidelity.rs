//! The GL features of paper 4, where this code uses them, and what differs.

use crate::report::Fidelity;

pub fn rows() -> Vec<Fidelity> {
    vec![
        Fidelity::new(
            "integrands of eq. 4 and 6 in a fragment shader, three render targets (MRT)",
            "GLSL listing, section 3.1",
            "cg_ports/mass_integrands.frag",
            "GLSL 1.10 ported to 330: gl_FragData becomes an output array; the listing's lost \
             closing brace restored; a prelude renames its main() so the peel test runs first",
        ),
        Fidelity::new(
            "depth peeling until every surface fragment is found",
            "section 3.2",
            "src/mass/peel.rs, src/mass/peel_end.rs",
            "the paper does not say how the end is found; here an occlusion query per body \
             counts each peel, and from pass 2 on the stencil counts the fragments met at \
             each pixel, so a body with no pixel that met two is not peeled again (no empty \
             last peel; pass 1's stencil holds the faces-down bit, so a body that drew in \
             pass 1 is always peeled once more); by default each peel is added into running \
             sums by blending (peel memory and passes do not grow with n); the paper's order, \
             keeping the n layers and reducing each, is the mode `--order keep-layers` and \
             agrees to fp32 rounding (table 'Order of peels and sums'); peeling stops at \
             `--max-peels` (64) with a warning; the bodies of a batch are tiles of one target",
        ),
        Fidelity::new(
            "summation by ping-pong buffer reduction",
            "section 3.3, Fig. 2",
            "src/mass/reduce.rs, src/gl/reduce.rs",
            "the three integrand targets are reduced together (MRT), one texel per body tile; \
             each pass sums blocks of up to 8x8 texels (the paper: 'two or more values'), so a \
             32x32 tile takes 2 passes instead of 5",
        ),
        Fidelity::new(
            "n + 2 passes: fluid depth, peels below it, fluid patch where pass 1 faced down",
            "section 5.2, Fig. 7-8",
            "src/mass/peel.rs, glsl/mass/peel_main.frag, glsl/mass/water_patch.frag",
            "the stencil bit is written by two-sided stencil (back faces, n_z < 0, write 1) \
             rather than by the fragment shader; the water is a plane, not a height field",
        ),
        Fidelity::new(
            "Mirtich's analytic algorithm as the baseline",
            "section 4 [13]",
            "src/mass/analytic.rs",
            "computed in f64 on the CPU; the paper's test meshes are not published, so the \
             objects are this project's generators and the Stanford bunny",
        ),
    ]
}
