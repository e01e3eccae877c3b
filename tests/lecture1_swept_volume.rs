//! Lecture 1, swept volumes (a reconstruction of Kim, Varadhan, Lin & Manocha 2003): the
//! volume of the extracted boundary converges to the exact swept volume as the resolution
//! grows (a convex polytope under pure translation sweeps exactly hull(start ∪ end), whose
//! volume is computed here from the model's faces), a rotation sweeps the expected cylinder,
//! the path's interpolation and checks, the primitives within ε, the exact segment test, and
//! the command's output.

use classic_gpgpu::lecture1::swept_volume::classify::segment_meets_triangle;
use classic_gpgpu::lecture1::swept_volume::features::feature_point;
use classic_gpgpu::lecture1::swept_volume::path::{Keyframe, Path3};
use classic_gpgpu::lecture1::swept_volume::primitives::{edges, primitives};
use classic_gpgpu::lecture1::swept_volume::topology::{analyse, of_mesh};
use classic_gpgpu::lecture1::swept_volume::{sweep, Options, SweptVolume, DEFAULT_POSES};
use classic_gpgpu::mesh::generate::{cube, cuboid, torus_closed, uv_sphere};
use classic_gpgpu::mesh::{parse_obj, to_obj_string, Mesh};
use common::{classic_gpgpu, context, json_of, soup};
use glam::{DQuat, DVec3, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod common;

fn keyframe(t: DVec3, q: DQuat) -> Keyframe {
    Keyframe {
        translation: t.to_array(),
        rotation: [q.w, q.x, q.y, q.z],
    }
}

fn translation(v: DVec3) -> Path3 {
    Path3::new(&[
        keyframe(DVec3::ZERO, DQuat::IDENTITY),
        keyframe(v, DQuat::IDENTITY),
    ])
    .unwrap()
}

/// A tetrahedron with no face parallel to an axis, outward faces.
fn tetrahedron() -> Mesh {
    Mesh::new(
        vec![
            Vec3::new(0.1, -0.2, 0.0),
            Vec3::new(1.2, 0.1, 0.2),
            Vec3::new(0.3, 1.0, -0.1),
            Vec3::new(0.4, 0.3, 1.1),
        ],
        vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
    )
}

/// The exact volume swept by convex `mesh` translated by `v`: hull(P ∪ (P + v)) has volume
/// vol(P) + |v| area(shadow of P along v), and the shadow's area is half the sum over the
/// faces of |area vector · v̂|.
fn convex_translation_volume(mesh: &Mesh, v: DVec3) -> f64 {
    let shadow: f64 = (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.triangle(t).map(|p| p.as_dvec3());
            0.5 * (b - a).cross(c - a).dot(v.normalize()).abs()
        })
        .sum::<f64>()
        * 0.5;
    mesh.signed_volume() + v.length() * shadow
}

/// A bound on the length of the swept hull's sharp edges: they are among the model's sharp
/// edges (two faces at an angle) at the start and at the end and its vertices' straight
/// paths. Surface nets round a sharp edge off by at most about a voxel's square of volume per
/// unit of length, which bounds the error (faces are placed exactly: the signed field is
/// exact for a plane).
fn sharp_edge_length(mesh: &Mesh, v: DVec3) -> f64 {
    let normals = mesh.face_normals();
    let sharp: f64 = edges(mesh)
        .iter()
        .filter(|&&[a, b]| {
            let faces: Vec<Vec3> = mesh
                .triangles
                .iter()
                .zip(&normals)
                .filter(|(t, _)| t.contains(&a) && t.contains(&b))
                .map(|(_, n)| *n)
                .collect();
            faces.windows(2).any(|f| f[0].dot(f[1]) < 1.0 - 1e-6)
        })
        .map(|&[a, b]| (mesh.positions[a as usize] - mesh.positions[b as usize]).length() as f64)
        .sum();
    2.0 * sharp + mesh.positions.len() as f64 * v.length()
}

fn run(mesh: &Mesh, path: &Path3, n: usize, poses: usize) -> SweptVolume {
    let ctx = context();
    sweep(
        &ctx,
        mesh,
        path,
        Options {
            resolution: n,
            poses,
            epsilon: None,
        },
    )
    .unwrap()
}

/// The floor under which a volume error is not the resolution's: the primitives' positions
/// are fp32 (relative rounding 6e-8, a few hundred of them summed), and a feature vertex that
/// shares its place with another is drawn into its own tetrahedron by
/// `features::TETRAHEDRON_DEPTH` of a cell (so that the mesh is a 2-manifold by position),
/// which moves the volume by about that fraction of a cell's volume per vertex moved: with a
/// few dozen such vertices at the models' corners, up to a few 1e-5 of these models' volumes.
fn rounding_floor(exact: f64) -> f64 {
    5e-5 * exact
}

