//! Lecture 1, penetration depth by rasterized Minkowski sums: the GPU's T buffer against the
//! CPU's per-ray exits texel by texel, the rasterized upper bound within the angular error of
//! the resolution, and the refined depth against the exact depth of convex pairs (and
//! parry3d's independent contact query) and against closed forms for unions; touching,
//! coplanar, separated and extremely scaled models; the compute counterpart against the
//! classic path; bad input refused with errors naming it.
//!
//! Tolerances. T is computed in fp32 in a unit frame (coordinates within [-1, 1]): a ray's
//! exit is a quotient of fp32 dot products, good to a few 1e-7; per texel the GPU and the CPU
//! (f64 on the same fp32 planes) agree within 1e-4 of the scene's scale except where a ray
//! grazes an edge between sums (the chain rule entry <= T decides differently within
//! rounding), so at least 98% of texels must agree. The rasterized bound is the exit along
//! the pixel ray nearest the true direction: for a nearest point inside a face, a ray at
//! angle θ exits no farther than depth / cos θ, and every direction is within the half
//! diagonal of a pixel, at most √2 / N radians, of a pixel's ray (the widest pixels are at a
//! face's centre, 2 / N wide); at a crease between sums the exit grows linearly with θ
//! instead, within depth · (1 + 2θ) for the creases here (two perpendicular faces). The
//! refinement is exact up to the tolerance of 1e-6 of the scale it states.

use classic_gpgpu::lecture1::penetration::minkowski::{minkowski_sums, Polytope};
use classic_gpgpu::lecture1::penetration::pieces::{pieces_of_meshes, pieces_of_obj, Piece};
use classic_gpgpu::lecture1::penetration::reference::{convex_depth, rounded_to_f32, t_buffer};
use classic_gpgpu::lecture1::penetration::scenes::{box_between, corner_pair, tetrahedron};
use classic_gpgpu::lecture1::penetration::{
    scaled, Formulation, Options, Penetration, PenetrationQuery,
};
use classic_gpgpu::mesh::{cuboid, Mesh};
use common::{classic_gpgpu, compute_context, context};
use glam::{DVec3, Vec3};

mod common;

fn pieces(name: &str, meshes: &[Mesh]) -> Vec<Piece> {
    pieces_of_meshes(name, meshes).unwrap()
}

fn run(query: &PenetrationQuery, a: &[Piece], b: &[Piece], n: usize) -> Penetration {
    query
        .run(
            a,
            b,
            &Options {
                resolution: n,
                formulation: Formulation::Classic,
                keep_exits: true,
            },
        )
        .unwrap()
}

/// Exact depth of a convex pair (one sum).
fn exact_convex(a: &[Piece], b: &[Piece]) -> (f64, DVec3) {
    let sums = minkowski_sums(a, b).unwrap();
    assert_eq!(sums.len(), 1);
    convex_depth(&sums[0], 1e-9).expect("the pair overlaps")
}

/// The bound of a nearest point inside a face: depth / cos(√2 / N), plus fp32.
fn face_bound(depth: f64, n: usize, scale: f64) -> f64 {
    depth / (2f64.sqrt() / n as f64).cos() + 1e-5 * scale
}

/// parry3d's contact query on two convex meshes: (depth, normal on A towards B).
fn parry_depth(a: &Mesh, b: &Mesh) -> (f64, DVec3) {
    use parry3d::math::{Pose, Vector3};
    use parry3d::shape::ConvexPolyhedron;
    let hull = |m: &Mesh| {
        let points: Vec<Vector3> = m
            .positions
            .iter()
            .map(|p| Vector3::new(p.x, p.y, p.z))
            .collect();
        ConvexPolyhedron::from_convex_hull(&points).unwrap()
    };
    let (ha, hb) = (hull(a), hull(b));
    let at = Pose::translation(0.0, 0.0, 0.0);
    let c = parry3d::query::contact(&at, &ha, &at, &hb, 0.0)
        .unwrap()
        .expect("parry finds the contact");
    let n = c.normal1;
    (
        -c.dist as f64,
        DVec3::new(n.x as f64, n.y as f64, n.z as f64),
    )
}

