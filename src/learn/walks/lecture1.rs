//! Lecture 1 walked: the pairwise triangle test with the triangles in textures (our
//! reconstruction of Choi, Kim & Kim 2006, [`crate::lecture1::pairwise`]) on two small tori.

use super::{buffer_png, Check, Shot, Step, Walk};
use crate::collide::{triangles_intersect, Predicate};
use crate::gl::Context;
use crate::lecture1::pairwise::{PairwiseTester, TriangleTexture};
use crate::mesh::{self, Mesh};
use glam::Vec3;
use std::path::Path;

pub const WALK: Walk = Walk {
    id: "lecture1",
    title: "Lecture 1 walked: pairwise triangle tests with the triangles in textures",
    source: "The tutorial's lecture 1 (Young J. Kim), proximity queries on the GPU; the pairwise \
             test of Choi, Kim & Kim, \"Rapid pairwise intersection tests using programmable \
             GPUs\", The Visual Computer 22(2), 2006, as this project reconstructs it (only the \
             paper's record and paper 1's account of it are public: see lecture1-sources.md, \
             section 3).",
    run_is: "two tori of about 120 triangles whose tubes cross: a quad of about 120 x 120 triangle pairs",
    steps: STEPS,
    run,
};

const STEPS: &[Step] = &[
    Step {
        pass: "triangles into textures",
        section: "lecture1-sources.md, section 3 (reconstructed)",
        step: "each model's triangles mapped into a texture, three texels a triangle",
        reads: "the two meshes, on the CPU",
        writes: "one RGBA32F texture per model: x, y, z of a corner and its vertex id",
        code: &[("src/lecture1/pairwise.rs", "triangle-texture")],
        lesson: "texture-is-array",
    },
    Step {
        pass: "the pair quad",
        section: "lecture1-sources.md, section 3 (reconstructed)",
        step: "a quad whose fragment (j, i) tests triangle i of A against triangle j of B, \
               counted by an occlusion query",
        reads: "the two triangle textures",
        writes: "P0: 1 where the pair may intersect (a box test, then the exact test with each \
                 sign filtered in fp32, discarding only pairs certainly apart)",
        code: &[
            ("src/lecture1/pairwise.rs", "pair-test"),
            ("glsl/lecture1/pair_test.frag", "pair-test-main"),
        ],
        lesson: "count-and-mask",
    },
    Step {
        pass: "hierarchical readback",
        section: "paper 1, Sec. 5.3.1 (the same encoding)",
        step: "P0 encoded into P1, P2, P3 (a 4x4 mask per texel); the CPU descends from P3",
        reads: "P0, then each level the one below",
        writes: "P1, P2, P3",
        code: &[
            ("src/collide/reduction_gpu.rs", "encode-hierarchical"),
            ("glsl/collide/encode_4x4.frag", "encode-4x4"),
        ],
        lesson: "readback-and-upload",
    },
    Step {
        pass: "exact confirmation (CPU)",
        section: "lecture1-sources.md, section 3 (reconstructed)",
        step: "every reported pair confirmed with the exact predicate",
        reads: "the pairs read back",
        writes: "the intersecting triangle pairs, on the CPU",
        code: &[("src/lecture1/pairwise.rs", "confirm")],
        lesson: "readback-and-upload",
    },
];

/// The two models: tori of 120 triangles, one turned a quarter and moved
/// half its radius, so that the tubes cross.
pub fn models() -> (Mesh, Mesh) {
    let a = mesh::torus_with_triangles(1.0, 0.3, 120);
    let turn = glam::Affine3A::from_rotation_x(std::f32::consts::FRAC_PI_2);
    let b = a.transformed(&turn).translated(Vec3::new(0.5, 0.0, 0.0));
    (a, b)
}