/// The volume's relative error at each resolution, each within `bound(spacing)` (relative),
/// the surface a closed 2-manifold of `chi`; and the error falls at every step until it
/// reaches the rounding floor.
fn falls_with_resolution(
    mesh: &Mesh,
    path: &Path3,
    poses: usize,
    exact: f64,
    resolutions: &[usize],
    bound: impl Fn(f64) -> f64,
    chi: i64,
) {
    let mut errors = Vec::new();
    for &n in resolutions {
        let swept = run(mesh, path, n, poses);
        let error = (swept.surface.volume - exact).abs() / exact;
        let bound = bound(swept.grid.spacing);
        eprintln!(
            "n = {n}: volume {} (exact {exact}), relative error {error:.3e}, bound {bound:.3e}, \
             {} feature vertices, {} flips",
            swept.surface.volume, swept.surface.feature_vertices, swept.surface.feature_flips
        );
        assert!(
            swept.surface.watertight(),
            "n = {n}: the surface is not watertight"
        );
        assert_eq!(
            swept.surface.topology.euler_characteristic,
            Some(chi),
            "n = {n}: {:?}",
            swept.surface.topology
        );
        assert!(error <= bound, "n = {n}: error {error} above {bound}");
        errors.push(error);
    }
    let floor = rounding_floor(1.0);
    for (k, pair) in errors.windows(2).enumerate() {
        assert!(
            pair[1] < pair[0] || pair[1] <= floor,
            "the error did not fall from n = {} to n = {}: {errors:?}",
            resolutions[k],
            resolutions[k + 1]
        );
    }
}

/// A convex model translated by `v`: within the sharp-edge bound at each resolution, falling.
fn converges(mesh: &Mesh, v: DVec3, resolutions: &[usize]) {
    let exact = convex_translation_volume(mesh, v);
    let bound = |h: f64| sharp_edge_length(mesh, v) * h * h / exact;
    falls_with_resolution(mesh, &translation(v), 2, exact, resolutions, bound, 2);
}

#[test]
fn a_translated_cube_converges_to_one_plus_d() {
    let mesh = cube(1.0);
    let v = DVec3::new(1.5, 0.0, 0.0);
    assert!((convex_translation_volume(&mesh, v) - 2.5).abs() < 1e-6);
    // The report's case; without its sharp edges kept, n = 24 was four times worse than 16.
    converges(&mesh, v, &[16, 20, 24, 32]);
}

#[test]
fn a_translated_tetrahedron_converges_to_its_hull() {
    converges(&tetrahedron(), DVec3::new(0.8, 0.5, 0.3), &[20, 28, 40]);
}

#[test]
fn a_translated_polyhedral_sphere_converges_to_its_hull() {
    // Its facets meet at 22.5 degrees: shallow sharp edges, many of them in one cell.
    converges(
        &uv_sphere(0.6, 16, 8),
        DVec3::new(0.9, -0.4, 0.3),
        &[16, 24, 32, 40],
    );
}

#[test]
fn a_turning_cube_converges_to_its_sampled_sweep() {
    // A unit cube turning a quarter turn about z through its centre, K poses: its corners
    // land on 4 (K - 1) equally spaced points of the circle of radius sqrt(2)/2, and the
    // ruled quads of its vertical edges join them, so the sampled sweep is exactly the
    // regular 4 (K - 1)-gon on that circle times the height: (K - 1) sin(pi / (2 (K - 1))).
    let k = 9;
    let path = quarter_turn_about_z();
    let sides = (k - 1) as f64;
    let exact = sides * (std::f64::consts::PI / (2.0 * sides)).sin();
    // Its sharp edges: the two caps' rims (the polygon's perimeter, under 2 pi r each).
    let bound = |h: f64| 2.0 * std::f64::consts::TAU * 0.75 * h * h / exact;
    falls_with_resolution(&cube(1.0), &path, k, exact, &[16, 24, 32], bound, 2);
}