/// The T buffers of the GPU and the CPU agree texel by texel (see the module doc).
fn assert_t_buffers_agree(sums: &[Polytope], result: &Penetration, what: &str) {
    let n = result.resolution;
    let unit: Vec<Polytope> = sums.iter().map(|s| scaled(s, 1.0 / result.scale)).collect();
    let cpu = t_buffer(&rounded_to_f32(&unit), n);
    let gpu = result.exits.as_ref().expect("kept");
    assert_eq!(gpu.len(), cpu.len());
    let tolerance = 1e-4;
    let agree = gpu
        .iter()
        .zip(&cpu)
        .filter(|(g, c)| ((**g as f64 / result.scale) - **c as f64).abs() <= tolerance)
        .count();
    assert!(
        agree as f64 >= 0.98 * cpu.len() as f64,
        "{what}: {agree} of {} texels agree",
        cpu.len()
    );
    let cpu_min = cpu.iter().copied().fold(f32::INFINITY, f32::min) as f64 * result.scale;
    assert!(
        (cpu_min - result.rasterized_bound).abs() <= tolerance * result.scale,
        "{what}: smallest T {} on the GPU, {cpu_min} on the CPU",
        result.rasterized_bound
    );
}

#[test]
fn convex_boxes_match_the_exact_depth_and_parry() {
    let ctx = context();
    let query = PenetrationQuery::new(&ctx).unwrap();
    let a_mesh = box_between(Vec3::splat(-1.0), Vec3::splat(1.0));
    let b_mesh = cuboid(Vec3::new(0.5, 0.7, 0.3)).translated(Vec3::new(1.1, 0.2, -0.1));
    let (a, b) = (
        pieces("A", std::slice::from_ref(&a_mesh)),
        pieces("B", std::slice::from_ref(&b_mesh)),
    );
    let (exact, normal) = exact_convex(&a, &b);
    // B pokes 0.4 into A's +x face: move it 0.4 along +x.
    assert!((exact - 0.4).abs() < 1e-6, "{exact}");
    let (parry, parry_normal) = parry_depth(&a_mesh, &b_mesh);
    assert!((parry - exact).abs() < 1e-5, "parry {parry}, exact {exact}");
    assert!(parry_normal.dot(normal) > 0.9999);
    for n in [8, 16, 32] {
        let r = run(&query, &a, &b, n);
        assert!(r.overlap);
        assert!(r.upper_bound >= exact - 1e-6, "N {n}: {}", r.upper_bound);
        assert!(
            r.upper_bound <= face_bound(exact, n, 1.0),
            "N {n}: {}",
            r.upper_bound
        );
        assert!(
            (r.depth - exact).abs() < 1e-5,
            "N {n}: {} vs {exact}",
            r.depth
        );
        let d = DVec3::from_array(r.direction.unwrap());
        assert!(d.dot(normal) > 0.9999, "N {n}: {d}");
        assert_t_buffers_agree(&minkowski_sums(&a, &b).unwrap(), &r, "boxes");
    }
}

