//! Lecture 1, distance fields by rasterization: the 3D field slice by slice (and its compute
//! counterpart) against brute force on the CPU, with and without a clamp, with degenerate
//! triangles and at extreme scales; against parry3d's closest points (an independent
//! reference) on a cube, a sphere and a torus; the 2D generalized Voronoi diagram against brute force,
//! ties included; and the commands' files.

use classic_gpgpu::lecture1::distance_field::compute::ComputeField;
use classic_gpgpu::lecture1::distance_field::independent::parry_field;
use classic_gpgpu::lecture1::distance_field::point_triangle::point_triangle;
use classic_gpgpu::lecture1::distance_field::reference::brute_force;
use classic_gpgpu::lecture1::distance_field::slices::SliceRasterizer;
use classic_gpgpu::lecture1::distance_field::{DistanceField, Grid};
use classic_gpgpu::lecture1::voronoi::mesh::{cone_sides, error_bound};
use classic_gpgpu::lecture1::voronoi::raster::{Method, VoronoiRasterizer};
use classic_gpgpu::lecture1::voronoi::reference::{brute_force as voronoi_cpu, compare};
use classic_gpgpu::lecture1::voronoi::{Domain, Site, Sites};
use classic_gpgpu::mesh::Mesh;
use common::{classic_gpgpu, compute_context, context, json_of, soup};
use glam::{DVec3, Vec3};

mod common;

/// fp32 tolerance of a field against the f64 reference: the GPU works in voxel units, where
/// coordinates are at most a few times N; a few hundred ulps of that, in mesh units.
fn tolerance(grid: &Grid) -> f64 {
    2e-5 * grid.n as f64 * grid.spacing
}

fn largest_difference(a: &DistanceField, b: &DistanceField) -> f64 {
    assert_eq!(a.values.len(), b.values.len());
    a.values
        .iter()
        .zip(&b.values)
        .map(|(&x, &y)| (x as f64 - y as f64).abs())
        .fold(0.0, f64::max)
}

fn check_classic(mesh: &Mesh, n: usize, clamp: Option<f64>) -> DistanceField {
    let ctx = context();
    let grid = Grid::around(mesh, n, Grid::default_margin(mesh).max(1e-3)).unwrap();
    let (gpu, timings) = SliceRasterizer::new(&ctx)
        .unwrap()
        .field(mesh, &grid, clamp)
        .unwrap();
    let cpu = brute_force(mesh, &grid, clamp);
    let error = largest_difference(&gpu, &cpu);
    assert!(
        error <= tolerance(&grid),
        "slices differ from brute force by {error} (tolerance {}, clamp {clamp:?})",
        tolerance(&grid)
    );
    assert!(timings.triangles_drawn > 0);
    gpu
}

#[test]
fn point_triangle_distance_by_region() {
    let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
    // Above the face, beyond an edge, beyond a corner.
    assert_eq!(point_triangle(DVec3::new(0.25, 0.25, 2.0), t), 2.0);
    assert!((point_triangle(DVec3::new(0.5, -1.0, 0.0), t) - 1.0).abs() < 1e-15);
    assert!((point_triangle(DVec3::new(2.0, 0.0, 1.0), t) - 2f64.sqrt()).abs() < 1e-15);
    // A zero-area triangle is its segment; one collapsed to a point is the point.
    let flat = [DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)];
    assert_eq!(point_triangle(DVec3::new(1.0, 3.0, 0.0), flat), 3.0);
    let dot = [DVec3::ONE; 3];
    assert!((point_triangle(DVec3::ZERO, dot) - 3f64.sqrt()).abs() < 1e-15);
}

#[test]
fn slices_equal_brute_force_without_a_clamp() {
    let field = check_classic(&soup(10, 0.5, 7), 16, None);
    // Unclamped: the corners of the grid are far from everything.
    assert!(field.values.iter().all(|&v| v >= 0.0));
    assert!(field.values.iter().any(|&v| v > 0.3));
}

#[test]
fn slices_equal_brute_force_with_a_clamp() {
    let mesh = soup(10, 0.5, 8);
    let field = check_classic(&mesh, 16, Some(0.15));
    assert!(field.values.iter().all(|&v| v <= 0.15));
    assert!(field.values.contains(&0.15));
    assert!(field.values.iter().any(|&v| v < 0.05));
}

