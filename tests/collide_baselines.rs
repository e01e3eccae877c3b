//! Paper 1's baselines and scenes: SOLID finds exactly the brute-force pairs,
//! CULLIDE finds a subset of them (it may miss, never invent) after pruning most triangles,
//! and every scene is deterministic. Small scenes, so llvmpipe runs them quickly.

use classic_gpgpu::collide::brute_force::all_pairs;
use classic_gpgpu::collide::cullide::Cullide;
use classic_gpgpu::collide::pipeline::{Options, StreamingCollider};
use classic_gpgpu::collide::reduction_gpu::ReadbackMode;
use classic_gpgpu::collide::scenes::{Scene, SCENES};
use classic_gpgpu::collide::tri_test::{test_caps, ModelView};
use classic_gpgpu::collide::{solid, AabbStream, Predicate};
use common::context;

mod common;

#[test]
fn solid_equals_and_cullide_is_a_subset_of_the_exact_pairs_on_every_scene() {
    let ctx = context();
    let (mut cullide_found, mut exact_found) = (0, 0);
    for name in SCENES {
        let scene = Scene::build(name, Some(800)).unwrap();
        let (x, y) = (&scene.x.rest, &scene.y.rest);
        let sx = AabbStream::build(x, 8).unwrap();
        let sy = AabbStream::build(y, 8).unwrap();
        let mut cullide = Cullide::new(&ctx, (x, &sx), (y, &sy), 1024).unwrap();
        for f in [0, 7] {
            let (px, py) = scene.frame(f);
            let exact = all_pairs(x, &px, y, &py, Predicate::Moller);
            let bx = solid::refit(&sx, &px);
            let by = solid::refit(&sy, &py);
            let caps = solid::overlapping_leaves(&sx, &bx, &sy, &by);
            let vx = ModelView {
                triangles: &x.triangles,
                positions: &px,
                stream: &sx,
            };
            let vy = ModelView {
                triangles: &y.triangles,
                positions: &py,
                stream: &sy,
            };
            let solid_pairs = test_caps(vx, vy, &caps, Predicate::Moller);
            assert_eq!(solid_pairs.pairs, exact, "SOLID on {name}, frame {f}");
            let c = cullide.frame(&px, &py, Predicate::Moller).unwrap();
            assert!(
                c.pairs.iter().all(|p| exact.binary_search(p).is_ok()),
                "CULLIDE reported a pair that does not intersect ({name}, frame {f})"
            );
            // CULLIDE must prune: at 1024 x 1024 fewer than a third of either model's
            // triangles survive on these scenes (measured: at most 27%), so that at most a
            // tenth of the triangle pairs reach the exact test (measured: at most 7%).
            let all = [x.triangles.len(), y.triangles.len()];
            for (kept, total) in c.survivors.into_iter().zip(all) {
                assert!(
                    3 * kept < total,
                    "CULLIDE kept {kept} of {total} triangles ({name}, frame {f})"
                );
            }
            assert_eq!(c.pctps, (c.survivors[0] * c.survivors[1]) as u64);
            assert!(10 * c.pctps < (all[0] * all[1]) as u64, "{name}, frame {f}");
            cullide_found += c.ctps;
            exact_found += exact.len();
        }
    }
    // Nor prune too much: at 1024 x 1024 it misses a few percent of the pairs (the paper's
    // 26-74% is at 512 x 512 with its view directions); at most half is allowed here.
    assert!(
        2 * cullide_found >= exact_found,
        "CULLIDE found {cullide_found} of {exact_found} colliding pairs at 1024 x 1024"
    );
}

#[test]
fn scenes_are_deterministic_and_collide() {
    let ctx = context();
    for name in ["interlocking-tori", "bump-bunnies"] {
        let a = Scene::build(name, Some(600)).unwrap();
        let b = Scene::build(name, Some(600)).unwrap();
        assert_eq!(a.x.rest, b.x.rest);
        assert_eq!(a.frame(5), b.frame(5));
        let opts = Options {
            readback: ReadbackMode::Hierarchical,
            ..Options::default()
        };
        let mut ca = StreamingCollider::new(&ctx, &a.x.rest, &a.y.rest, opts).unwrap();
        let mut cb = StreamingCollider::new(&ctx, &b.x.rest, &b.y.rest, opts).unwrap();
        let mut total = 0;
        for f in 0..3 {
            let (px, py) = a.frame(f);
            let ra = ca.frame(&px, &py).unwrap();
            let rb = cb.frame(&px, &py).unwrap();
            assert_eq!(ra.pairs, rb.pairs);
            total += ra.ctps;
        }
        assert!(total > 0, "scene {name} must have collisions");
    }
}