#[test]
fn feature_points_meet_the_tangent_planes() {
    // Three faces of a box corner at (1, 2, 3): their planes meet at the corner.
    let corner = DVec3::new(1.0, 2.0, 3.0);
    let points = [
        corner + DVec3::new(-0.3, -0.2, 0.0),
        corner + DVec3::new(0.0, -0.4, -0.1),
        corner + DVec3::new(-0.2, 0.0, -0.3),
    ];
    let normals = [DVec3::Z, DVec3::X, DVec3::Y];
    let f = feature_point(&points, &normals).unwrap();
    assert!((f - corner).length() < 1e-12, "{f}");
    // Two planes (x = 1 and y = 2) leave z free: the point on their line nearest the
    // crossings' centroid.
    let points = [DVec3::new(1.0, 1.5, 0.2), DVec3::new(0.6, 2.0, 0.6)];
    let f = feature_point(&points, &[DVec3::X, DVec3::Y]).unwrap();
    assert!((f - DVec3::new(1.0, 2.0, 0.4)).length() < 1e-12, "{f}");
    // Normals 2 degrees apart are one flat sheet: no feature; 10 degrees apart, an edge.
    let tilted = |deg: f64| DVec3::new(0.0, deg.to_radians().sin(), deg.to_radians().cos());
    assert!(feature_point(&points, &[DVec3::Z, tilted(2.0)]).is_none());
    assert!(feature_point(&points, &[DVec3::Z, tilted(10.0)]).is_some());
}

/// The swept surface's topology: `V - E + F` and the genus, checked to be a manifold.
fn euler_and_genus(mesh: &Mesh, path: &Path3, n: usize, poses: usize) -> (i64, i64) {
    let swept = run(mesh, path, n, poses);
    let t = &swept.surface.topology;
    assert!(t.is_manifold(), "n = {n}: {t:?}");
    assert_eq!(t.components, 1, "{t:?}");
    (t.euler_characteristic.unwrap(), t.genus.unwrap())
}

#[test]
fn a_sphere_along_a_line_sweeps_a_sphere_topologically() {
    let sphere = uv_sphere(0.5, 12, 8);
    let path = translation(DVec3::new(1.0, 0.4, 0.2));
    assert_eq!(euler_and_genus(&sphere, &path, 28, 2), (2, 0));
}

#[test]
fn a_ring_moved_along_its_axis_sweeps_a_torus() {
    // Major radius 1, tube radius 0.3: the hole (radius 0.7) stays open, many voxels wide.
    let ring = torus_closed(1.0, 0.3, 24, 8);
    let path = translation(DVec3::new(0.1, 0.0, 0.5));
    assert_eq!(euler_and_genus(&ring, &path, 36, 2), (0, 1));
}

#[test]
fn a_cube_around_a_closed_loop_sweeps_a_solid_torus() {
    // A cube of edge 0.5 carried around a circle of radius 1.5 and back to its start: its
    // boundary is a torus.
    let frames: Vec<Keyframe> = (0..=12)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 12.0;
            keyframe(1.5 * DVec3::new(a.cos(), a.sin(), 0.0), DQuat::IDENTITY)
        })
        .collect();
    let path = Path3::new(&frames).unwrap();
    assert_eq!(euler_and_genus(&cube(0.5), &path, 40, 25), (0, 1));
}

#[test]
fn topology_is_reported_only_for_a_manifold() {
    // A closed sphere and torus: 2 and 0.
    let s = uv_sphere(1.0, 8, 5);
    let t = analyse(&s.triangles, s.positions.len());
    assert_eq!((t.euler_characteristic, t.genus), (Some(2), Some(0)));
    let r = torus_closed(1.0, 0.3, 8, 5);
    let t = analyse(&r.triangles, r.positions.len());
    assert_eq!((t.euler_characteristic, t.genus), (Some(0), Some(1)));
    // Two cubes apart: two spheres, V - E + F = 4, genus 0.
    let two = |shift: Vec3, share: bool| {
        let a = cube(1.0);
        let mut positions = a.positions.clone();
        let offset = positions.len() as u32;
        positions.extend(a.positions.iter().map(|p| *p + shift));
        let mut triangles = a.triangles.clone();
        triangles.extend(a.triangles.iter().map(|t| t.map(|v| v + offset)));
        if share {
            // Weld the second cube's corner 0 (at -0.5 + shift) onto the first's corner 7.
            let corner = |i: u32| (offset + i, 7);
            let (from, to) = corner(0);
            for t in &mut triangles {
                for v in t.iter_mut() {
                    if *v == from {
                        *v = to;
                    }
                }
            }
        }
        analyse(&triangles, positions.len())
    };
    let apart = two(Vec3::splat(3.0), false);
    assert_eq!(apart.components, 2);
    assert_eq!(
        (apart.euler_characteristic, apart.genus),
        (Some(4), Some(0))
    );
    // Touching at one vertex: every edge still has two triangles, but the vertex's
    // triangles make two fans, so no Euler characteristic is given.
    let pinched = two(Vec3::splat(1.0), true);
    assert_eq!(pinched.non_manifold_edges, 0);
    assert_eq!(pinched.non_manifold_vertices, 1);
    assert!(!pinched.is_manifold());
    assert_eq!(pinched.euler_characteristic, None);
    // Three triangles on one edge, an open surface, a flipped triangle: none is a manifold.
    let fin = [[0, 1, 2], [1, 0, 3], [0, 1, 4]];
    assert_eq!(analyse(&fin, 5).non_manifold_edges, 1);
    let mut open = s.triangles.clone();
    open.pop();
    assert!(analyse(&open, s.positions.len()).boundary_edges > 0);
    let mut flipped = s.triangles.clone();
    flipped[0].swap(1, 2);
    let t = analyse(&flipped, s.positions.len());
    assert!(t.misoriented_edges > 0 && t.euler_characteristic.is_none());
}