#[test]
fn degenerate_triangles_are_their_edges() {
    let mesh = Mesh::new(
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.2, 0.3),
            Vec3::new(2.0, 0.4, 0.6), // collinear: zero area
            Vec3::new(0.5, 1.0, 0.5), // a point-triangle (all three corners)
            Vec3::new(0.2, 0.9, 0.1),
            Vec3::new(1.8, 0.9, 0.1),
            Vec3::new(1.0, 1.5, 0.8),
        ],
        vec![[0, 1, 2], [3, 3, 3], [4, 5, 6]],
    );
    check_classic(&mesh, 16, None);
    check_classic(&mesh, 16, Some(0.3));
}

#[test]
fn extreme_scales_keep_their_precision() {
    let mesh = soup(6, 0.5, 9);
    for (scale, offset) in [(1e-4f32, 0.0f32), (1e4, 0.0), (1.0, 1e4), (1e-3, -50.0)] {
        let moved = Mesh::new(
            mesh.positions
                .iter()
                .map(|p| *p * scale + Vec3::splat(offset))
                .collect(),
            mesh.triangles.clone(),
        );
        check_classic(&moved, 16, None);
    }
}

#[test]
fn compute_equals_slices_and_brute_force() {
    let (ctx, has_compute) = compute_context();
    let mesh = soup(8, 0.5, 10);
    let grid = Grid::around(&mesh, 16, 0.1).unwrap();
    let (slices, _) = SliceRasterizer::new(&ctx)
        .unwrap()
        .field(&mesh, &grid, None)
        .unwrap();
    if !has_compute {
        assert!(ComputeField::new(&ctx).is_err());
        eprintln!("no OpenGL 4.3: the compute field is skipped, the slices ran");
        return;
    }
    let compute = ComputeField::new(&ctx).unwrap();
    for clamp in [None, Some(0.2)] {
        let (field, _) = compute.field(&mesh, &grid, clamp).unwrap();
        let cpu = brute_force(&mesh, &grid, clamp);
        let error = largest_difference(&field, &cpu);
        assert!(error <= tolerance(&grid), "compute vs CPU: {error}");
        if clamp.is_none() {
            let error = largest_difference(&field, &slices);
            assert!(error <= tolerance(&grid), "compute vs slices: {error}");
        }
    }
}

/// The slices' field against parry3d's closest-point query (another library's triangle
/// projection, fp32) on a cube, a polyhedral sphere and a torus (not convex), with and
/// without a clamp. Tolerance: the GPU's fp32 bound ([`tolerance`]) plus 1e-5 mesh units for
/// parry3d's fp32 projection at coordinates of order 1 (these meshes are about 1 across).
/// An odd N puts a voxel at the cube's centre, where the distance is 0.5 exactly.
#[test]
fn slices_equal_parry3ds_closest_points_on_convex_and_non_convex_meshes() {
    use classic_gpgpu::mesh::generate::{cube, torus_closed, uv_sphere};
    let ctx = context();
    let slices = SliceRasterizer::new(&ctx).unwrap();
    let meshes = [
        ("cube", cube(1.0)),
        ("sphere", uv_sphere(0.5, 12, 6)),
        ("torus", torus_closed(0.35, 0.15, 12, 6)),
    ];
    for (name, mesh) in &meshes {
        for clamp in [None, Some(0.1)] {
            let grid = Grid::around(mesh, 15, Grid::default_margin(mesh)).unwrap();
            let (gpu, _) = slices.field(mesh, &grid, clamp).unwrap();
            let parry = parry_field(mesh, &grid, clamp).unwrap();
            let tol = tolerance(&grid) + 1e-5;
            let worst = largest_difference(&gpu, &parry);
            assert!(
                worst <= tol,
                "{name}, clamp {clamp:?}: |GPU - parry3d| = {worst:e} > {tol:e}"
            );
            if *name == "cube" && clamp.is_none() {
                let centre = grid.index(7, 7, 7);
                assert!(grid.point(7, 7, 7).length() < 1e-12);
                assert!((parry.values[centre] as f64 - 0.5).abs() < 1e-6);
                assert!((gpu.values[centre] as f64 - 0.5).abs() < tol);
            }
        }
    }
    // The torus's hole: its centre is the inner radius away, 0.35 - 0.15 = 0.2, along the
    // axis direction's normal plane (the polygonal tube is a little nearer than the round one).
    let (_, torus) = &meshes[2];
    let grid = Grid::around(torus, 15, Grid::default_margin(torus)).unwrap();
    let parry = parry_field(torus, &grid, None).unwrap();
    let hole = parry.values[grid.index(7, 7, 7)] as f64;
    assert!(hole > 0.15 && hole <= 0.2 + 1e-6, "{hole}");
}