#[test]
fn unknown_scene_names_the_choices() {
    let err = Scene::build("teapots", None).err().unwrap().to_string();
    assert!(
        err.contains("teapots") && err.contains("merging-tori"),
        "{err}"
    );
}

/// CULLIDE's warm-up (the object level only, before the timed frames) changes nothing that
/// a frame finds: the same pairs, survivors and query count as without it.
#[test]
fn a_cullide_warm_up_leaves_the_frames_unchanged() {
    let ctx = context();
    let scene = Scene::build("merging-tori", Some(800)).unwrap();
    let (x, y) = (&scene.x.rest, &scene.y.rest);
    let sx = AabbStream::build(x, 8).unwrap();
    let sy = AabbStream::build(y, 8).unwrap();
    let mut cold = Cullide::new(&ctx, (x, &sx), (y, &sy), 512).unwrap();
    let mut warm = Cullide::new(&ctx, (x, &sx), (y, &sy), 512).unwrap();
    let (px, py) = scene.frame(0);
    warm.warm_up(&px, &py).unwrap();
    for f in [1, 5] {
        let (px, py) = scene.frame(f);
        let a = cold.frame(&px, &py, Predicate::Moller).unwrap();
        let b = warm.frame(&px, &py, Predicate::Moller).unwrap();
        assert!(!a.pairs.is_empty(), "frame {f}");
        assert_eq!(
            (&a.pairs, a.survivors, a.pctps, a.queries),
            (&b.pairs, b.survivors, b.pctps, b.queries),
            "frame {f}"
        );
    }
}

/// The streaming collider's warm-up (before the timed frames, smaller than a frame) changes
/// nothing that a frame finds, in one rectangle and in tiles, for every fixed scheme and the
/// paper's switch: the same pairs, CAPs, eta, scheme and bytes read back as after a whole
/// frame 0. `auto`'s lazy calibration measures no point for it.
#[test]
fn a_streaming_warm_up_leaves_the_frames_unchanged() {
    use classic_gpgpu::collide::pipeline::LazyCalibration;
    use classic_gpgpu::collide::reduction_gpu::CALIBRATION_ETAS;
    let ctx = context();
    let scene = Scene::build("merging-tori", Some(800)).unwrap();
    let (x, y) = (&scene.x.rest, &scene.y.rest);
    let (px, py) = scene.frame(0);
    for (readback, max_tile) in [
        (ReadbackMode::PaperSwitch, None),
        (ReadbackMode::Hierarchical, Some(64)),
        (ReadbackMode::Reduced, None),
        (ReadbackMode::Full, Some(64)),
    ] {
        let options = Options {
            leaf_size: 4,
            readback,
            max_tile,
            ..Options::default()
        };
        let mut cold = StreamingCollider::new(&ctx, x, y, options).unwrap();
        let mut warm = StreamingCollider::new(&ctx, x, y, options).unwrap();
        assert_eq!(warm.layout.count() > 1, max_tile.is_some(), "{readback:?}");
        cold.frame(&px, &py).unwrap();
        warm.warm_up(&px, &py).unwrap();
        for f in [1, 5] {
            let (px, py) = scene.frame(f);
            let a = cold.frame(&px, &py).unwrap();
            let b = warm.frame(&px, &py).unwrap();
            assert!(!a.pairs.is_empty(), "{readback:?} frame {f}");
            assert_eq!(
                (&a.pairs, &a.cap_leaves, a.eta, a.scheme, a.readback_bytes),
                (&b.pairs, &b.cap_leaves, b.eta, b.scheme, b.readback_bytes),
                "{readback:?} frame {f}"
            );
        }
    }
    let options = Options {
        leaf_size: 4,
        readback: ReadbackMode::Auto,
        ..Options::default()
    };
    let mut auto = StreamingCollider::new_uncalibrated(&ctx, x, y, options).unwrap();
    auto.calibrate_lazily(LazyCalibration::new(&CALIBRATION_ETAS, 1));
    auto.warm_up(&px, &py).unwrap();
    let lazy = auto.take_lazy_calibration().unwrap();
    assert!(lazy.points.iter().all(Option::is_none));
}