#[test]
fn a_quarter_turn_sweeps_a_cylinder() {
    // A unit cube turning a quarter turn about the z axis through its centre sweeps the disk
    // of radius sqrt(2)/2 (the corners' circle) times its height: pi / 2.
    let path = quarter_turn_about_z();
    let swept = run(&cube(1.0), &path, 40, 17);
    let exact = std::f64::consts::FRAC_PI_2;
    let error = (swept.surface.volume - exact).abs() / exact;
    assert!(error < 0.03, "volume {} vs {exact}", swept.surface.volume);
    assert!(swept.surface.watertight());
    assert_eq!(swept.surface.topology.euler_characteristic, Some(2));
    assert!(swept.primitives.ruled_triangles > 0);
}

#[test]
fn a_model_at_rest_is_its_own_volume() {
    let path = Path3::new(&[keyframe(DVec3::new(3.0, -2.0, 1.0), DQuat::IDENTITY)]).unwrap();
    let swept = run(&cube(1.0), &path, 32, 1);
    assert!(
        (swept.surface.volume - 1.0).abs() < 12.0 * swept.grid.spacing.powi(2),
        "{}",
        swept.surface.volume
    );
}

#[test]
fn the_path_interpolates_and_checks_its_keyframes() {
    let q = DQuat::from_rotation_y(1.0);
    let path = Path3::new(&[
        keyframe(DVec3::ZERO, DQuat::IDENTITY),
        keyframe(DVec3::new(2.0, 0.0, 0.0), q),
        keyframe(DVec3::new(2.0, 4.0, 0.0), q),
    ])
    .unwrap();
    let mid = path.at(0.25);
    assert!((mid.translation - DVec3::new(1.0, 0.0, 0.0)).length() < 1e-12);
    assert!(mid.rotation.angle_between(DQuat::from_rotation_y(0.5)) < 1e-9);
    let late = path.at(0.75);
    assert!((late.translation - DVec3::new(2.0, 2.0, 0.0)).length() < 1e-12);
    let poses = path.sample(5);
    assert_eq!(poses.len(), 5);
    assert_eq!(poses[4].translation, DVec3::new(2.0, 4.0, 0.0));
    // A quaternion that is not of unit length is refused, not normalised.
    let err = Path3::parse(
        r#"[{"translation": [0, 0, 0], "rotation": [1, 0, 0, 0]},
            {"translation": [1, 0, 0], "rotation": [2, 0, 0, 0]}]"#,
    )
    .unwrap_err();
    assert!(format!("{err:#}").contains("keyframe 1"), "{err:#}");
    assert!(Path3::parse("[]").is_err());
    assert!(Path3::parse(r#"[{"translation": [0, 0], "rotation": [1, 0, 0, 0]}]"#).is_err());
}

#[test]
fn ruled_quads_are_within_epsilon() {
    // A unit square edge turning half a turn: a twisted quad, split finely enough.
    let mesh = Mesh::new(
        vec![Vec3::ZERO, Vec3::X, Vec3::new(0.0, 1.0, 0.0)],
        vec![[0, 1, 2]],
    );
    let path = Path3::new(&[
        keyframe(DVec3::ZERO, DQuat::IDENTITY),
        keyframe(
            DVec3::Z,
            DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
        ),
    ])
    .unwrap();
    let poses = path.sample(2);
    let epsilon = 0.01;
    let p = primitives(&mesh, &poses, epsilon).unwrap();
    assert_eq!(p.face_triangles, 2);
    let m = p.most_splits;
    assert_eq!(p.ruled_triangles, 3 * 2 * m * m);
    // A cell's two triangles are within |twist| / (4 m^2) of the bilinear quad: m is the
    // smallest split that brings the most twisted edge's quad within ε.
    let corner = |pose: usize, v: u32| poses[pose].apply(mesh.positions[v as usize].as_dvec3());
    let twist = edges(&mesh)
        .iter()
        .map(|&[a, b]| (corner(0, a) - corner(0, b) - corner(1, a) + corner(1, b)).length())
        .fold(0.0, f64::max);
    assert!(twist / (4.0 * (m * m) as f64) <= epsilon);
    assert!(twist / (4.0 * ((m - 1) * (m - 1)) as f64) > epsilon);
    assert!(primitives(&mesh, &poses, 0.0).is_err());
}

#[test]
fn segments_meet_triangles_exactly() {
    let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
    let z = |x: f64, y: f64, z0: f64, z1: f64| (DVec3::new(x, y, z0), DVec3::new(x, y, z1));
    let (p, q) = z(0.2, 0.2, -1.0, 1.0);
    assert!(segment_meets_triangle(p, q, t));
    let (p, q) = z(0.7, 0.7, -1.0, 1.0); // beyond the hypotenuse
    assert!(!segment_meets_triangle(p, q, t));
    let (p, q) = z(0.5, 0.5, -1.0, 1.0); // on the hypotenuse: touching counts
    assert!(segment_meets_triangle(p, q, t));
    let (p, q) = z(0.2, 0.2, 0.5, 1.0); // above it
    assert!(!segment_meets_triangle(p, q, t));
    let (p, q) = z(0.2, 0.2, 0.0, 1.0); // ends on it
    assert!(segment_meets_triangle(p, q, t));
}

#[test]
fn swept_volume_command_reports_and_refuses() {
    let dir = std::env::temp_dir().join(format!("lecture1-swept-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("cube.obj");
    classic_gpgpu::mesh::write_obj(&cube(1.0), &model).unwrap();
    let path = dir.join("path.json");
    std::fs::write(
        &path,
        r#"[{"translation": [0, 0, 0], "rotation": [1, 0, 0, 0]},
            {"translation": [1, 0.5, 0], "rotation": [1, 0, 0, 0]}]"#,
    )
    .unwrap();
    let out = dir.join("swept.obj");
    let _ = std::fs::remove_file(&out);
    let args = [
        "--json",
        "lecture1",
        "swept-volume",
        model.to_str().unwrap(),
        "--path",
        path.to_str().unwrap(),
        "--resolution",
        "24",
        "--out",
        out.to_str().unwrap(),
        "--poses",
        "2",
    ];
    let report = json_of(&args);
    assert_eq!(report["resolution"], 24);
    assert_eq!(report["euler_characteristic"], 2);
    assert_eq!(report["genus"], 0);
    assert_eq!(report["manifold"], true);
    let volume = report["volume"].as_f64().unwrap();
    // The written mesh encloses the reported volume.
    let written = classic_gpgpu::mesh::load_obj(&out).unwrap();
    assert!((written.signed_volume() - volume).abs() < 1e-3 * volume);
    let exact = convex_translation_volume(&cube(1.0), DVec3::new(1.0, 0.5, 0.0));
    assert!((volume - exact).abs() < 0.1 * exact, "{volume} vs {exact}");
    // The output exists now: refused without --force.
    let again = classic_gpgpu(&args);
    assert!(!again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("--force"));
    // A non-unit quaternion: a clear error naming the file and the keyframe.
    std::fs::write(
        &path,
        r#"[{"translation": [0, 0, 0], "rotation": [0.5, 0, 0, 0]}]"#,
    )
    .unwrap();
    let mut forced = args.to_vec();
    forced.push("--force");
    let bad = classic_gpgpu(&forced);
    assert!(!bad.status.success());
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(
        err.contains("path.json") && err.contains("keyframe 0"),
        "{err}"
    );
}

#[test]
fn report_blocks_render() {
    use classic_gpgpu::report::lecture1::{distance_field, swept_volume, Setting};
    use classic_gpgpu::report::BenchOptions;
    use classic_gpgpu::timing::Runs;
    let ctx = context();
    let dir = common::temp_dir("lecture1", "report");
    let opts = BenchOptions {
        gl: &ctx,
        quick: true,
        out_dir: dir.clone(),
        progress: indicatif::MultiProgress::with_draw_target(
            indicatif::ProgressDrawTarget::hidden(),
        ),
        runs: Some(1),
    };
    let setting = Setting {
        opts: &opts,
        runs: Runs::exactly(1),
        renderer: ctx.info().renderer_line(),
        software: ctx.info().is_software(),
    };
    let field = distance_field::block(&setting).unwrap();
    let rows = field.results.as_array().unwrap();
    // Exact methods at fp32 rounding, distance meshes within their tessellation bound.
    for r in rows {
        let bound = r["tessellation_bound"].as_f64().map_or(1e-3, |b| b + 1e-2);
        assert!(r["max_error_voxels"].as_f64().unwrap() < bound, "{r}");
    }
    assert!(rows
        .iter()
        .any(|r| r["tessellation_bound"].as_f64().is_some()));
    let swept = swept_volume::block(&setting).unwrap();
    let swept_rows = swept.results.as_array().unwrap();
    let mut cases: Vec<&str> = swept_rows
        .iter()
        .map(|r| r["case"].as_str().unwrap())
        .collect();
    cases.dedup();
    assert_eq!(cases.len(), 3, "{cases:?}");
    for case in cases {
        let errors: Vec<f64> = swept_rows
            .iter()
            .filter(|r| r["case"] == case)
            .map(|r| r["relative_error"].as_f64().unwrap())
            .collect();
        // Falling at every step, or already at the fp32 rounding floor.
        assert!(
            errors
                .windows(2)
                .all(|e| e[1] < e[0] || e[1] <= rounding_floor(1.0)),
            "{case}: {errors:?}"
        );
    }
    for block in [&field, &swept] {
        assert_eq!(block.tables.len(), 1);
        assert!(!block.tables[0].rows.is_empty());
        for f in &block.figures {
            assert!(dir.join(&f.file).exists(), "{}", f.file);
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A quarter turn about the z axis through the origin, in one step.
fn quarter_turn_about_z() -> Path3 {
    Path3::new(&[
        keyframe(DVec3::ZERO, DQuat::IDENTITY),
        keyframe(
            DVec3::ZERO,
            DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
        ),
    ])
    .unwrap()
}

/// The surface as the command writes it (an OBJ, read back): a closed 2-manifold by position
/// (after welding equal positions every edge has two opposite triangles and every vertex one
/// fan) with no degenerate triangle, and the topology the sweep reported is that of this mesh.
/// Its `V - E + F`.
fn written_manifold(swept: &SweptVolume, what: &str) -> i64 {
    let text = to_obj_string(&swept.surface.mesh, "");
    let mesh = parse_obj(&text, what).unwrap();
    let report = mesh.validate();
    assert_eq!(report.degenerate_triangles(), 0, "{what}: {report}");
    let closed = report.closedness.as_ref().unwrap();
    assert!(closed.is_closed(), "{what}: {report}");
    let t = of_mesh(&mesh);
    assert!(t.is_manifold(), "{what}: {t:?}");
    assert_eq!(t.vertices, closed.welded_vertices, "{what}");
    assert_eq!(
        t.euler_characteristic, swept.surface.topology.euler_characteristic,
        "{what}: the reported topology is not the written mesh's"
    );
    t.euler_characteristic.unwrap()
}

/// Relative volume error within the sharp-edge bound (see `sharp_edge_length`) for a convex
/// `mesh` translated by `v`.
fn check_translated_volume(mesh: &Mesh, v: DVec3, swept: &SweptVolume, what: &str) {
    let exact = convex_translation_volume(mesh, v);
    let h = swept.grid.spacing;
    let error = (swept.surface.volume - exact).abs() / exact;
    let bound = sharp_edge_length(mesh, v) * h * h / exact;
    assert!(
        error <= bound,
        "{what}: volume {} vs exact {exact}: relative error {error:.3e} above {bound:.3e}",
        swept.surface.volume
    );
}

#[test]
fn the_reported_translations_of_a_cube_are_closed_manifolds() {
    // Issue 43: these failed with "the signed field has a zero or non-finite value" (voxel
    // centres on the diagonal ruled quads) at the command's defaults (17 poses).
    let cube = cube(1.0);
    let cases = [
        (DVec3::new(1.0, 1.0, 0.0), 64),
        (DVec3::new(0.6, 0.3, 0.2), 40),
        (DVec3::new(0.6, 0.3, 0.2), 48),
        (DVec3::new(0.6, 0.3, 0.2), 64),
        (DVec3::new(1.0, 0.7, 0.3), 48),
    ];
    for (v, n) in cases {
        let what = format!("cube moved by {v} at {n}");
        let swept = run(&cube, &translation(v), n, DEFAULT_POSES);
        assert_eq!(written_manifold(&swept, &what), 2, "{what}");
        check_translated_volume(&cube, v, &swept, &what);
    }
}

/// An L-shaped prism: the L of arms `a` (along x) and `b` (along y), both `t` thick, from
/// the origin, extruded to height `h`; outward faces. Not convex.
fn l_prism(a: f32, b: f32, t: f32, h: f32) -> Mesh {
    let outline = [(0.0, 0.0), (a, 0.0), (a, t), (t, t), (t, b), (0.0, b)];
    let mut positions = Vec::new();
    for z in [0.0, h] {
        positions.extend(outline.iter().map(|&(x, y)| Vec3::new(x, y, z)));
    }
    let mut triangles = Vec::new();
    // The caps: a fan from the corner at the origin (the L is star-shaped from it).
    for i in 1..5u32 {
        triangles.push([0, i + 1, i]);
        triangles.push([6, 6 + i, 6 + i + 1]);
    }
    // The sides, counter-clockwise outline seen from above.
    for i in 0..6u32 {
        let j = (i + 1) % 6;
        triangles.push([i, j, 6 + j]);
        triangles.push([i, 6 + j, 6 + i]);
    }
    Mesh::new(positions, triangles)
}

/// Whether the segment from `p` to `p - v` meets the box `lo..hi` (slab test).
fn segment_meets_box(p: DVec3, v: DVec3, lo: DVec3, hi: DVec3) -> bool {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for k in 0..3 {
        let (o, d) = (p[k], -v[k]);
        if d.abs() < 1e-300 {
            if o < lo[k] || o > hi[k] {
                return false;
            }
            continue;
        }
        let (a, b) = ((lo[k] - o) / d, (hi[k] - o) / d);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    t0 <= t1
}

/// The volume swept by `l_prism(a, b, t, h)` translated by `v`, by Monte Carlo over the box
/// of the sweep (a point is swept when the segment back along `v` meets one of the L's two
/// boxes), with its standard error.
fn l_prism_translation_volume(a: f64, b: f64, t: f64, h: f64, v: DVec3, seed: u64) -> (f64, f64) {
    let boxes = [
        (DVec3::ZERO, DVec3::new(a, t, h)),
        (DVec3::ZERO, DVec3::new(t, b, h)),
    ];
    let lo = DVec3::ZERO.min(v);
    let hi = DVec3::new(a, b, h).max(DVec3::new(a, b, h) + v);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let samples = 200_000;
    let hits = (0..samples)
        .filter(|_| {
            let p = lo + (hi - lo) * DVec3::new(rng.gen(), rng.gen(), rng.gen());
            boxes
                .iter()
                .any(|&(bl, bh)| segment_meets_box(p, v, bl, bh))
        })
        .count();
    let box_volume = (hi - lo).element_product();
    let p = hits as f64 / samples as f64;
    (
        box_volume * p,
        box_volume * (p * (1.0 - p) / samples as f64).sqrt(),
    )
}

/// The convex hull of the model's volume swept by turning about `centre`: at least the model's
/// volume, at most the ball through its farthest vertex; `slack` for the discretisation.
fn check_turned_volume(mesh: &Mesh, centre: DVec3, swept: &SweptVolume, what: &str) {
    let h = swept.grid.spacing;
    let slack = mesh.surface_area() * h;
    let r = mesh
        .positions
        .iter()
        .map(|p| (p.as_dvec3() - centre).length())
        .fold(0.0, f64::max);
    let ball = 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let v = swept.surface.volume;
    assert!(
        v >= mesh.signed_volume() - slack && v <= ball + slack,
        "{what}: volume {v} outside [{} - {slack}, {ball} + {slack}]",
        mesh.signed_volume()
    );
}

#[test]
fn a_seeded_sweep_of_shapes_motions_and_resolutions() {
    // Convex and non-convex shapes, translations and turns, resolutions from 16 up: every
    // run succeeds and writes a closed 2-manifold by position with no degenerate triangle,
    // of the genus the motion gives, and its volume agrees with a reference where there is
    // one.
    let mut rng = ChaCha8Rng::seed_from_u64(43);
    let ctx = context();
    for case in 0..12 {
        let n = rng.gen_range(16..=40);
        let shape = case % 4;
        let turn = case % 3 == 2 && shape != 2;
        let (mesh, centre, name) = match shape {
            0 => {
                let half = Vec3::new(
                    rng.gen_range(0.2..0.7),
                    rng.gen_range(0.2..0.7),
                    rng.gen_range(0.2..0.7),
                );
                (cuboid(half), DVec3::ZERO, "box")
            }
            1 => (
                uv_sphere(
                    rng.gen_range(0.4..0.8),
                    rng.gen_range(8..16),
                    rng.gen_range(5..9),
                ),
                DVec3::ZERO,
                "polyhedral sphere",
            ),
            2 => (torus_closed(1.0, 0.3, 20, 8), DVec3::ZERO, "ring"),
            _ => {
                // Star-shaped from the square where its arms meet.
                let t = rng.gen_range(0.3..0.5);
                let mesh = l_prism(rng.gen_range(0.9..1.4), rng.gen_range(0.9..1.4), t, 0.4);
                let centre = DVec3::new(0.5 * t as f64, 0.5 * t as f64, 0.2);
                (mesh, centre, "L prism")
            }
        };
        let (path, poses, v) = if turn {
            // A turn about an axis through `centre`: every pose holds `centre` and is
            // star-shaped from it, so the sweep is too (genus 0).
            let axis = DVec3::new(rng.gen(), rng.gen(), rng.gen()) - 0.5;
            let q = DQuat::from_axis_angle(axis.normalize(), rng.gen_range(0.3..1.5));
            let path = Path3::new(&[
                keyframe(DVec3::ZERO, DQuat::IDENTITY),
                keyframe(centre - q * centre, q),
            ])
            .unwrap();
            (path, rng.gen_range(5..10), DVec3::ZERO)
        } else if shape == 2 {
            // Along the ring's axis, a little aside: the hole stays open.
            let v = DVec3::new(
                rng.gen_range(-0.1..0.1),
                rng.gen_range(-0.1..0.1),
                rng.gen_range(0.2..1.0),
            );
            (translation(v), 2, v)
        } else {
            let v = DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            );
            (translation(v), 2, v)
        };
        let what = format!("case {case}: {name} at {n}, {poses} poses, moved by {v}, turn {turn}");
        eprintln!("{what}");
        let swept = sweep(
            &ctx,
            &mesh,
            &path,
            Options {
                resolution: n,
                poses,
                epsilon: None,
            },
        )
        .unwrap_or_else(|e| panic!("{what}: {e:#}"));
        let chi = written_manifold(&swept, &what);
        assert_eq!(chi, if shape == 2 { 0 } else { 2 }, "{what}");
        match (shape, turn) {
            (0 | 1, false) => check_translated_volume(&mesh, v, &swept, &what),
            (3, false) => {
                let [a, b] = [mesh.positions[1].x, mesh.positions[4].y].map(f64::from);
                let t = mesh.positions[2].y as f64;
                let (exact, sigma) = l_prism_translation_volume(a, b, t, 0.4, v, case as u64);
                let h = swept.grid.spacing;
                let tolerance = 5.0 * sigma + sharp_edge_length(&mesh, v) * h * h;
                let error = (swept.surface.volume - exact).abs();
                assert!(
                    error <= tolerance,
                    "{what}: volume {} vs Monte Carlo {exact} ± {sigma}: off by {error} > \
                     {tolerance}",
                    swept.surface.volume
                );
            }
            (_, true) => check_turned_volume(&mesh, centre, &swept, &what),
            _ => {}
        }
    }
}

#[test]
fn an_open_model_or_a_triangle_soup_is_refused() {
    let ctx = context();
    let path = translation(DVec3::new(0.5, 0.0, 0.0));
    let options = Options {
        resolution: 16,
        poses: 2,
        epsilon: None,
    };
    let mut open = cube(1.0);
    open.triangles.pop();
    let err = format!("{:#}", sweep(&ctx, &open, &path, options).unwrap_err());
    assert!(
        err.contains("not a closed surface") && err.contains("3 edges have one triangle"),
        "{err}"
    );
    let err = format!(
        "{:#}",
        sweep(&ctx, &soup(20, 0.3, 7), &path, options).unwrap_err()
    );
    assert!(err.contains("not a closed surface"), "{err}");
    // Through the command: a non-zero exit naming the model, and nothing written.
    let dir = common::temp_dir("lecture1-swept", "open");
    let model = dir.join("open.obj");
    classic_gpgpu::mesh::write_obj(&open, &model).unwrap();
    let path_file = dir.join("path.json");
    std::fs::write(
        &path_file,
        r#"[{"translation": [0, 0, 0], "rotation": [1, 0, 0, 0]},
            {"translation": [0.5, 0, 0], "rotation": [1, 0, 0, 0]}]"#,
    )
    .unwrap();
    let out = dir.join("swept.obj");
    let run = classic_gpgpu(&[
        "lecture1",
        "swept-volume",
        model.to_str().unwrap(),
        "--path",
        path_file.to_str().unwrap(),
        "--resolution",
        "16",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("open.obj") && stderr.contains("not a closed surface"),
        "{stderr}"
    );
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