#[test]
fn the_grid_is_a_cube_around_the_box() {
    let mesh = soup(4, 0.3, 11);
    let grid = Grid::around(&mesh, 10, 0.5).unwrap();
    let b = mesh.bounds();
    let side = b.size().max_element() as f64 + 1.0;
    assert!((grid.spacing - side / 10.0).abs() < 1e-6);
    let centre = (grid.point(0, 0, 0) + grid.point(9, 9, 9)) * 0.5;
    assert!((centre - b.center().as_dvec3()).length() < 1e-6);
    assert!(Grid::around(&mesh, 1, 0.1).is_err());
    assert!(Grid::around(&mesh, 8, -1.0).is_err());
    let point = Mesh::new(vec![Vec3::ONE; 3], vec![[0, 1, 2]]);
    assert!(Grid::around(&point, 8, 0.0).is_err());
}

#[test]
fn distance_field_command_writes_the_field_it_read_back() {
    let dir = common::temp_dir("lecture1", "field-command");
    let mesh = soup(6, 0.5, 12);
    let obj = dir.join("soup.obj");
    classic_gpgpu::mesh::write_obj(&mesh, &obj).unwrap();
    let npy = dir.join("soup_field.npy");
    let _ = std::fs::remove_file(&npy);
    let args = [
        "lecture1",
        "distance-field",
        obj.to_str().unwrap(),
        "--resolution",
        "16",
        "--npy",
        npy.to_str().unwrap(),
        "--margin",
        "0.25",
        "--check",
    ];
    let mut with_json = vec!["--json"];
    with_json.extend(args);
    let report = json_of(&with_json);
    assert_eq!(report["shape"], serde_json::json!([16, 16, 16]));
    assert_eq!(report["margin"], 0.25);
    assert!(report["clamp"].is_null());
    // The file holds the field this process computes on the same grid.
    let loaded = classic_gpgpu::mesh::load_obj(&obj).unwrap();
    let grid = Grid::around(&loaded, 16, 0.25).unwrap();
    let origin: Vec<f64> = serde_json::from_value(report["origin"].clone()).unwrap();
    assert!((DVec3::from_slice(&origin) - grid.origin).length() < 1e-9);
    assert!((report["spacing"][0].as_f64().unwrap() - grid.spacing).abs() < 1e-12);
    let (shape, values) = classic_gpgpu::files::read_npy(&npy).unwrap();
    assert_eq!(shape, vec![16, 16, 16]);
    let ctx = context();
    let (field, _) = SliceRasterizer::new(&ctx)
        .unwrap()
        .field(&loaded, &grid, None)
        .unwrap();
    assert_eq!(values, field.values);
    assert!(report["max_error_vs_cpu"].as_f64().unwrap() <= tolerance(&grid));
    // An existing file is refused without --force, replaced with it.
    let again = classic_gpgpu(&with_json);
    assert!(!again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("--force"));
    with_json.push("--force");
    json_of(&with_json);
    // Bad input: a clear error, no panic.
    let bad = classic_gpgpu(&[
        "lecture1",
        "distance-field",
        obj.to_str().unwrap(),
        "--resolution",
        "16",
        "--npy",
        dir.join("bad.npy").to_str().unwrap(),
        "--clamp=-1",
    ]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("clamp"));
    std::fs::remove_dir_all(&dir).unwrap();
}

// ---- The 2D generalized Voronoi diagram ----

fn random_sites(count: usize, seed: u64) -> Vec<Site> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut p = || [rng.gen_range(0.0..10.0), rng.gen_range(0.0..10.0)];
    (0..count)
        .map(|i| match i % 3 {
            0 => Site::Point(p()),
            1 => Site::Segment([p(), p()]),
            _ => Site::Triangle([p(), p(), p()]),
        })
        .collect()
}

fn check_voronoi(
    sites: &[Site],
    domain: Domain,
    n: usize,
) -> classic_gpgpu::lecture1::voronoi::Diagram {
    let ctx = context();
    let (diagram, _) = VoronoiRasterizer::new(&ctx)
        .unwrap()
        .diagram(sites, domain, n)
        .unwrap();
    let agreement = compare(&diagram, sites);
    assert!(agreement.agrees(), "{agreement:?}");
    assert_eq!(agreement.pixels, n * n);
    diagram
}