#[test]
fn tetrahedra_match_parry_and_the_cpu_t_buffer() {
    let ctx = context();
    let query = PenetrationQuery::new(&ctx).unwrap();
    let a_mesh = tetrahedron([
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(2.0, 0.1, 0.0),
        Vec3::new(0.3, 1.8, 0.2),
        Vec3::new(0.4, 0.5, 1.9),
    ]);
    let b_mesh = tetrahedron([
        Vec3::new(0.5, 0.4, 0.3),
        Vec3::new(1.6, 1.2, 0.8),
        Vec3::new(0.2, 1.5, 1.4),
        Vec3::new(1.3, -0.4, 1.1),
    ]);
    let (a, b) = (
        pieces("A", std::slice::from_ref(&a_mesh)),
        pieces("B", std::slice::from_ref(&b_mesh)),
    );
    let (exact, normal) = exact_convex(&a, &b);
    let (parry, parry_normal) = parry_depth(&a_mesh, &b_mesh);
    assert!(
        (parry - exact).abs() < 1e-4 * exact.max(1.0),
        "parry {parry}, exact {exact}"
    );
    assert!(parry_normal.dot(normal) > 0.999, "{parry_normal} {normal}");
    let r = run(&query, &a, &b, 24);
    assert!((r.depth - exact).abs() < 1e-5, "{} vs {exact}", r.depth);
    assert!(r.upper_bound <= face_bound(exact, 24, r.scale));
    assert_t_buffers_agree(&minkowski_sums(&a, &b).unwrap(), &r, "tetrahedra");
}

/// A pixel's ray through an edge shared by two back faces, one of whose other vertices
/// projects 400 pixels outside its cube face (found by a random search at N = 32). GL 3.3
/// section 3.6.1 requires exactly one of the two triangles to produce that fragment; softpipe
/// (Mesa 22.3) produces neither, so its T stays 0 there. The query must still be right: the
/// bound's point is checked against every sum in f64, and then every ray whose T lies inside
/// a sum takes its exit in f64, so the T buffer agrees everywhere and the bound is as tight as
/// without the loss.
#[test]
fn a_pixel_centre_on_a_long_shared_edge_is_still_right() {
    let ctx = context();
    let query = PenetrationQuery::new(&ctx).unwrap();
    let a_mesh = tetrahedron([
        Vec3::new(0.5754197, 0.3569799, 0.34134808),
        Vec3::new(0.34646365, 0.88578206, 0.5717152),
        Vec3::new(1.7797859, 0.5593571, 1.086653),
        Vec3::new(1.7902366, 1.8637482, 0.80537117),
    ]);
    let b_mesh = tetrahedron([
        Vec3::new(0.117673494, 0.81997633, 1.985052),
        Vec3::new(0.17743684, 1.8961915, 1.0865502),
        Vec3::new(1.4144318, 0.8770681, 0.023955368),
        Vec3::new(1.1495664, 0.9844303, 0.6012149),
    ]);
    let (a, b) = (pieces("A", &[a_mesh]), pieces("B", &[b_mesh]));
    let (exact, normal) = exact_convex(&a, &b);
    let r = run(&query, &a, &b, 32);
    assert!((r.depth - exact).abs() < 1e-5, "{} vs {exact}", r.depth);
    let direction = DVec3::from_array(r.direction.unwrap());
    assert!(direction.dot(normal) > 0.999, "{direction} {normal}");
    assert!(r.upper_bound <= face_bound(exact, 32, r.scale));
    let sums = minkowski_sums(&a, &b).unwrap();
    let unit: Vec<Polytope> = sums.iter().map(|s| scaled(s, 1.0 / r.scale)).collect();
    let cpu = t_buffer(&rounded_to_f32(&unit), 32);
    let differ = r
        .exits
        .as_ref()
        .unwrap()
        .iter()
        .zip(&cpu)
        .filter(|(g, c)| ((**g as f64 / r.scale) - **c as f64).abs() > 1e-4)
        .count();
    assert_eq!(
        differ, 0,
        "texels differ (corrected: {})",
        r.bound_corrected
    );
}

