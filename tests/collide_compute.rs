//! Paper 1's compute formulation (OpenGL 4.3) against the classic pipeline, the CPU and
//! brute force: every frame of small deforming scenes gives the same colliding leaf pairs
//! (CAPs) and the same triangle pairs; the compute leaf boxes equal the CPU's bit for bit
//! (min/max is exact in fp32, so the tolerance is zero). On a context below 4.3 (softpipe)
//! the compute collider is a clear error and the classic pipeline still runs.

use classic_gpgpu::collide::brute_force::all_pairs;
use classic_gpgpu::collide::compute_pipeline::ComputeCollider;
use classic_gpgpu::collide::deform::{Deformation, Deforming, Wavy};
use classic_gpgpu::collide::pipeline::{Options, StreamingCollider};
use classic_gpgpu::collide::reduction_gpu::ReadbackMode;
use classic_gpgpu::collide::{solid, Predicate};
use classic_gpgpu::mesh;
use common::{compute_context, soup};
use glam::{Affine3A, Quat, Vec3};

mod common;

fn options(leaf_size: usize) -> Options {
    Options {
        leaf_size,
        readback: ReadbackMode::Hierarchical,
        predicate: Predicate::Moller,
        max_tile: None,
    }
}

#[test]
fn deforming_tori_same_pairs_as_classic_and_brute_force_every_frame() {
    let (ctx, compute) = compute_context();
    let a = mesh::torus_with_triangles(1.0, 0.33, 600);
    let b = a.transformed(&Affine3A::from_rotation_translation(
        Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
        Vec3::X * 1.38,
    ));
    let da = Deforming::new(a.clone(), Deformation::Wavy(Wavy::for_size(2.7, 1)));
    let db = Deforming::new(b.clone(), Deformation::Wavy(Wavy::for_size(2.7, 2)));
    let mut classic = StreamingCollider::new(&ctx, &a, &b, options(8)).unwrap();
    if !compute {
        let err = ComputeCollider::new(&ctx, &a, &b, options(8))
            .err()
            .unwrap()
            .to_string();
        assert!(
            err.contains("paper 1") && err.contains("needs OpenGL 4.3"),
            "{err}"
        );
        let (pa, pb) = (da.positions(0.3), db.positions(0.3));
        let r = classic.frame(&pa, &pb).unwrap();
        assert_eq!(r.pairs, all_pairs(&a, &pa, &b, &pb, Predicate::Moller));
        return;
    }
    let mut modern = ComputeCollider::new(&ctx, &a, &b, options(8)).unwrap();
    let mut total = 0;
    for f in 0..12 {
        let t = f as f32 * 0.1;
        let (pa, pb) = (da.positions(t), db.positions(t));
        let then = classic.frame(&pa, &pb).unwrap();
        let now = modern.frame(&pa, &pb).unwrap();
        let cpu_caps = solid::all_overlapping_leaves(
            &modern.stream_x.leaf_boxes(&pa),
            &modern.stream_y.leaf_boxes(&pb),
        );
        assert_eq!(now.cap_leaves, cpu_caps, "frame {f}: CAPs vs CPU");
        assert_eq!(
            now.cap_leaves, then.cap_leaves,
            "frame {f}: CAPs vs classic"
        );
        assert_eq!(now.pairs, then.pairs, "frame {f}: pairs vs classic");
        assert_eq!(
            now.pairs,
            all_pairs(&a, &pa, &b, &pb, Predicate::Moller),
            "frame {f}: pairs vs brute force"
        );
        assert_eq!(
            modern.x.download().unwrap(),
            modern.stream_x.leaf_boxes(&pa)
        );
        assert_eq!(
            modern.y.download().unwrap(),
            modern.stream_y.leaf_boxes(&pb)
        );
        total += now.ctps;
    }
    assert!(total > 0, "the tori must touch in some frame");
}

#[test]
fn soups_overflow_the_pair_list_and_still_give_every_pair() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    // Leaf size 1 and large overlapping triangles: more CAPs than the first list holds.
    let x = soup(200, 1.0, 41);
    let y = soup(150, 1.0, 42);
    let mut modern = ComputeCollider::new(&ctx, &x, &y, options(1)).unwrap();
    let mut classic = StreamingCollider::new(&ctx, &x, &y, options(1)).unwrap();
    for _ in 0..2 {
        let now = modern.frame(&x.positions, &y.positions).unwrap();
        let then = classic.frame(&x.positions, &y.positions).unwrap();
        assert!(now.caps > 4096, "{} CAPs", now.caps);
        assert_eq!(now.cap_leaves, then.cap_leaves);
        assert_eq!(
            now.pairs,
            all_pairs(&x, &x.positions, &y, &y.positions, Predicate::Moller)
        );
    }
}

#[test]
fn disjoint_models_and_bad_positions() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    let x = soup(50, 0.1, 43);
    let y = x.translated(Vec3::X * 5.0);
    let mut modern = ComputeCollider::new(&ctx, &x, &y, options(4)).unwrap();
    let r = modern.frame(&x.positions, &y.positions).unwrap();
    assert!(!r.global_overlap && r.pairs.is_empty());
    let mut bad = x.positions.clone();
    bad[3] = Vec3::NAN;
    let err = modern.frame(&bad, &y.positions).unwrap_err().to_string();
    assert!(err.contains("model X: vertex 3 is not finite"), "{err}");
    let err = modern
        .frame(&x.positions[1..], &y.positions)
        .unwrap_err()
        .to_string();
    assert!(err.contains("model X"), "{err}");
}