#[test]
fn voronoi_equals_brute_force() {
    let sites = random_sites(9, 3);
    let domain = Domain {
        min: [0.0, 0.0],
        size: 10.0,
    };
    let diagram = check_voronoi(&sites, domain, 32);
    // Nearly every pixel the same site (ties are rare on random sites).
    let cpu = voronoi_cpu(&sites, domain, 32, diagram.depth_range);
    let same = diagram
        .site
        .iter()
        .zip(&cpu.site)
        .filter(|(a, b)| a == b)
        .count();
    assert!(same >= 32 * 32 - 4, "{same}");
    let counts = diagram.pixel_counts(sites.len());
    assert_eq!(counts.iter().sum::<usize>(), 32 * 32);
}

#[test]
fn cone_sides_are_the_fewest_within_the_error() {
    for (radius, error) in [(100.0, 0.5), (724.0, 0.25), (30.0, 2.0), (1.0, 0.1)] {
        let k = cone_sides(radius, error).unwrap();
        assert!(
            error_bound(radius, k) <= error * (1.0 + 1e-12),
            "{radius} {error} {k}"
        );
        if k > 3 {
            assert!(error_bound(radius, k - 1) > error, "{radius} {error} {k}");
        }
    }
    assert!(cone_sides(10.0, 0.0).is_err());
    assert!(cone_sides(10.0, f64::NAN).is_err());
}

/// The diagram by distance meshes within `error_pixels`, against brute force and against the
/// exact per-fragment path; the largest distance error in pixels and the bound.
fn check_meshes(sites: &[Site], domain: Domain, n: usize, error_pixels: f64) -> (f64, f64) {
    let ctx = context();
    let raster = VoronoiRasterizer::new(&ctx).unwrap();
    let (meshed, _) = raster
        .diagram_by(sites, domain, n, Method::Mesh { error_pixels })
        .unwrap();
    let (exact, _) = raster.diagram(sites, domain, n).unwrap();
    let pixel = domain.pixel(n);
    // The bound is what was asked, in input units.
    assert!(meshed.mesh_error > 0.0 && meshed.mesh_error <= error_pixels * pixel * (1.0 + 1e-9));
    let agreement = compare(&meshed, sites);
    assert!(agreement.agrees(), "{agreement:?}");
    // A distance is never negative, whatever the rasterizer's coverage at an edge.
    if let Some(i) = meshed.distance.iter().position(|&d| d < 0.0) {
        panic!("pixel {i}: negative distance {}", meshed.distance[i]);
    }
    // One-sided: a mesh lies above the distance function (its facets are chords of a convex
    // cone), never below it by more than fp32 rounding.
    let rounding = exact.tolerance();
    let cpu = voronoi_cpu(sites, domain, n, exact.depth_range);
    let mut largest: f64 = 0.0;
    for i in 0..n * n {
        let (m, d) = (meshed.distance[i] as f64, cpu.distance[i] as f64);
        let fp32 = meshed.tolerance() - meshed.mesh_error;
        assert!(m >= d - fp32, "pixel {i}: {m} below {d}");
        assert!(
            m <= d + meshed.mesh_error + fp32,
            "pixel {i}: {m} above {d}"
        );
        let e = exact.distance[i] as f64;
        assert!((m - e).abs() <= meshed.mesh_error + meshed.tolerance() + rounding);
        largest = largest.max(m - d);
    }
    (largest / pixel, meshed.mesh_error / pixel)
}

#[test]
fn voronoi_meshes_stay_within_their_bound() {
    let sites = random_sites(12, 5);
    let domain = Domain {
        min: [0.0, 0.0],
        size: 10.0,
    };
    let (fine, fine_bound) = check_meshes(&sites, domain, 48, 0.05);
    let (coarse, coarse_bound) = check_meshes(&sites, domain, 48, 3.0);
    eprintln!("mesh error: {fine:.4} px (bound {fine_bound:.4}), {coarse:.4} px (bound {coarse_bound:.4})");
    assert!(fine <= fine_bound + 0.01 && coarse <= coarse_bound + 0.01);
    // The coarse cones are visibly faceted: the error is a real part of its bound, so the
    // meshes, not exact distances, drew the diagram. (The bound holds out to the farthest
    // corner of the domain, `r (1 / cos(π/k) - 1)` at r = R; a pixel's nearest site is much
    // nearer, here about a fifth of R.)
    assert!(coarse > 0.1 * coarse_bound, "{coarse} of {coarse_bound}");
    assert!(coarse > fine);
}

