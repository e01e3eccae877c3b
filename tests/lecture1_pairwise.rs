//! Lecture 1, pairwise triangle tests with the triangles in textures: the pairs the GPU
//! reports and the CPU confirms equal brute force with paper 1's exact predicate, between two
//! models and within one (no neighbours), tiled and not, with touching and coplanar pairs, at
//! extreme coordinate scales; and the fp32 filter reports no more than a few pairs beyond
//! the true ones.

use classic_gpgpu::lecture1::knotted_tube::{KnottedTube, RADIUS_RANGE};
use classic_gpgpu::lecture1::pairwise::PairwiseTester;
use classic_gpgpu::lecture1::reference::{pairs_between, self_pairs};
use classic_gpgpu::lecture1::weld::weld;
use classic_gpgpu::mesh::Mesh;
use common::{context, soup};
use glam::Vec3;

mod common;

fn scaled(mesh: &Mesh, s: f32) -> Mesh {
    Mesh::new(
        mesh.positions.iter().map(|p| *p * s).collect(),
        mesh.triangles.clone(),
    )
}

/// A grid of `n x n` unit squares in the plane z = 0 (two triangles each) and the same grid
/// turned so that it stands in x = 0.5 + k (a vertical wall crossing it), plus a copy of the
/// first grid shifted by half a square in its own plane (coplanar overlaps) and one lying on
/// it exactly (shared faces), and triangles touching it from above at a vertex.
fn contact_scene(n: usize) -> (Mesh, Mesh) {
    let grid = |f: &dyn Fn(f32, f32) -> Vec3| {
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for y in 0..=n {
            for x in 0..=n {
                positions.push(f(x as f32, y as f32));
            }
        }
        let at = |x: usize, y: usize| (y * (n + 1) + x) as u32;
        for y in 0..n {
            for x in 0..n {
                triangles.push([at(x, y), at(x + 1, y), at(x + 1, y + 1)]);
                triangles.push([at(x, y), at(x + 1, y + 1), at(x, y + 1)]);
            }
        }
        Mesh::new(positions, triangles)
    };
    let floor = grid(&|x, y| Vec3::new(x, y, 0.0));
    let wall = grid(&|x, y| Vec3::new(0.5 + (n / 2) as f32, x, y - 1.0));
    let shifted = grid(&|x, y| Vec3::new(x + 0.5, y + 0.25, 0.0));
    let same = grid(&|x, y| Vec3::new(x, y, 0.0));
    let spikes = Mesh::new(
        vec![
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.5, 1.0, 1.0),
            Vec3::new(1.0, 1.5, 1.0),
            Vec3::new(2.25, 2.5, 0.0),
            Vec3::new(2.5, 2.0, 1.0),
            Vec3::new(2.0, 2.0, 1.0),
        ],
        vec![[0, 1, 2], [3, 4, 5]],
    );
    (floor, Mesh::merged([&wall, &shifted, &same, &spikes]))
}

#[test]
fn two_models_equal_brute_force_tiled_and_untiled() {
    let ctx = context();
    let (a, b) = contact_scene(6);
    let expected = pairs_between(&a, &b);
    assert!(expected.len() > 100, "{}", expected.len());
    for tile in [1024, 16, 7] {
        let tester = PairwiseTester::new(&ctx, tile).unwrap();
        let found = tester.run(&a, Some(&b)).unwrap();
        assert_eq!(found.pairs, expected, "tile {tile}");
        // The fp32 filter is exact away from contact: here every contact is a touching or
        // coplanar one, so it may report more, but only pairs whose boxes meet.
        assert!(found.candidates >= expected.len());
        if tile == 7 {
            assert!(found.tiles > 1);
        }
    }
    // Random soups: most pairs cross properly, where the filter alone decides.
    let (x, y) = (soup(300, 0.15, 1), soup(250, 0.15, 2));
    let expected = pairs_between(&x, &y);
    assert!(expected.len() > 20, "{}", expected.len());
    let found = PairwiseTester::new(&ctx, 64)
        .unwrap()
        .run(&x, Some(&y))
        .unwrap();
    assert_eq!(found.pairs, expected);
    // No touching pairs in a random soup: the filter reports at most a few extra.
    assert!(
        found.candidates <= expected.len() + expected.len() / 20 + 2,
        "{} candidates for {} pairs",
        found.candidates,
        expected.len()
    );
}

#[test]
fn one_model_is_self_intersection_without_neighbours() {
    let ctx = context();
    let tube = KnottedTube::new(40, 8);
    let mut thick = tube.mesh.clone();
    thick.positions = tube.positions_at_radius(RADIUS_RANGE.1);
    let (a, b) = contact_scene(4);
    let merged = Mesh::merged([&a, &b]);
    for (name, mesh) in [("knot", &thick), ("contact scene", &merged)] {
        let expected = self_pairs(&weld(mesh), &mesh.positions);
        assert!(!expected.is_empty(), "{name}");
        for tile in [1024, 13] {
            let found = PairwiseTester::new(&ctx, tile)
                .unwrap()
                .run(mesh, None)
                .unwrap();
            assert_eq!(found.pairs, expected, "{name}, tile {tile}");
        }
    }
    // The thinnest tube: no pair; its neighbours (which touch along edges) are skipped on the
    // GPU, so the filter leaves at most a few near-touching pairs to the CPU.
    let thin = PairwiseTester::new(&ctx, 1024)
        .unwrap()
        .run(&tube.mesh, None)
        .unwrap();
    assert!(thin.pairs.is_empty() && thin.candidates < 5, "{thin:?}");
}

#[test]
fn extreme_scales() {
    let ctx = context();
    let tester = PairwiseTester::new(&ctx, 32).unwrap();
    let (a, b) = contact_scene(4);
    let (x, y) = (soup(120, 0.2, 3), soup(120, 0.2, 4));
    for s in [1e24f32, 1e-30, 3e37] {
        for (a, b) in [(&a, &b), (&x, &y)] {
            let (a, b) = (scaled(a, s), scaled(b, s));
            let expected = pairs_between(&a, &b);
            assert!(!expected.is_empty());
            assert_eq!(
                tester.run(&a, Some(&b)).unwrap().pairs,
                expected,
                "scale {s}"
            );
        }
    }
}

#[test]
fn bad_models_are_refused() {
    let ctx = context();
    let tester = PairwiseTester::new(&ctx, 64).unwrap();
    let (a, _) = contact_scene(2);
    let mut bad = a.clone();
    bad.positions[2].x = f32::INFINITY;
    let err = tester.run(&a, Some(&bad)).unwrap_err().to_string();
    assert!(err.contains("model B") && err.contains("vertex 2"), "{err}");
    let empty = Mesh::new(Vec::new(), Vec::new());
    let err = tester.run(&empty, None).unwrap_err().to_string();
    assert!(
        err.contains("model A") && err.contains("no triangles"),
        "{err}"
    );
}
