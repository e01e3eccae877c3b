//! Paper 1's GPU pipeline on a real headless context (llvmpipe in CI), against the CPU:
//! the pair set equals the brute-force all-pairs Möller answer exactly (same predicate) for
//! every readback scheme, with and without tiles, on rigid and deforming inputs; the stream
//! update's boxes equal the CPU's leaf boxes bit for bit (min/max and texture storage are
//! exact in fp32, so the tolerance is zero); bad inputs give errors that say what is wrong.

use classic_gpgpu::collide::brute_force::all_pairs;
use classic_gpgpu::collide::deform::{Deformation, Deforming, Wavy};
use classic_gpgpu::collide::pipeline::{Options, StreamingCollider};
use classic_gpgpu::collide::reduction::P0Contents;
use classic_gpgpu::collide::reduction_gpu::{paper_switch, ReadbackMode};
use classic_gpgpu::collide::{solid, AabbStream, Predicate};
use classic_gpgpu::mesh::{self, Mesh};
use common::{context, soup};
use glam::{Affine3A, Quat, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod common;

fn options(readback: ReadbackMode, leaf_size: usize) -> Options {
    Options {
        leaf_size,
        readback,
        predicate: Predicate::Moller,
        max_tile: None,
    }
}

const FIXED: [ReadbackMode; 3] = [
    ReadbackMode::Hierarchical,
    ReadbackMode::Reduced,
    ReadbackMode::Full,
];

/// The CAPs as the CPU sees them: pairs of real leaves whose boxes overlap.
fn cpu_caps(x: &AabbStream, px: &[Vec3], y: &AabbStream, py: &[Vec3]) -> Vec<(u32, u32)> {
    solid::all_overlapping_leaves(&x.leaf_boxes(px), &y.leaf_boxes(py))
}

#[test]
fn random_soups_give_exactly_the_brute_force_pairs_with_every_readback() {
    let ctx = context();
    for (seed, leaf) in [(1u64, 4usize), (2, 1), (3, 16)] {
        let x = soup(300, 0.12, seed);
        let y = soup(200, 0.12, seed + 50);
        for predicate in [Predicate::Moller, Predicate::Exact] {
            let expected = all_pairs(&x, &x.positions, &y, &y.positions, predicate);
            assert!(!expected.is_empty());
            for readback in FIXED {
                let mut o = options(readback, leaf);
                o.predicate = predicate;
                let mut c = StreamingCollider::new(&ctx, &x, &y, o).unwrap();
                let r = c.frame(&x.positions, &y.positions).unwrap();
                assert_eq!(r.pairs, expected, "seed {seed} leaf {leaf} {readback:?}");
                let caps = cpu_caps(&c.x.stream, &x.positions, &c.y.stream, &y.positions);
                assert_eq!(
                    r.cap_leaves, caps,
                    "CAPs differ from the CPU's ({readback:?})"
                );
                let mut unique = r.cap_leaves.clone();
                unique.dedup();
                assert_eq!(
                    unique.len(),
                    r.cap_leaves.len(),
                    "a virtual node duplicated a CAP"
                );
            }
        }
    }
}

#[test]
fn stream_update_matches_cpu_leaf_boxes_exactly() {
    let ctx = context();
    let x = soup(250, 0.1, 7);
    let y = soup(100, 0.1, 8);
    let mut c = StreamingCollider::new(&ctx, &x, &y, options(ReadbackMode::Full, 7)).unwrap();
    assert!(
        c.x.stream.virtual_slots() > 0,
        "the test needs virtual nodes"
    );
    let moved: Vec<Vec3> = x.positions.iter().map(|p| *p * 1.5 - 0.2).collect();
    c.frame(&moved, &y.positions).unwrap();
    assert_eq!(
        c.gpu_slot_boxes(false).unwrap(),
        c.x.stream.slot_boxes(&moved)
    );
    assert_eq!(
        c.gpu_slot_boxes(true).unwrap(),
        c.y.stream.slot_boxes(&y.positions)
    );
}

#[test]
fn random_rigid_placements_of_generated_meshes() {
    let ctx = context();
    let mut rng = ChaCha8Rng::seed_from_u64(21);
    let shapes = [
        mesh::torus_with_triangles(1.0, 0.3, 400),
        mesh::uv_sphere(0.8, 16, 10),
        mesh::cube(1.2),
        mesh::load_bunny(),
    ];
    for k in 0..4 {
        let a = &shapes[k % shapes.len()];
        let b = &shapes[(k + 1) % shapes.len()];
        let scale_b = 0.9 * size(a) / size(b);
        let place = Affine3A::from_scale_rotation_translation(
            Vec3::splat(scale_b),
            Quat::from_euler(glam::EulerRot::XYZ, rng.gen(), rng.gen(), rng.gen()),
            Vec3::new(rng.gen(), rng.gen(), rng.gen()) * 0.3 * size(a),
        );
        let b = b.transformed(&place);
        let expected = all_pairs(a, &a.positions, &b, &b.positions, Predicate::Moller);
        for readback in [ReadbackMode::Hierarchical, ReadbackMode::Reduced] {
            let mut c = StreamingCollider::new(&ctx, a, &b, options(readback, 8)).unwrap();
            let r = c.frame(&a.positions, &b.positions).unwrap();
            assert_eq!(r.pairs, expected, "placement {k} {readback:?}");
        }
    }
}

fn size(m: &Mesh) -> f32 {
    let b = m.bounds();
    (b.max - b.min).max_element()
}

#[test]
fn deforming_tori_over_many_frames() {
    let ctx = context();
    let a = mesh::torus_with_triangles(1.0, 0.33, 600);
    let b = a.transformed(&Affine3A::from_rotation_translation(
        Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
        Vec3::X * 1.38,
    ));
    let da = Deforming::new(a.clone(), Deformation::Wavy(Wavy::for_size(2.7, 1)));
    let db = Deforming::new(b.clone(), Deformation::Wavy(Wavy::for_size(2.7, 2)));
    for readback in [ReadbackMode::Hierarchical, ReadbackMode::Reduced] {
        let mut c = StreamingCollider::new(&ctx, &a, &b, options(readback, 8)).unwrap();
        let mut total = 0;
        for f in 0..12 {
            let (pa, pb) = (da.positions(f as f32 * 0.1), db.positions(f as f32 * 0.1));
            let r = c.frame(&pa, &pb).unwrap();
            let expected = all_pairs(&a, &pa, &b, &pb, Predicate::Moller);
            assert_eq!(r.pairs, expected, "frame {f} {readback:?}");
            assert_eq!(c.gpu_slot_boxes(false).unwrap(), c.x.stream.slot_boxes(&pa));
            total += r.ctps;
        }
        assert!(total > 0, "the tori must touch in some frame");
    }
}

#[test]
fn a_model_forced_through_many_tiles() {
    let ctx = context();
    let x = soup(400, 0.1, 31);
    let y = soup(300, 0.1, 32);
    let expected = all_pairs(&x, &x.positions, &y, &y.positions, Predicate::Moller);
    for readback in [
        ReadbackMode::Hierarchical,
        ReadbackMode::Reduced,
        ReadbackMode::Auto,
        ReadbackMode::PaperSwitch,
    ] {
        let mut o = options(readback, 4);
        o.max_tile = Some(32);
        let mut c = StreamingCollider::new(&ctx, &x, &y, o).unwrap();
        assert!(c.layout.count() >= 8, "{:?}", c.layout);
        let r = c.frame(&x.positions, &y.positions).unwrap();
        assert_eq!(r.pairs, expected, "{readback:?}");
        assert_eq!(r.tiles, c.layout.count());
    }
}

#[test]
fn disjoint_models_are_rejected_by_the_global_test() {
    let ctx = context();
    let x = soup(50, 0.1, 41);
    let y = Mesh::new(
        x.positions.iter().map(|p| *p + Vec3::X * 5.0).collect(),
        x.triangles.clone(),
    );
    let mut c =
        StreamingCollider::new(&ctx, &x, &y, options(ReadbackMode::Hierarchical, 4)).unwrap();
    let r = c.frame(&x.positions, &y.positions).unwrap();
    assert!(!r.global_overlap);
    assert!(r.pairs.is_empty() && r.caps == 0);
}

#[test]
fn bad_inputs_give_clear_errors() {
    let ctx = context();
    let good = soup(20, 0.1, 1);
    let err = |x: &Mesh, y: &Mesh, o: Options| {
        StreamingCollider::new(&ctx, x, y, o)
            .err()
            .expect("must fail")
            .to_string()
    };
    let o = options(ReadbackMode::Full, 4);
    assert!(err(&Mesh::default(), &good, o).contains("no triangles"));
    let mut nan = good.clone();
    nan.positions[4].x = f32::NAN;
    assert!(err(&good, &nan, o).contains("model Y"));
    // Streams of 2^14 slots each in tiles of 2: far more tiles than the budget.
    let big = soup(1 << 14, 0.01, 2);
    let mut tiny_tiles = options(ReadbackMode::Full, 1);
    tiny_tiles.max_tile = Some(2);
    assert!(err(&big, &big, tiny_tiles).contains("tiles"));
    // One leaf with more vertices than a texture has rows.
    let rows = ctx.info().limits.max_texture_size as usize;
    let wide = soup(rows / 3 + 1, 0.01, 3);
    let one_leaf = options(ReadbackMode::Full, wide.triangles.len());
    let e = err(&wide, &good, one_leaf);
    assert!(e.contains("vertices") && e.contains("leaf size"), "{e}");
    // A frame with the wrong vertex count or a NaN.
    let mut c = StreamingCollider::new(&ctx, &good, &good, o).unwrap();
    let short = &good.positions[..10];
    assert!(c
        .frame(short, &good.positions)
        .unwrap_err()
        .to_string()
        .contains("model X"));
    let mut p = good.positions.clone();
    p[0].y = f32::INFINITY;
    assert!(c
        .frame(&good.positions, &p)
        .unwrap_err()
        .to_string()
        .contains("not finite"));
}

#[test]
fn every_collide_shader_compiles_and_links() {
    use classic_gpgpu::gl::Program;
    use classic_gpgpu::shader;
    let ctx = context();
    let rect = [
        shader!("cg_ports/collide_table1_streaming_aabb_test.frag"),
        shader!("glsl/collide/stencil_mask.frag"),
        shader!("glsl/collide/encode_4x4.frag"),
        shader!("glsl/collide/encode_8x8.frag"),
    ];
    Program::new(&ctx, &[shader!("glsl/collide/aabb_pairs.vert")], &rect[..1]).unwrap();
    for fragment in &rect[1..] {
        Program::rect(&ctx, std::slice::from_ref(fragment)).unwrap();
    }
    Program::new(
        &ctx,
        &[shader!("glsl/collide/stream_line.vert")],
        &[shader!("cg_ports/collide_table2_stream_update.frag")],
    )
    .unwrap();
    Program::new(
        &ctx,
        &[shader!("glsl/collide/cullide.vert")],
        &[shader!("glsl/collide/cullide.frag")],
    )
    .unwrap();
    Program::new(
        &ctx,
        &[shader!("glsl/collide/snapshot.vert")],
        &[shader!("glsl/collide/snapshot.frag")],
    )
    .unwrap();
}

/// The paper's size: every scene of Table III, two frames, each readback scheme, against
/// brute force. Slow in debug builds; run with `cargo test --release -- --ignored`.
#[test]
#[ignore = "paper size (15K-50K triangles per model): run in release with --ignored"]
fn paper_size_scenes_match_brute_force() {
    use classic_gpgpu::collide::scenes::{Scene, SCENES};
    let ctx = context();
    for name in SCENES {
        let scene = Scene::build(name, None).unwrap();
        let (x, y) = (&scene.x.rest, &scene.y.rest);
        for readback in FIXED {
            let mut c = StreamingCollider::new(&ctx, x, y, options(readback, 16)).unwrap();
            for f in [0, 9] {
                let (px, py) = scene.frame(f);
                let r = c.frame(&px, &py).unwrap();
                let expected = all_pairs(x, &px, y, &py, Predicate::Moller);
                assert_eq!(r.pairs, expected, "{name} frame {f} {readback:?}");
                eprintln!("{name} frame {f} {readback:?}: {} pairs", expected.len());
            }
        }
    }
}

#[test]
fn streams_of_one_and_few_slots_in_every_scheme() {
    // P0 of 1 x n and n x 2: the encodings must handle blocks cut by the edges.
    let ctx = context();
    for (nx, ny, leaf) in [(1usize, 200usize, 2usize), (300, 3, 2), (5, 5, 1)] {
        let x = soup(nx, 0.6, nx as u64);
        let y = soup(ny, 0.6, 100 + ny as u64);
        let expected = all_pairs(&x, &x.positions, &y, &y.positions, Predicate::Moller);
        for readback in ReadbackMode::ALL {
            let mut c = StreamingCollider::new(&ctx, &x, &y, options(readback, leaf)).unwrap();
            let r = c.frame(&x.positions, &y.positions).unwrap();
            assert_eq!(r.pairs, expected, "{nx} x {ny} {readback:?}");
            if readback == ReadbackMode::PaperSwitch && r.caps > 0 {
                // One tile: the frame's eta is the tile's.
                assert_eq!(r.scheme, Some(paper_switch(r.eta)), "{nx} x {ny}");
            }
        }
    }
}

#[test]
fn auto_calibrates_on_clustered_p0_contents() {
    // Sec. 5.3.1's hierarchy counts on CAPs that cluster, as the scenes' do; uniformly
    // random contents put one CAP in each set P1 texel.
    let ctx = context();
    let x = soup(200, 0.1, 61);
    let y = soup(200, 0.1, 62);
    let c = StreamingCollider::new(&ctx, &x, &y, options(ReadbackMode::Auto, 1)).unwrap();
    assert!(!c.calibration.is_empty());
    assert!(c
        .calibration
        .iter()
        .all(|p| p.contents == P0Contents::Clustered));
    let dense = c
        .calibration
        .iter()
        .find(|p| p.caps >= 20)
        .expect("a point with CAPs");
    assert!(dense.caps_per_set_p1_texel > 1.5, "{dense:?}");
    let fixed =
        StreamingCollider::new(&ctx, &x, &y, options(ReadbackMode::PaperSwitch, 1)).unwrap();
    assert!(
        fixed.calibration.is_empty(),
        "the paper's switch needs no calibration"
    );
}

/// A calibration made at one `P0` size serves another collider of that size (the bench
/// shares them): same pairs as brute force; and `auto` with no calibration at all is an
/// error, not a silent fall back to one scheme.
#[test]
fn a_shared_calibration_serves_auto_and_none_is_an_error() {
    let ctx = context();
    let x = soup(150, 0.1, 71);
    let y = soup(150, 0.1, 72);
    let first = StreamingCollider::new(&ctx, &x, &y, options(ReadbackMode::Auto, 1)).unwrap();
    let mut shared =
        StreamingCollider::new_uncalibrated(&ctx, &x, &y, options(ReadbackMode::Auto, 1)).unwrap();
    let err = shared.frame(&x.positions, &y.positions).unwrap_err();
    assert!(err.to_string().contains("no calibration"), "{err}");
    assert_eq!(
        (shared.target.width(), shared.target.height()),
        (first.target.width(), first.target.height())
    );
    shared.set_calibration(first.calibration.clone());
    let r = shared.frame(&x.positions, &y.positions).unwrap();
    let expected = all_pairs(&x, &x.positions, &y, &y.positions, Predicate::Moller);
    assert!(!expected.is_empty());
    assert_eq!(r.pairs, expected);
}

/// `auto` calibrated lazily (the bench's colliders) measures only the point nearest to the
/// frame's eta, on the same P0 contents as the whole calibration's point there (same CAPs
/// and clustering, so the same random fills), finds the brute-force pairs, and hands the
/// point on to the next collider of its size, which measures nothing again.
#[test]
fn a_lazy_calibration_measures_only_the_points_frames_need() {
    use classic_gpgpu::collide::pipeline::LazyCalibration;
    use classic_gpgpu::collide::reduction_gpu::{nearest, CALIBRATION_ETAS};
    let ctx = context();
    let x = soup(150, 0.1, 81);
    let y = soup(150, 0.1, 82);
    let whole = StreamingCollider::new(&ctx, &x, &y, options(ReadbackMode::Auto, 1)).unwrap();
    let mut lazy =
        StreamingCollider::new_uncalibrated(&ctx, &x, &y, options(ReadbackMode::Auto, 1)).unwrap();
    lazy.calibrate_lazily(LazyCalibration::new(&CALIBRATION_ETAS, 1));
    let r = lazy.frame(&x.positions, &y.positions).unwrap();
    let expected = all_pairs(&x, &x.positions, &y, &y.positions, Predicate::Moller);
    assert!(!expected.is_empty());
    assert_eq!(r.pairs, expected);
    let k = nearest(CALIBRATION_ETAS.iter().copied(), r.eta).unwrap();
    let points = lazy.take_lazy_calibration().unwrap().points;
    let measured: Vec<usize> = (0..points.len()).filter(|&i| points[i].is_some()).collect();
    assert_eq!(measured, vec![k], "eta {}", r.eta);
    let (got, want) = (points[k].as_ref().unwrap(), &whole.calibration[k]);
    assert_eq!(got.eta, want.eta);
    assert_eq!(
        (got.caps, got.caps_per_set_p1_texel),
        (want.caps, want.caps_per_set_p1_texel)
    );
    let mut next =
        StreamingCollider::new_uncalibrated(&ctx, &x, &y, options(ReadbackMode::Auto, 1)).unwrap();
    next.calibrate_lazily(LazyCalibration {
        etas: CALIBRATION_ETAS.to_vec(),
        repeats: 1,
        points: points.clone(),
    });
    assert_eq!(
        next.frame(&x.positions, &y.positions).unwrap().pairs,
        expected
    );
    let again = next.take_lazy_calibration().unwrap().points;
    assert_eq!(again.iter().filter(|p| p.is_some()).count(), 1);
}

/// The decoders take any non-zero mark for a CAP, so a NaN in a level read back would be
/// a pair that does not exist: every value read is checked, and a non-finite one is an
/// error naming the level and the pass that wrote it. (Here `P0` is filled by hand.)
#[test]
fn a_non_finite_mark_is_an_error_naming_the_level_and_the_pass() {
    use classic_gpgpu::collide::reduction::Scheme;
    use classic_gpgpu::collide::reduction_gpu::Reduction;
    use classic_gpgpu::collide::streaming_test::PairTarget;
    let ctx = context();
    let (w, h) = (64, 48);
    let p0 = PairTarget::new(&ctx, w, h).unwrap();
    let reduction = Reduction::new(&ctx, w, h).unwrap();
    let mut marks = vec![0.0f32; w * h];
    marks[5 * w + 7] = 1.0;
    marks[40 * w + 60] = 1.0;
    p0.p0.upload_f32(&marks).unwrap();
    for scheme in [Scheme::Hierarchical, Scheme::Reduced, Scheme::Full] {
        let read = reduction.read(&ctx, &p0, scheme).unwrap();
        assert_eq!(read.decoded.caps.len(), 2, "{scheme:?}");
    }
    marks[40 * w + 61] = f32::NAN;
    p0.p0.upload_f32(&marks).unwrap();
    // The encoders pass it on to the level each scheme reads first.
    for (scheme, pass) in [
        (Scheme::Hierarchical, "encode P2 -> P3 (4x4)"),
        (Scheme::Reduced, "encode P0 -> P1' (8x8)"),
        (Scheme::Full, "streaming AABB test (Table I)"),
    ] {
        let err = reduction.read(&ctx, &p0, scheme).unwrap_err().to_string();
        assert!(
            err.contains("collide: the CAP marks of P0")
                && err.contains(&format!("pass '{pass}'"))
                && err.contains("NaN"),
            "{scheme:?}: {err}"
        );
    }
}

/// Two crossing tori scaled by ~10^25 (here 2^83, and 2^-70, so that scaling is exact in
/// f32 and the geometry is the same): with the default options the pipeline reports exactly
/// the pairs of the unscaled tori (exact predicate, brute force). Möller's float test
/// answered 1048 pairs, 564 false, at 10^25.
#[test]
fn default_pipeline_reports_the_same_pairs_at_extreme_scales() {
    use classic_gpgpu::collide::scenes::Scene;
    let ctx = context();
    let scene = Scene::build("interlocking-tori", Some(800)).unwrap();
    let (px, py) = scene.frame(3);
    let (x, y) = (&scene.x.rest, &scene.y.rest);
    let want = all_pairs(x, &px, y, &py, Predicate::Exact);
    assert!(want.len() > 20, "{}", want.len());
    for scale in [1.0, 2f32.powi(83), 2f32.powi(-70)] {
        let (sx, sy): (Vec<Vec3>, Vec<Vec3>) = (
            px.iter().map(|p| *p * scale).collect(),
            py.iter().map(|p| *p * scale).collect(),
        );
        let (mx, my) = (
            Mesh::new(sx.clone(), x.triangles.clone()),
            Mesh::new(sy.clone(), y.triangles.clone()),
        );
        let options = Options {
            leaf_size: 8,
            ..Options::default()
        };
        let mut collider = StreamingCollider::new(&ctx, &mx, &my, options).unwrap();
        let got = collider.frame(&sx, &sy).unwrap();
        assert_eq!(got.pairs, want, "scale {scale:e}");
    }
}