/// Where a mesh crosses the target's edge it is cut. Cut by the renderer, softpipe left pixel
/// centres on the inner edge of the clipper's fan (from a cone's apex to a corner of the
/// target) uncovered by both halves, here at 61 pixels (a point's pixel won by a segment
/// 0.18 farther), and set up the plane of a cut sliver far off (at 63 pixels the auto domain's
/// triangle came out below its distance); these sites and resolutions hit both.
#[test]
fn voronoi_meshes_cover_every_pixel_where_cut() {
    let sites = [
        Site::Point([2.0, 2.0]),
        Site::Point([7.0, 7.0]),
        Site::Point([5.0, 5.0]),
        Site::Segment([[5.0, 1.0], [8.0, 3.0]]),
        Site::Triangle([[1.0, 6.0], [3.0, 9.0], [4.0, 5.0]]),
    ];
    let domain = Domain {
        min: [0.0, 0.0],
        size: 10.0,
    };
    for n in [60, 61, 62] {
        for error in [0.1, 0.5] {
            check_meshes(&sites, domain, n, error);
        }
    }
    let sliver = random_sites(5, 18);
    let domain = Sites {
        domain: None,
        sites: sliver.clone(),
    }
    .domain()
    .unwrap();
    for error in [0.1, 0.5, 2.0] {
        check_meshes(&sliver, domain, 63, error);
    }
}

#[test]
fn voronoi_meshes_at_extreme_scales() {
    let sites = random_sites(7, 4);
    for (scale, offset) in [(1e-4, 0.0), (1e4, 0.0), (1.0, 1e4)] {
        let (moved, domain) = scaled(&sites, scale, offset);
        check_meshes(&moved, domain, 24, 0.5);
    }
}

#[test]
fn voronoi_ties_go_to_the_smaller_id() {
    // Sites 0 and 2 are the same point, 1 and 3 the same triangle, 4 overlaps 1: where they
    // tie exactly (the same distance computed the same way), the smaller id wins.
    let sites = vec![
        Site::Point([2.0, 2.0]),
        Site::Triangle([[5.0, 5.0], [8.0, 5.0], [6.0, 8.0]]),
        Site::Point([2.0, 2.0]),
        Site::Triangle([[5.0, 5.0], [8.0, 5.0], [6.0, 8.0]]),
        Site::Triangle([[6.0, 6.0], [9.0, 6.0], [7.0, 9.5]]),
        // A zero-area triangle (its segment) and a zero-length segment (a point).
        Site::Triangle([[1.0, 8.0], [2.0, 8.5], [3.0, 9.0]]),
        Site::Segment([[8.0, 1.0], [8.0, 1.0]]),
    ];
    let domain = Domain {
        min: [0.0, 0.0],
        size: 10.0,
    };
    let diagram = check_voronoi(&sites, domain, 32);
    let counts = diagram.pixel_counts(sites.len());
    assert_eq!(counts[2], 0, "{counts:?}");
    assert_eq!(counts[3], 0, "{counts:?}");
    assert!(counts[0] > 0 && counts[1] > 0 && counts[4] > 0 && counts[5] > 0 && counts[6] > 0);
    // Inside both triangles 1 and 4 the distance is 0 for both: site 1 keeps the pixels.
    let at = |x: f64, y: f64| {
        let (px, py) = ((x / 10.0 * 32.0) as usize, (y / 10.0 * 32.0) as usize);
        diagram.site[py * 32 + px]
    };
    assert_eq!(at(6.6, 6.4), 1);
    assert_eq!(at(8.0, 7.5), 4);
}

#[test]
fn voronoi_at_extreme_scales() {
    let sites = random_sites(7, 4);
    for (scale, offset) in [(1e-4, 0.0), (1e4, 0.0), (1.0, 1e4)] {
        let (moved, domain) = scaled(&sites, scale, offset);
        check_voronoi(&moved, domain, 24);
    }
}