/// An L of two overlapping boxes (tall in z) and a small cube near its inner corner: the
/// nearest way out is over the re-entrant corner, a crease between the two sums, at
/// 0.15 √2 along (1, 1, 0) / √2.
#[test]
fn union_of_two_pieces_finds_the_reentrant_corner() {
    let ctx = context();
    let query = PenetrationQuery::new(&ctx).unwrap();
    let scene = corner_pair();
    let (a, b) = (scene.a, scene.b);
    let exact = 0.15 * 2f64.sqrt();
    assert_eq!(scene.closed_form, Some(exact));
    let along = DVec3::new(1.0, 1.0, 0.0).normalize();
    let sums = minkowski_sums(&a, &b).unwrap();
    // Each sum alone would give a smaller, wrong depth: the union matters.
    for s in &sums {
        assert!(convex_depth(s, 1e-9).unwrap().0 < exact - 0.01);
    }
    let n = 32;
    let r = run(&query, &a, &b, n);
    assert_eq!(r.pieces, [2, 1]);
    assert_eq!(r.sums, 2);
    assert!(
        r.passes >= 2,
        "the chain needs two raising passes: {}",
        r.passes
    );
    let theta = 2f64.sqrt() / n as f64;
    assert!(r.upper_bound >= exact - 1e-6);
    assert!(
        r.upper_bound <= exact * (1.0 + 2.0 * theta) + 1e-5 * r.scale,
        "{}",
        r.upper_bound
    );
    assert!((r.depth - exact).abs() < 1e-5, "{} vs {exact}", r.depth);
    assert!(DVec3::from_array(r.direction.unwrap()).dot(along) > 0.9999);
    assert_t_buffers_agree(&sums, &r, "L");
}

#[test]
fn touching_separated_and_coplanar() {
    let ctx = context();
    let query = PenetrationQuery::new(&ctx).unwrap();
    let a = pieces("A", &[box_between(Vec3::splat(-1.0), Vec3::splat(1.0))]);
    // Touching A's +x face from outside: depth 0 (within the tolerance).
    let touching = pieces(
        "B",
        &[box_between(
            Vec3::new(1.0, -0.5, -0.5),
            Vec3::new(2.0, 0.5, 0.5),
        )],
    );
    let r = run(&query, &a, &touching, 16);
    assert!(r.depth <= r.tolerance, "{}", r.depth);
    // Apart: no overlap, depth 0, no direction, T zero everywhere.
    let apart = pieces(
        "B",
        &[box_between(
            Vec3::new(1.5, -0.5, -0.5),
            Vec3::new(2.0, 0.5, 0.5),
        )],
    );
    let r = run(&query, &a, &apart, 16);
    assert!(!r.overlap);
    assert_eq!(r.depth, 0.0);
    assert!(r.direction.is_none());
    assert!(r.exits.as_ref().unwrap().iter().all(|&t| t == 0.0));
    // B's top face coplanar with A's, B half inside through +x: 0.5 along +x.
    let b_mesh = box_between(Vec3::new(0.5, -0.5, 0.0), Vec3::new(1.5, 0.5, 1.0));
    let b = pieces("B", std::slice::from_ref(&b_mesh));
    let (exact, _) = exact_convex(&a, &b);
    assert!((exact - 0.5).abs() < 1e-6);
    let (parry, _) = parry_depth(&box_between(Vec3::splat(-1.0), Vec3::splat(1.0)), &b_mesh);
    assert!((parry - exact).abs() < 1e-5);
    let r = run(&query, &a, &b, 16);
    assert!((r.depth - 0.5).abs() < 1e-5, "{}", r.depth);
    assert!(DVec3::from_array(r.direction.unwrap()).dot(DVec3::X) > 0.9999);
    assert_t_buffers_agree(&minkowski_sums(&a, &b).unwrap(), &r, "coplanar");
}

