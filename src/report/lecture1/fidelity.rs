//! What the lecture-1 code does, where, and how far it is a reconstruction
//! (`lecture1-sources.md`: [C] confirmed, [I] inferred, [R] reconstruction).

use crate::report::Fidelity;

pub fn rows() -> Vec<Fidelity> {
    vec![
        Fidelity::new(
            "self-collision between deformable bodies",
            "lecture 1 programme; attributed to Choi, Kim & Kim 2006 (inferred)",
            "src/lecture1/self_collision.rs, glsl/lecture1/diagonal_mask.frag",
            "reconstruction: paper 1's streaming AABB pipeline with one stream against itself; \
             tiles on and above the diagonal only, a stencil pass clearing the diagonal tile's \
             lower half, each leaf against itself sent straight to the triangle test, \
             triangles sharing a (position-welded) vertex skipped. How the lecture's sources \
             did it is not public",
        ),
        Fidelity::new(
            "triangles mapped into textures, tested pair by pair on the GPU",
            "paper 1 on its reference 38 (Sec. 2.2.2, 5.4); Choi, Kim & Kim 2006 (record only)",
            "src/lecture1/pairwise.rs, glsl/lecture1/pair_test.frag, glsl/lecture1/pair_filter.glsl",
            "reconstruction: three RGBA32F texels per triangle, a quad whose fragment (j, i) \
             tests pair (i, j) (the i < j half for one model), tiles of at most 1024 x 1024; \
             box reject, then paper 1's exact test with each sign filtered in fp32 (a pair is \
             dropped only when certainly disjoint) and the CPU's exact predicate on what is \
             reported",
        ),
        Fidelity::new(
            "hierarchical en/decoding readback of the pair results",
            "paper 1 Sec. 5.3 (it says reference 38 introduced it)",
            "src/collide/reduction_gpu.rs",
            "paper 1's 4x4 hierarchical encoding reused as it is; an occlusion query per tile \
             skips the readback of tiles without pairs (ours)",
        ),
        Fidelity::new(
            "pairwise tests as a compute pass (then and now)",
            "not in the sources",
            "src/lecture1/pairwise_compute.rs, glsl/lecture1/compute/pair_test.comp",
            "ours: the same filter over all pairs in one OpenGL 4.3 dispatch, pairs appended \
             to a list by an atomic counter (no pair texture, tiles or hierarchical readback)",
        ),
        Fidelity::new(
            "a scene that folds onto itself",
            "lecture 1 (self-collision of deformable bodies)",
            "src/lecture1/knotted_tube.rs",
            "ours: a tube around a trefoil knot whose radius swells until its strands press \
             through each other; paper 1's wavy and pulsating deformations on a flattened torus",
        ),
    ]
}