#[test]
fn voronoi_command_reports_and_refuses() {
    let dir = common::temp_dir("lecture1", "voronoi-command");
    let sites = dir.join("sites.json");
    std::fs::write(
        &sites,
        r#"{"sites": [{"point": [1, 1]}, {"segment": [[3, 1], [4, 4]]},
                     {"triangle": [[0, 4], [1, 5], [0, 5]]}]}"#,
    )
    .unwrap();
    let png = dir.join("voronoi.png");
    let npy = dir.join("voronoi.npy");
    let _ = std::fs::remove_file(&png);
    let _ = std::fs::remove_file(&npy);
    let args = [
        "--json",
        "lecture1",
        "voronoi",
        sites.to_str().unwrap(),
        "--resolution",
        "24",
        "--png",
        png.to_str().unwrap(),
        "--npy",
        npy.to_str().unwrap(),
    ];
    let report = json_of(&args);
    assert_eq!(report["resolution"], 24);
    let counts: Vec<usize> = serde_json::from_value(report["pixel_counts"].clone()).unwrap();
    assert_eq!(counts.len(), 3);
    assert_eq!(counts.iter().sum::<usize>(), 24 * 24);
    assert_eq!(report["agreement"]["wrong"], 0);
    assert!(png.exists());
    let (shape, values) = classic_gpgpu::files::read_npy(&npy).unwrap();
    assert_eq!(shape, vec![24, 24, 2]);
    let mut from_file = vec![0usize; 3];
    for v in values.chunks(2) {
        from_file[v[0] as usize] += 1;
    }
    assert_eq!(from_file, counts);
    // Existing outputs are refused without --force.
    assert!(!classic_gpgpu(&args).status.success());
    // Bad sites: a clear error naming the file.
    let bad = dir.join("bad_sites.json");
    std::fs::write(&bad, r#"{"sites": [{"circle": [1, 1]}]}"#).unwrap();
    let out = classic_gpgpu(&[
        "lecture1",
        "voronoi",
        bad.to_str().unwrap(),
        "--png",
        dir.join("bad.png").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("bad_sites.json"));
    // Hoff's distance meshes from the command: the bound is stated and met.
    let mut meshed = args.to_vec();
    meshed.extend(["--force", "--method", "mesh", "--mesh-error", "0.25"]);
    let report = json_of(&meshed);
    assert_eq!(report["method"], "mesh");
    let bound = report["mesh_error_bound"].as_f64().unwrap();
    let pixel = report["domain"]["size"].as_f64().unwrap() / 24.0;
    assert!(
        bound > 0.0 && bound <= 0.25 * pixel * (1.0 + 1e-9),
        "{bound}"
    );
    assert_eq!(report["agreement"]["wrong"], 0);
    // --mesh-error without the mesh method, or not positive: refused.
    let mut exact = args.to_vec();
    exact.extend(["--force", "--mesh-error", "0.5"]);
    let out = classic_gpgpu(&exact);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--mesh-error"));
    meshed.pop();
    meshed.push("0");
    let out = classic_gpgpu(&meshed);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--mesh-error"));
    assert!(Sites::parse(r#"{"sites": []}"#).is_err());
    assert!(Sites::parse(
        r#"{"sites": [{"point": [1, 1]}], "domain": {"min": [0, 0], "size": 0}}"#
    )
    .is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `sites` on the 10 x 10 domain at the origin, scaled by `scale` and moved by `offset` on
/// both axes, with the domain they then cover.
fn scaled(sites: &[Site], scale: f64, offset: f64) -> (Vec<Site>, Domain) {
    let moved = sites
        .iter()
        .map(|s| match *s {
            Site::Point(p) => Site::Point(p.map(|v| v * scale + offset)),
            Site::Segment(s) => Site::Segment(s.map(|p| p.map(|v| v * scale + offset))),
            Site::Triangle(t) => Site::Triangle(t.map(|p| p.map(|v| v * scale + offset))),
        })
        .collect();
    let domain = Domain {
        min: [offset, offset],
        size: 10.0 * scale,
    };
    (moved, domain)
}

/// Pixel centres within a rasterizer's sub-pixel step of a segment or a triangle's edge: on
/// llvmpipe the other side's tent covered them and read its plane extended, a negative
/// distance (-0.00013 where the truth is 0.00013, at these inputs and resolutions). The mesh
/// distance is never negative, and stays within the coverage allowance of the truth.
#[test]
fn voronoi_meshes_beside_an_edge_read_no_negative_distance() {
    let fixed = Domain {
        min: [0.0, 0.0],
        size: 10.0,
    };
    for (seed, domain, n) in [
        (0, None, 57),
        (0, None, 59),
        (0, Some(fixed), 59),
        (0, Some(fixed), 63),
        (0, Some(fixed), 65),
        (1, None, 65),
    ] {
        let sites = random_sites(5, seed);
        let domain = domain.unwrap_or_else(|| {
            Sites {
                domain: None,
                sites: sites.clone(),
            }
            .domain()
            .unwrap()
        });
        check_meshes(&sites, domain, n, 0.5);
    }
}
