//! The GL features of paper 4, where this code uses them, and what differs.

use super::paths;
use crate::report::Fidelity;

pub fn rows() -> Vec<Fidelity> {
    vec![
        Fidelity::new(
            "mass properties: the integrands of eq. 4 and 6 in a fragment shader, three render \
             targets (MRT)",
            "GLSL listing, section 3.1",
            "cg_ports/mass_integrands.frag",
            "GLSL 1.10 ported to 330: gl_FragData becomes an output array; the listing's lost \
             closing brace restored; a prelude renames its main() so the peel test runs first",
        )
        .covers(&[paths::MASS_LISTING]),
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
        )
        .covers(&[paths::PEEL]),
        Fidelity::new(
            "summation by ping-pong buffer reduction",
            "section 3.3, Fig. 2",
            "src/mass/reduce.rs, src/gl/reduce.rs",
            "the integrand targets (three for mass properties, one for buoyancy) are reduced \
             together (MRT), one texel per body tile; each pass sums blocks of up to 8x8 texels \
             (the paper: 'two or more values'), so a 32x32 tile takes 2 passes instead of 5",
        )
        .covers(&[paths::REDUCE]),
        Fidelity::new(
            "n + 2 passes: fluid depth, peels below it, fluid patch where pass 1 faced down",
            "section 5.2, Fig. 7-8",
            "src/mass/peel.rs, glsl/mass/peel_main.frag, glsl/mass/water_patch.frag",
            "the stencil bit is written by two-sided stencil (back faces, n_z < 0, write 1) \
             rather than by the fragment shader; the water is a plane, not a height field",
        )
        .covers(&[paths::BUOYANCY_PASSES]),
        Fidelity::new(
            "buoyancy's pass 1 to n and the fluid patch: the four integrands of eq. 4, one \
             render target",
            "section 5.2, pass 1: sgn(n_z) xz, sgn(n_z) yz, sgn(n_z) z^2 and sgn(n_z) z",
            "glsl/mass/integrands_eq4.frag, src/mass/integrands.rs (Integrands::Eq4)",
            "none in what is evaluated: the listing's first target alone, (rx, ry, rz, V), \
             written to one render target instead of three; the other six integrals (eq. 6) \
             are not needed for the volume and the centre of buoyancy",
        )
        .covers(&[paths::BUOYANCY_PASSES]),
        Fidelity::new(
            "buoyant force and viscous drag",
            "section 5.1, eq. 7; section 5.3: drag at the centre of buoyancy 'proportional to \
             the submerged volume and the square of the body velocity', its constant not given",
            "src/mass/buoyancy/forces.rs",
            "the drag's constant is chosen: F = -c rho_w V_sub |v| v with c = 1 per metre, \
             rho_w = 1000 kg/m^3, g = 9.81 m/s^2; 'the body velocity' is read as the velocity of \
             the centre of mass (not the velocity of the centre of buoyancy, which would add \
             the spin's part); by default that drag is all, as in the paper",
        )
        .covers(&[paths::FORCES]),
        Fidelity::new(
            "extra damping (`buoyancy --extra-damping`, off by default)",
            "not in the paper",
            "src/mass/buoyancy/forces.rs (Water::with_extra_damping)",
            "ours, off unless asked and never in the report: a linear drag 2/s and a rotational \
             damping 1/s scaled by the submerged fraction, standing in for the energy real \
             bodies lose to the waves they make (still water has none), so bodies settle in \
             seconds instead of rocking on under the quadratic drag alone",
        ),
        Fidelity::new(
            "rigid-body integration",
            "section 5: the simulation 'runs on the CPU'; the integrator and the step are not \
             given",
            "src/mass/buoyancy/rigid_body.rs",
            "chosen: semi-implicit Euler (velocities from the wrench, with Euler's gyroscopic \
             term, then the pose from the new velocities; symplectic in translation, so \
             gravity and buoyancy alone keep the energy bounded), dt = 1/60 s (one step per \
             frame; `buoyancy --dt` changes it, up to 0.1 s)",
        )
        .covers(&[paths::INTEGRATOR]),
        Fidelity::new(
            "the 50-body scene",
            "section 5.3, Fig. 9: ten spheres, boxes, tori, teapots and Stanford bunnies; \
             boxes denser than water sink; densities, sizes and placement not given",
            "src/mass/buoyancy/scene.rs",
            "chosen: each body about 1 m across (the box 1.2 x 0.8 x 0.5 m); densities 200 to \
             900 kg/m^3 for spheres, tori, teapots and bunnies, 250 to 850 for seven boxes and \
             1300, 1600 and 2000 for the three that sink; a grid 3 m apart, each dropped at \
             rest with its centre 0.3, 0.4 or 0.5 m above the water, in assorted fixed \
             orientations",
        )
        .covers(&[paths::SCENE]),
        Fidelity::new(
            "the scene's teapot",
            "section 5.3 and Table 1: Newell's teapot",
            "src/mass/buoyancy/scene.rs (closed_teapot)",
            "a closed teapot: Newell's lid, rim, body and Crow's bottom as one surface of \
             revolution, without handle and spout. Newell's surface is open (the lid floats \
             over the rim, spout and handle pierce the body), so its peels and analytic mass \
             properties disagree (6.4% in volume); Table 1's objects keep Newell's teapot",
        )
        .covers(&[paths::SCENE]),
        Fidelity::new(
            "Mirtich's analytic algorithm as the baseline",
            "section 4 [13]",
            "src/mass/analytic.rs",
            "computed in f64 on the CPU; the paper's test meshes are not published, so the \
             objects are this project's generators and the Stanford bunny (next row)",
        )
        .covers(&[paths::ANALYTIC]),
        Fidelity::new(
            "Table 1's test objects at the paper's vertex and face counts",
            "Table 1: cube 8/12, sphere 422/840, teapot 821/1628, torus 1024/1922, knot \
             1440/2880, bunny 2557/5110, pipe 4626/9252",
            "src/mass/models.rs, src/mesh/generate/, src/mesh/retessellate.rs",
            "the meshes are ours (the paper's are not published); cube, sphere, torus and knot \
             are generated at the paper's counts; the shipped Stanford bunny (1839/3674) and \
             the generated pipe (4624/9248) are refined to 2557/5110 and 4626/9252 by \
             longest-edge midpoint splits, which keep the surface and its closedness (the \
             buoyancy scene's bunnies are the same 5110-face mesh); the teapot has the paper's \
             821 vertices but 1560 faces, 68 (4%) short: Newell's 32 patches at 5 x 5 \
             segments give 1600 triangles, of which the 40 that collapse at the lid's knob \
             and the bottom's centre are dropped, and no even grid gives 1628 with 821 \
             vertices; its surface is open, so its analytic values are unreliable anyway",
        ),
        Fidelity::new(
            "the inertia tensor",
            "eq. 2 (the tensor: y^2 + z^2 on the diagonal, products off it, signs negative); \
             eq. 5 as printed puts I_xx, I_yy, I_zz of eq. 6, the second moments such as the \
             integral of x^2, on its diagonal",
            "src/mass/assemble.rs",
            "eq. 2 is followed, not eq. 5 as printed: the diagonal is the sum of the other two \
             second moments (I = rho (tr(S) 1 - S)), and the tensor is taken about the centre \
             of mass (S shifted from the origin by the parallel-axis rule), since eq. 5 names \
             no point; the second moments of eq. 6 themselves are what the listing's \
             integrands and Fig. 4's I_xx, I_yy, I_zz compare",
        ),
        Fidelity::new(
            "the sign of each fragment's integrands",
            "eq. 4 and 6: sgn(n_z) of the surface normal",
            "glsl/mass/peel_main.frag, src/gl/facing.rs",
            "sgn(n_z) as the listing computes it, except for slivers the rasterizer turned \
             over (their vertices snapped to the sub-pixel grid): a fragment whose drawn \
             facing (gl_FrontFacing, checked against the rasterizer's winding on each \
             context) disagrees with its n_z is counted with the facing it was drawn with, so \
             the fold such a sliver makes with its neighbours adds nothing, as the layers of \
             the snapped closed surface alternate in and out at every pixel; on a context \
             whose gl_FrontFacing tells nothing, n_z alone decides",
        )
        .covers(&[paths::PEEL]),
        Fidelity::new(
            "mass properties and buoyancy as compute passes (then and now)",
            "not in the paper",
            "src/mass/compute.rs, src/mass/buoyancy/compute.rs",
            "ours, OpenGL 4.3: the same integrals by the divergence theorem over each \
             triangle's signed tetrahedron, summed by a shared-memory reduction (no framing, \
             resolution or peels); for buoyancy every body's triangles clipped against the \
             water plane; beside the classic path in the 'then and now' tables",
        )
        .covers(&[paths::COMPUTE]),
    ]
}
