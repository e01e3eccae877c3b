//! Lecture 1, self-collision: paper 1's streaming AABBs with one model against itself find
//! exactly the pairs that brute force with the same exact predicate finds (intersecting, no
//! shared vertex, vertices at equal positions shared), on a tube that folds through itself,
//! on contact cases (touching, coplanar, neighbours that cross), on paper 1's deformations,
//! tiled and not, and at extreme coordinate scales.

use classic_gpgpu::collide::deform::{Deformation, Deforming, Pulsating, Wavy};
use classic_gpgpu::collide::reduction_gpu::ReadbackMode;
use classic_gpgpu::lecture1::knotted_tube::{KnottedTube, RADIUS_RANGE};
use classic_gpgpu::lecture1::reference::self_pairs;
use classic_gpgpu::lecture1::self_collision::{Options, SelfCollider};
use classic_gpgpu::lecture1::weld::weld;
use classic_gpgpu::mesh::{self, Mesh};
use common::context;
use glam::Vec3;

mod common;

fn options(leaf_size: usize, max_tile: usize, readback: ReadbackMode) -> Options {
    Options {
        leaf_size,
        readback,
        max_tile,
    }
}

/// GPU pairs at `positions` against brute force on the welded model; returns the pairs.
fn check(collider: &mut SelfCollider, positions: &[Vec3], what: &str) -> Vec<(u32, u32)> {
    let gpu = collider.frame(positions).unwrap();
    let cpu = self_pairs(&collider.mesh, positions);
    assert_eq!(gpu.pairs, cpu, "{what}");
    cpu
}

#[test]
fn the_swelling_knot_finds_the_brute_force_pairs_tiled_and_untiled() {
    let ctx = context();
    let tube = KnottedTube::new(40, 8);
    // Leaves of 4 triangles: 80 leaves in 128 slots; 32-slot tiles make 4 x 4 tiles, of
    // which the 10 on or above the diagonal are drawn.
    for (max_tile, readback) in [
        (4096, ReadbackMode::PaperSwitch),
        (32, ReadbackMode::Hierarchical),
        (32, ReadbackMode::Full),
    ] {
        let mut collider =
            SelfCollider::new(&ctx, &tube.mesh, options(4, max_tile, readback)).unwrap();
        let thin = check(
            &mut collider,
            &tube.positions_at_radius(RADIUS_RANGE.0),
            "thinnest tube",
        );
        assert!(thin.is_empty(), "the thinnest tube must not touch itself");
        let thick = check(
            &mut collider,
            &tube.positions_at_radius(RADIUS_RANGE.1),
            "thickest tube",
        );
        assert!(thick.len() > 20, "the thickest tube folds through itself");
        for t in [0.5, 1.0, 1.7] {
            check(&mut collider, &tube.positions(t), &format!("t = {t}"));
        }
    }
}

/// Triangles meeting in the ways exact predicates must decide: coplanar overlap, a vertex on
/// a face, edge on edge, a neighbour (shared vertex, one of them split) that crosses, and
/// pairs that miss by one float step.
fn contact_cases() -> Mesh {
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let triangles: Vec<[Vec3; 3]> = vec![
        // 0, 1: coplanar, overlapping.
        [v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0)],
        [v(0.25, 0.25, 0.0), v(1.25, 0.25, 0.0), v(0.25, 1.25, 0.0)],
        // 2: its vertex on triangle 0's face.
        [v(0.2, 0.2, 0.0), v(0.2, 0.3, 1.0), v(0.3, 0.2, 1.0)],
        // 3: coplanar with 0, touching it along part of an edge only.
        [v(0.0, 0.0, 0.0 + 0.0), v(0.5, -1.0, 0.0), v(1.0, 0.0, 0.0)],
        // 4: one float step above triangle 0's plane, not touching it.
        [
            v(0.1, 0.1, f32::MIN_POSITIVE),
            v(0.4, 0.1, 1.0),
            v(0.1, 0.4, 1.0),
        ],
        // 5, 6: far away, edge crossing edge.
        [v(5.0, 0.0, 0.0), v(6.0, 0.0, 0.0), v(5.5, 1.0, 0.0)],
        [v(5.5, 0.5, -1.0), v(5.5, 0.5, 1.0), v(5.5, -1.0, 0.0)],
        // 7: shares triangle 5's vertex (5, 0, 0) through a split copy, and crosses it.
        [v(5.0, 0.0, 0.0), v(5.8, 0.2, -0.5), v(5.8, 0.2, 0.5)],
    ];
    let positions: Vec<Vec3> = triangles.iter().flatten().copied().collect();
    let indices = (0..triangles.len() as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    Mesh::new(positions, indices)
}