#[test]
fn extreme_scales_scale_the_depth() {
    let ctx = context();
    let query = PenetrationQuery::new(&ctx).unwrap();
    let a = box_between(Vec3::new(0.0, 0.0, -1.0), Vec3::new(3.0, 1.0, 1.0));
    let a2 = box_between(Vec3::new(0.0, 0.0, -1.0), Vec3::new(1.0, 3.0, 1.0));
    let b = tetrahedron([
        Vec3::new(0.6, 0.6, -0.3),
        Vec3::new(1.3, 0.7, 0.0),
        Vec3::new(0.7, 1.3, 0.1),
        Vec3::new(0.8, 0.8, 0.5),
    ]);
    let at = |s: f32| {
        let m = |x: &Mesh| x.scaled(Vec3::splat(s));
        run(
            &query,
            &pieces("A", &[m(&a), m(&a2)]),
            &pieces("B", &[m(&b)]),
            16,
        )
    };
    let unit = at(1.0);
    assert!(unit.depth > 0.0);
    for s in [1e-3f32, 1e4] {
        let r = at(s);
        let expected = unit.depth * s as f64;
        assert!(
            (r.depth - expected).abs() <= 1e-5 * expected,
            "scale {s}: {} vs {expected}",
            r.depth
        );
        let d = DVec3::from_array(r.direction.unwrap());
        assert!(d.dot(DVec3::from_array(unit.direction.unwrap())) > 0.9999);
    }
}

#[test]
fn compute_matches_the_classic_path() {
    let (ctx, has_compute) = compute_context();
    let query = PenetrationQuery::new(&ctx).unwrap();
    let a = pieces(
        "L",
        &[
            box_between(Vec3::new(0.0, 0.0, -2.0), Vec3::new(3.0, 1.0, 2.0)),
            box_between(Vec3::new(0.0, 0.0, -2.0), Vec3::new(1.0, 3.0, 2.0)),
        ],
    );
    let b = pieces(
        "B",
        &[tetrahedron([
            Vec3::new(0.6, 0.6, -0.3),
            Vec3::new(1.3, 0.7, 0.0),
            Vec3::new(0.7, 1.3, 0.1),
            Vec3::new(0.8, 0.8, 0.5),
        ])],
    );
    let options = |formulation| Options {
        resolution: 16,
        formulation,
        keep_exits: true,
    };
    let classic = query.run(&a, &b, &options(Formulation::Classic)).unwrap();
    let compute = query.run(&a, &b, &options(Formulation::Compute));
    if !has_compute {
        let e = format!("{:#}", compute.unwrap_err());
        assert!(e.contains("4.3"), "{e}");
        return;
    }
    let compute = compute.unwrap();
    assert_eq!(compute.passes, 0);
    assert!(!classic.bound_corrected && !compute.bound_corrected);
    let (c, g) = (classic.exits.unwrap(), compute.exits.unwrap());
    let agree = c
        .iter()
        .zip(&g)
        .filter(|(x, y)| (**x - **y).abs() <= 1e-4 * classic.scale as f32)
        .count();
    assert!(
        agree as f64 >= 0.98 * c.len() as f64,
        "{agree} of {}",
        c.len()
    );
    assert!((classic.upper_bound - compute.upper_bound).abs() <= 1e-4 * classic.scale);
    assert!((classic.depth - compute.depth).abs() <= 1e-6 * classic.scale);
}

#[test]
fn bad_pieces_are_refused_by_name() {
    // An L-shaped prism in one group: not convex.
    let l_prism = "o elbow\n\
        v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n\
        v 0 0 1\nv 2 0 1\nv 2 1 1\nv 1 1 1\nv 1 2 1\nv 0 2 1\n\
        f 1 6 5 4 3 2\nf 7 8 9 10 11 12\n\
        f 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 12\n";
    let e = format!("{:#}", pieces_of_obj(l_prism, "l.obj").unwrap_err());
    assert!(e.contains("'elbow'") && e.contains("not convex"), "{e}");
    // A box with a face missing: not closed.
    let open = "g lid\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
        f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    let e = format!("{:#}", pieces_of_obj(open, "open.obj").unwrap_err());
    assert!(e.contains("'lid'") && e.contains("closed"), "{e}");
    // Two groups, each a closed box: two pieces, named.
    let two = "o left\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
        f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n\
        o right\nv 2 0 0\nv 3 0 0\nv 3 1 0\nv 2 1 0\nv 2 0 1\nv 3 0 1\nv 3 1 1\nv 2 1 1\n\
        f 9 12 11 10\nf 13 14 15 16\nf 9 10 14 13\nf 10 11 15 14\nf 11 12 16 15\nf 12 9 13 16\n";
    let p = pieces_of_obj(two, "two.obj").unwrap();
    assert_eq!(
        p.iter().map(|p| p.name.as_str()).collect::<Vec<_>>(),
        ["left", "right"]
    );
    assert!(p.iter().all(|p| p.mesh.triangles.len() == 12));
    // Not finite, empty.
    let nan = "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    assert!(pieces_of_obj(nan, "nan.obj").is_err());
    assert!(pieces_of_obj("# nothing\n", "empty.obj").is_err());
}

