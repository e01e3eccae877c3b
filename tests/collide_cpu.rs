//! CPU side of paper 1: the stream, the SOLID baseline and the primitive test against the
//! brute-force all-pairs answer (same predicate), on data made here.

use classic_gpgpu::collide::brute_force::all_pairs;
use classic_gpgpu::collide::deform::{Deformation, Deforming, Pulsating, Wavy};
use classic_gpgpu::collide::solid;
use classic_gpgpu::collide::tri_test::{test_caps, ModelView};
use classic_gpgpu::collide::{AabbStream, Predicate};
use classic_gpgpu::mesh::Mesh;
use common::soup;
use glam::Vec3;

mod common;

fn view<'a>(m: &'a Mesh, p: &'a [Vec3], s: &'a AabbStream) -> ModelView<'a> {
    ModelView {
        triangles: &m.triangles,
        positions: p,
        stream: s,
    }
}

/// The streaming test's answer computed on the CPU: every slot pair with both stencils
/// set whose boxes overlap, mapped to leaf pairs.
fn streaming_caps_cpu(x: &AabbStream, px: &[Vec3], y: &AabbStream, py: &[Vec3]) -> Vec<(u32, u32)> {
    let bx = x.slot_boxes(px);
    let by = y.slot_boxes(py);
    let mut caps = Vec::new();
    for (i, bi) in bx.iter().enumerate() {
        for (j, bj) in by.iter().enumerate() {
            if x.stencil[i] == 1 && y.stencil[j] == 1 && bi.overlaps(bj) {
                caps.push((x.slot_leaf[i], y.slot_leaf[j]));
            }
        }
    }
    caps
}

#[test]
fn stream_and_solid_find_exactly_the_brute_force_pairs_on_random_soups() {
    for (seed, leaf) in [(1, 1), (2, 4), (3, 7), (4, 16)] {
        let x = soup(300, 0.15, seed);
        let y = soup(250, 0.15, seed + 100);
        let sx = AabbStream::build(&x, leaf).unwrap();
        let sy = AabbStream::build(&y, leaf).unwrap();
        for predicate in [Predicate::Moller, Predicate::Exact] {
            let expected = all_pairs(&x, &x.positions, &y, &y.positions, predicate);
            assert!(!expected.is_empty());
            let caps = streaming_caps_cpu(&sx, &x.positions, &sy, &y.positions);
            let mut unique = caps.clone();
            unique.sort_unstable();
            unique.dedup();
            assert_eq!(
                unique.len(),
                caps.len(),
                "virtual nodes produced a duplicate CAP"
            );
            let vx = view(&x, &x.positions, &sx);
            let vy = view(&y, &y.positions, &sy);
            let streamed = test_caps(vx, vy, &caps, predicate);
            assert_eq!(streamed.pairs, expected, "seed {seed} leaf {leaf}");

            let bx = solid::refit(&sx, &x.positions);
            let by = solid::refit(&sy, &y.positions);
            let solid_caps = solid::overlapping_leaves(&sx, &bx, &sy, &by);
            let mut caps_sorted = caps.clone();
            caps_sorted.sort_unstable();
            assert_eq!(solid_caps, caps_sorted, "SOLID's leaf pairs differ");
            assert_eq!(test_caps(vx, vy, &solid_caps, predicate).pairs, expected);
        }
    }
}

#[test]
fn solid_refit_follows_a_deformation_without_rebuilding() {
    let rest = soup(200, 0.2, 9);
    let other = soup(200, 0.2, 10);
    let so = AabbStream::build(&other, 8).unwrap();
    for def in [
        Deformation::Wavy(Wavy::for_size(1.0, 5)),
        Deformation::Pulsating(Pulsating::for_size(3.0)),
    ] {
        let d = Deforming::new(rest.clone(), def);
        let s = AabbStream::build(&rest, 8).unwrap();
        let bo = solid::refit(&so, &other.positions);
        for frame in 0..4 {
            let p = d.positions(frame as f32 * 0.25);
            let b = solid::refit(&s, &p);
            // The root box bounds every vertex.
            assert!(p
                .iter()
                .all(|q| b[0].min.cmple(*q).all() && b[0].max.cmpge(*q).all()));
            let caps = solid::overlapping_leaves(&s, &b, &so, &bo);
            let pairs = test_caps(
                view(&rest, &p, &s),
                view(&other, &other.positions, &so),
                &caps,
                Predicate::Moller,
            );
            let expected = all_pairs(&rest, &p, &other, &other.positions, Predicate::Moller);
            assert_eq!(pairs.pairs, expected, "frame {frame}");
        }
    }
}

#[test]
fn automatic_leaf_size_bounds_the_stream_and_keeps_the_default_for_the_papers_tori() {
    use classic_gpgpu::collide::stream_setup::{auto_leaf_size, max_slots, DEFAULT_LEAF_SIZE};
    let tori = classic_gpgpu::mesh::torus_with_triangles(1.0, 0.4, 15_000);
    let large = classic_gpgpu::mesh::torus_with_triangles(1.0, 0.4, 50_000);
    for software in [true, false] {
        assert_eq!(
            auto_leaf_size(&tori, max_slots(software)).unwrap(),
            DEFAULT_LEAF_SIZE
        );
    }
    // On a GPU the 50K model keeps the default; on a software renderer its leaves grow until
    // the stream fits, and no smaller size would.
    assert_eq!(
        auto_leaf_size(&large, max_slots(false)).unwrap(),
        DEFAULT_LEAF_SIZE
    );
    let bound = max_slots(true);
    let n = auto_leaf_size(&large, bound).unwrap();
    assert!(n > DEFAULT_LEAF_SIZE);
    assert!(AabbStream::build(&large, n).unwrap().len() <= bound);
    assert!(AabbStream::build(&large, n / 2).unwrap().len() > bound);
}

#[test]
fn readback_modes_and_predicates_parse_their_names_and_refuse_others() {
    use classic_gpgpu::collide::reduction_gpu::ReadbackMode;
    for mode in ReadbackMode::ALL {
        assert_eq!(mode.to_string().parse::<ReadbackMode>(), Ok(mode));
    }
    for predicate in Predicate::ALL {
        assert_eq!(predicate.to_string().parse::<Predicate>(), Ok(predicate));
    }
    let e = "fast".parse::<ReadbackMode>().unwrap_err();
    assert!(e.contains("fast") && e.contains("hierarchical"), "{e}");
    let e = "fuzzy".parse::<Predicate>().unwrap_err();
    assert!(e.contains("fuzzy") && e.contains("exact"), "{e}");
}