fn run(ctx: &Context, dir: &Path) -> anyhow::Result<Vec<Shot>> {
    let (a, b) = models();
    let mut shots = Vec::new();

    let texture = TriangleTexture::new(ctx, &a)?;
    let texels = texture.texture.download_f32()?;
    let dims = (texture.texture.width(), texture.texture.height());
    shots.push(Shot {
        pictures: vec![buffer_png(
            dir,
            "triangles_A.png",
            "triangles of A",
            &texels,
            4,
            &["x", "y", "z", "vertex id"],
            dims,
        )?],
        key: format!(
            "{} triangles of A in one row, three texels each (corners 0, 1, 2), stretched \
             upward to be seen; blue below zero, red to yellow above",
            texture.count
        ),
        check: None,
    });

    let tester = PairwiseTester::new(ctx, 4096)?;
    let tile = tester.first_tile(&a, Some(&b))?;
    let p0 = tile.target.p0.download_f32()?;
    let p0_dims = (tile.target.p0.width(), tile.target.p0.height());
    // Every pair the exact test finds must be marked (the GPU's filter is conservative).
    let width = p0_dims.0 as usize;
    let mut exact = Vec::new();
    for i in 0..a.triangles.len() {
        for j in 0..b.triangles.len() {
            if triangles_intersect(&a.triangle(i), &b.triangle(j), Predicate::Exact) {
                exact.push((i, j));
            }
        }
    }
    let missed = exact
        .iter()
        .filter(|&&(i, j)| p0[i * width + j] == 0.0)
        .count();
    shots.push(Shot {
        pictures: vec![buffer_png(
            dir,
            "P0.png",
            "P0",
            &p0,
            1,
            &["value"],
            p0_dims,
        )?],
        key: format!(
            "rows: triangles of A, columns: triangles of B, row 0 at the bottom; 1 (pale) for a \
             pair that may intersect, 0 (grey) for one certainly apart; {} pairs reported",
            tile.reported
        ),
        check: Some(Check {
            what: format!(
                "every pair the CPU's exact test finds among all {} pairs is marked in P0: \
                 {missed} of {} missed (tolerance: none; P0 may mark more, the CPU confirms)",
                a.triangles.len() * b.triangles.len(),
                exact.len()
            ),
            passed: missed == 0,
        }),
    });

    let mut pictures = Vec::new();
    for (i, level) in tile.reduction.level_textures().into_iter().enumerate() {
        let values = level.download_f32()?;
        let name = format!("P{}", i + 1);
        let dims = (level.width(), level.height());
        pictures.push(buffer_png(
            dir,
            &format!("{name}.png"),
            &name,
            &values,
            level.format().components(),
            &["mask"],
            dims,
        )?);
    }
    shots.push(Shot {
        pictures,
        key: "each texel's value is a 16-bit mask (0 to 65535) of the set texels in the 4x4 \
              block below it; grey 0 means the block is empty and is never read"
            .into(),
        check: None,
    });

    let result = tester.run(&a, Some(&b))?;
    let mut found = vec![0f32; p0.len()];
    for &(i, j) in &result.pairs {
        found[i as usize * width + j as usize] = 1.0;
    }
    let exact_pairs: Vec<(u32, u32)> = exact.iter().map(|&(i, j)| (i as u32, j as u32)).collect();
    shots.push(Shot {
        pictures: vec![buffer_png(
            dir,
            "confirmed.png",
            "confirmed pairs",
            &found,
            1,
            &["value"],
            p0_dims,
        )?],
        key: format!(
            "the pairs the CPU confirmed, on the same grid as P0 (a CPU result drawn as P0 is): \
             {} of the {} reported",
            result.pairs.len(),
            result.candidates
        ),
        check: Some(Check {
            what: format!(
                "the confirmed pairs against brute force over all pairs with the exact \
                 predicate: {} found, {} expected (tolerance: none, the same list)",
                result.pairs.len(),
                exact_pairs.len()
            ),
            passed: result.pairs == exact_pairs,
        }),
    });
    Ok(shots)
}