#[test]
fn cli_prints_json_and_refuses_bad_models() {
    let dir = std::env::temp_dir().join(format!("classic-gpgpu-pd-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let a = dir.join("a.obj");
    let b = dir.join("b.obj");
    let box_obj = |lo: [f32; 3], hi: [f32; 3]| {
        classic_gpgpu::mesh::to_obj_string(
            &box_between(Vec3::from_array(lo), Vec3::from_array(hi)),
            "",
        )
    };
    std::fs::write(&a, box_obj([-1.0; 3], [1.0; 3])).unwrap();
    std::fs::write(&b, box_obj([0.75, -0.5, -0.5], [2.0, 0.5, 0.5])).unwrap();
    let png = dir.join("t.png");
    let args = [
        "lecture1",
        "penetration",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--resolution",
        "8",
        "--png",
        png.to_str().unwrap(),
        "--json",
    ];
    let v = common::json_of(&args);
    assert!((v["depth"].as_f64().unwrap() - 0.25).abs() < 1e-5, "{v}");
    assert_eq!(v["resolution"], 8);
    let d = v["direction"].as_array().unwrap();
    assert!((d[0].as_f64().unwrap() - 1.0).abs() < 1e-6, "{v}");
    assert!(png.exists());
    // The picture exists now: refused without --force, nothing changed.
    let out = classic_gpgpu(&args);
    assert!(!out.status.success());
    // A non-convex model: an error naming the piece.
    let l = dir.join("l.obj");
    std::fs::write(
        &l,
        "o elbow\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n\
         v 0 0 1\nv 2 0 1\nv 2 1 1\nv 1 1 1\nv 1 2 1\nv 0 2 1\n\
         f 1 6 5 4 3 2\nf 7 8 9 10 11 12\n\
         f 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 12\n",
    )
    .unwrap();
    let out = classic_gpgpu(&[
        "lecture1",
        "penetration",
        l.to_str().unwrap(),
        b.to_str().unwrap(),
        "--json",
    ]);
    assert!(!out.status.success());
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("elbow") && e.contains("not convex"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The report's measurement: quick resolutions, both scenes; the bound never below the exact
/// depth, its error shrinking as the resolution grows, the refined depth exact.
#[test]
fn report_measures_error_by_resolution() {
    use classic_gpgpu::report::lecture1::penetration::{figure, measure, table};
    let ctx = context();
    let dir = std::env::temp_dir().join(format!("classic-gpgpu-pd-report-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let opts = classic_gpgpu::report::BenchOptions {
        gl: &ctx,
        quick: true,
        out_dir: dir.clone(),
        progress: indicatif::MultiProgress::with_draw_target(
            indicatif::ProgressDrawTarget::hidden(),
        ),
        runs: None,
    };
    let errors = measure(&opts).unwrap();
    assert_eq!(errors.rows.len(), 6);
    for scene in errors.rows.chunks(3) {
        for row in scene {
            assert!(row.bound_error >= -1e-6, "{row:?}");
            assert!(row.refined_error < 1e-5, "{row:?}");
        }
        assert!(scene[2].bound_error < scene[0].bound_error, "{scene:?}");
    }
    assert_eq!(table(&errors).rows.len(), 6);
    let f = figure(&opts, &errors).unwrap();
    assert!(dir.join(&f.file).exists());
    let _ = std::fs::remove_dir_all(&dir);
}