#[test]
fn contact_cases_are_decided_exactly_and_neighbours_are_excluded() {
    let ctx = context();
    let mesh = contact_cases();
    let mut collider =
        SelfCollider::new(&ctx, &mesh, options(1, 4096, ReadbackMode::Hierarchical)).unwrap();
    let pairs = check(&mut collider, &mesh.positions, "contact cases");
    // 0-1 overlap, 0-2 vertex on face, 5-6 edge on edge. Triangle 3 has copies of two of
    // triangle 0's vertices and 7 one of 5's, so welded they are neighbours and excluded;
    // 0-4 miss by the smallest normal float.
    for expected in [(0, 1), (0, 2), (5, 6)] {
        assert!(pairs.contains(&expected), "{expected:?} in {pairs:?}");
    }
    for excluded in [(0, 3), (0, 4), (5, 7)] {
        assert!(!pairs.contains(&excluded), "{excluded:?} in {pairs:?}");
    }
    // Unwelded, the same triangles would not be neighbours: brute force finds 0-3 and 5-7.
    let unwelded = self_pairs(&mesh, &mesh.positions);
    assert!(unwelded.contains(&(0, 3)) && unwelded.contains(&(5, 7)));
}

#[test]
fn extreme_scales_and_paper_1_deformations() {
    let ctx = context();
    let tube = KnottedTube::new(32, 6);
    let thick = tube.positions_at_radius(RADIUS_RANGE.1);
    for scale in [1e24f32, 1e-30] {
        let scaled: Vec<Vec3> = thick.iter().map(|p| *p * scale).collect();
        let mesh = Mesh::new(scaled.clone(), tube.mesh.triangles.clone());
        let mut collider =
            SelfCollider::new(&ctx, &mesh, options(4, 16, ReadbackMode::PaperSwitch)).unwrap();
        let pairs = check(&mut collider, &scaled, &format!("scale {scale}"));
        assert!(!pairs.is_empty(), "scale {scale}");
        // The contact cases too, at scale.
        let cases = contact_cases();
        let p: Vec<Vec3> = cases.positions.iter().map(|p| *p * scale).collect();
        let mut c = SelfCollider::new(
            &ctx,
            &Mesh::new(p.clone(), cases.triangles.clone()),
            options(2, 4096, ReadbackMode::Full),
        )
        .unwrap();
        check(&mut c, &p, &format!("contact cases at scale {scale}"));
    }
    // Paper 1's deformations on a torus, folded flat so that its sides press together.
    let torus = mesh::torus_with_triangles(1.0, 0.3, 600).scaled(Vec3::new(1.0, 1.0, 0.15));
    let size = 2.0;
    for deformation in [
        Deformation::Wavy(Wavy::for_size(size, 7)),
        Deformation::Pulsating(Pulsating {
            amplitude: 0.1,
            ..Pulsating::for_size(size)
        }),
    ] {
        let deforming = Deforming::new(weld(&torus), deformation);
        let mut collider = SelfCollider::new(
            &ctx,
            &deforming.rest,
            options(8, 32, ReadbackMode::PaperSwitch),
        )
        .unwrap();
        let mut found = 0;
        for f in 0..4 {
            found += check(
                &mut collider,
                &deforming.positions(f as f32 * 0.3),
                &format!("{:?} frame {f}", deforming.deformation),
            )
            .len();
        }
        assert!(found > 0, "{:?}", deforming.deformation);
    }
}

#[test]
fn bad_positions_are_refused() {
    let ctx = context();
    let tube = KnottedTube::new(24, 6);
    let mut collider = SelfCollider::new(&ctx, &tube.mesh, Options::default()).unwrap();
    let mut p = tube.mesh.positions.clone();
    p[3].y = f32::NAN;
    let err = collider.frame(&p).unwrap_err().to_string();
    assert!(
        err.contains("vertex 3") && err.contains("not finite"),
        "{err}"
    );
    let err = collider.frame(&p[..5]).unwrap_err().to_string();
    assert!(err.contains("5 positions"), "{err}");
}
