//! Meshes: generator sizes (paper 4 Table 1, paper 1 section 7.2), closedness and
//! orientation, OBJ reading/writing and its errors, validation, retessellation, bunny.
//! No OpenGL needed.

use std::f64::consts::PI;
use std::path::PathBuf;

use classic_gpgpu::mesh::*;
use glam::{Affine3A, Quat, Vec3};

/// A fresh directory for this test's files.
fn temp_dir(test: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("classic-gpgpu-mesh-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write_temp(test: &str, name: &str, text: &str) -> PathBuf {
    let path = temp_dir(test).join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn assert_counts(mesh: &Mesh, vertices: usize, triangles: usize) {
    assert_eq!(
        (mesh.vertex_count(), mesh.triangle_count()),
        (vertices, triangles)
    );
}

/// Closed, one piece, the given genus, and facing out.
fn assert_closed_solid(name: &str, mesh: &Mesh, genus: i64) {
    let c = mesh.closedness();
    assert!(c.is_closed(), "{name} is not closed: {c:?}");
    assert_eq!(c.genus(), Some(genus), "{name}: {c:?}");
    assert!(mesh.signed_volume() > 0.0, "{name} is inside out");
    let report = mesh.validate();
    assert!(report.is_usable(), "{name}: {report:?}");
    assert_eq!(report.degenerate_triangles(), 0, "{name}");
}

fn relative_error(got: f64, want: f64) -> f64 {
    ((got - want) / want).abs()
}

// ---- generators: paper sizes -------------------------------------------------------

#[test]
fn cube_is_8_vertices_12_triangles_closed() {
    let cube = cube(2.0);
    assert_counts(&cube, 8, 12);
    assert_closed_solid("cube", &cube, 0);
    assert!(relative_error(cube.signed_volume(), 8.0) < 1e-12);
    let b = cube.bounds();
    assert_eq!((b.min, b.max), (Vec3::splat(-1.0), Vec3::splat(1.0)));
    let boxed = cuboid(Vec3::new(1.0, 2.0, 3.0));
    assert!(relative_error(boxed.signed_volume(), 48.0) < 1e-12);
}

#[test]
fn uv_sphere_of_paper_4_is_422_vertices_840_triangles_closed() {
    let sphere = uv_sphere(1.0, 30, 15);
    assert_counts(&sphere, 422, 840);
    assert_closed_solid("sphere", &sphere, 0);
    // An inscribed polyhedron: a little less than 4/3 pi, and within 2 %.
    let v = sphere.signed_volume();
    assert!(
        v < 4.0 / 3.0 * PI && relative_error(v, 4.0 / 3.0 * PI) < 0.02,
        "{v}"
    );
    for (segments, rings) in [(3, 2), (7, 5), (64, 32)] {
        let s = uv_sphere(2.0, segments, rings);
        assert_counts(&s, 2 + (rings - 1) * segments, 2 * segments * (rings - 1));
        assert_closed_solid("sphere", &s, 0);
    }
}

#[test]
fn torus_of_paper_4_is_1024_vertices_1922_triangles_closed_after_welding() {
    let torus = torus(1.0, 0.4, 31, 31);
    assert_counts(&torus, 1024, 1922);
    // The seams are duplicated: 32 x 32 vertices, 31 x 31 distinct ones.
    assert_eq!(torus.welded().vertex_count(), 961);
    assert_closed_solid("torus", &torus, 1);
    let exact = 2.0 * PI * PI * 1.0 * 0.4 * 0.4;
    assert!(relative_error(torus.signed_volume(), exact) < 0.02);
}

#[test]
fn closed_tori_of_paper_1_have_the_requested_triangle_count() {
    for (triangles, vertices) in [(15_000, 7_500), (20_000, 10_000), (50_000, 25_000)] {
        let torus = torus_with_triangles(1.0, 0.4, triangles);
        assert_counts(&torus, vertices, triangles);
        assert_closed_solid("torus", &torus, 1);
        // Inscribed polygons of n sides lose about (2 pi / n)^2 / 6 of the area; with at
        // least 50 segments around the tube that is under 0.3 %.
        let exact = 2.0 * PI * PI * 1.0 * 0.4 * 0.4;
        assert!(relative_error(torus.signed_volume(), exact) < 0.004);
    }
    // A count with no exact grid still lands within 0.5 %.
    let odd = torus_with_triangles(1.0, 0.4, 15_001);
    assert!((odd.triangle_count() as f64 - 15_001.0).abs() / 15_001.0 < 0.005);
    assert_counts(&torus_closed(2.0, 0.5, 12, 5), 60, 120);
}

#[test]
fn torus_knot_of_paper_4_is_1440_vertices_2880_triangles_closed() {
    let spec = TorusKnot::default();
    let knot = torus_knot(&spec);
    assert_counts(&knot, 1440, 2880);
    assert_closed_solid("knot", &knot, 1);
    // Volume of a tube: its cross-section (a 12-gon) times the centre line's length
    // (Pappus), within 2 % (the bends squeeze the inner side of the tube a little).
    let samples = 20_000;
    let length: f64 = (0..samples)
        .map(|i| {
            let t = |k: usize| 2.0 * std::f32::consts::PI * k as f32 / samples as f32;
            spec.curve(t(i)).distance(spec.curve(t(i + 1))) as f64
        })
        .sum();
    let sides = spec.radial_segments as f64;
    let section = 0.5 * sides * (spec.tube_radius as f64).powi(2) * (2.0 * PI / sides).sin();
    let tube = section * length;
    assert!(
        relative_error(knot.signed_volume(), tube) < 0.02,
        "{} vs {tube}",
        knot.signed_volume()
    );
}

#[test]
fn torus_knot_strands_stay_apart() {
    // The tube is a valid solid only if far-apart parts of the centre line stay more than
    // a tube diameter apart.
    let spec = TorusKnot::default();
    let n = 720;
    let points: Vec<Vec3> = (0..n)
        .map(|i| spec.curve(2.0 * std::f32::consts::PI * i as f32 / n as f32))
        .collect();
    let step = points[0].distance(points[1]);
    let mut closest = f32::INFINITY;
    for i in 0..n {
        for j in i + 1..n {
            let along = (j - i).min(n - (j - i)) as f32 * step; // roughly, along the curve
            if along > 1.5 {
                closest = closest.min(points[i].distance(points[j]));
            }
        }
    }
    assert!(
        closest > 2.0 * spec.tube_radius * 1.2,
        "strands {closest} apart"
    );
}

#[test]
fn pipe_is_a_closed_genus_1_solid_near_paper_4_size() {
    let spec = Pipe::default();
    let pipe = pipe(&spec);
    assert_counts(&pipe, 4624, 9248);
    assert!(relative_error(pipe.vertex_count() as f64, 4626.0) < 0.001);
    assert_closed_solid("pipe", &pipe, 1);
    // Pappus: cross-section area (of the polygons) times the centre line length.
    let polygon = |r: f64| 0.5 * spec.around as f64 * r * r * (2.0 * PI / spec.around as f64).sin();
    let area = polygon(spec.outer_radius as f64) - polygon(spec.inner_radius as f64);
    let expected = area * spec.path_length() as f64;
    assert!(
        relative_error(pipe.signed_volume(), expected) < 0.01,
        "{} vs {expected}",
        pipe.signed_volume()
    );
    let other = pipe_with(8, 5);
    assert_counts(&other, 80, 160);
    assert_closed_solid("small pipe", &other, 1);
}

fn pipe_with(around: usize, stations: usize) -> Mesh {
    pipe(&Pipe {
        around,
        stations,
        ..Pipe::default()
    })
}

#[test]
fn teapot_at_5_segments_has_paper_4_vertex_count() {
    let pot = teapot(5);
    // Paper 4 Table 1: 821 vertices (ours match), 1628 faces (ours: 64 n^2 - 8 n = 1560).
    assert_counts(&pot, 821, 1560);
    for n in 2..=7 {
        assert_eq!(teapot(n).triangle_count(), 64 * n * n - 8 * n, "n = {n}");
    }
}

#[test]
fn teapot_is_open_only_where_newell_left_it_open() {
    for n in [3, 5] {
        let teapot = teapot(n);
        let c = teapot.closedness();
        // Patches meet edge to edge and agree on orientation; what is left open is the
        // rim's inner edge, the lid's lower edge, both spout ends and both handle ends:
        // 2 four-patch loops and 4 two-patch loops, n edges per patch side.
        assert_eq!((c.non_manifold_edges, c.misoriented_edges), (0, 0), "{c:?}");
        assert_eq!(c.boundary_edges, 16 * n, "{c:?}");
        // Body with handle (they touch at one point), lid, spout.
        assert_eq!(c.components, 3);
        assert!(!teapot.is_closed());
        assert!(teapot.signed_volume() > 0.0);
        assert_eq!(teapot.validate().degenerate_triangles(), 0);
    }
}

#[test]
fn teapot_data_is_mirror_symmetric_and_in_its_known_box() {
    // A typo in the transcribed control points would break the symmetry about y = 0.
    let teapot = teapot(4);
    for p in &teapot.positions {
        let mirror = Vec3::new(p.x, -p.y, p.z);
        let nearest = teapot
            .positions
            .iter()
            .map(|q| q.distance(mirror))
            .fold(f32::INFINITY, f32::min);
        assert!(nearest < 1e-5, "{p} has no mirror image");
    }
    let b = teapot.bounds();
    assert!(
        (b.min.z - 0.0).abs() < 1e-6 && (b.max.z - 3.15).abs() < 1e-6,
        "{b:?}"
    );
    assert!(
        (b.min.x + 3.0).abs() < 0.05 && (b.max.x - 3.434).abs() < 0.05,
        "{b:?}"
    );
    // The body is a surface of revolution: on the rim and the bottom edge, radius 1.5.
    let rim: Vec<f32> = teapot
        .positions
        .iter()
        .filter(|p| (p.z - 2.4).abs() < 1e-6 && p.x.abs() < 1.6)
        .map(|p| p.truncate().length())
        .filter(|r| *r > 1.45)
        .collect();
    assert!(
        !rim.is_empty() && rim.iter().all(|r| (r - 1.5).abs() < 0.01),
        "{rim:?}"
    );
    assert_eq!(teapot_patches().len(), 32);
}

#[test]
fn generators_are_outward_face_by_face() {
    // Consistent orientation plus positive volume already implies outward; check the
    // sphere directly too: every face normal points away from the centre.
    let sphere = uv_sphere(1.0, 30, 15);
    for (t, n) in sphere.face_normals().iter().enumerate() {
        let [a, b, c] = sphere.triangle(t);
        assert!(n.dot((a + b + c) / 3.0) > 0.0, "triangle {t}");
    }
}

// ---- mesh measures and transforms --------------------------------------------------

#[test]
fn normals_areas_and_transforms() {
    let sphere = uv_sphere(1.0, 48, 24);
    for (p, n) in sphere.positions.iter().zip(sphere.vertex_normals()) {
        assert!(n.dot(p.normalize()) > 0.995, "{p} {n}");
    }
    assert!(sphere
        .face_normals()
        .iter()
        .all(|n| (n.length() - 1.0).abs() < 1e-5));
    let cube = cube(2.0);
    assert!((cube.surface_area() - 24.0).abs() < 1e-9);
    assert!(cube.face_areas().iter().all(|a| (a - 2.0).abs() < 1e-6));

    let motion =
        Affine3A::from_rotation_translation(Quat::from_rotation_y(0.7), Vec3::new(3.0, -1.0, 2.0));
    let moved = sphere.transformed(&motion);
    assert!(relative_error(moved.signed_volume(), sphere.signed_volume()) < 1e-5);
    assert!((moved.bounds().center() - Vec3::new(3.0, -1.0, 2.0)).length() < 1e-5);
    // A mirror keeps the mesh outward (the winding is reversed with it).
    let mirrored = sphere.transformed(&Affine3A::from_scale(Vec3::new(-1.0, 2.0, 1.0)));
    assert!(relative_error(mirrored.signed_volume(), 2.0 * sphere.signed_volume()) < 1e-5);
    assert!(mirrored.is_closed());
    // Turned inside out: negative volume, still closed.
    let inverted = sphere.flipped();
    assert!(!inverted.is_outward() && inverted.is_closed());
    let two = Mesh::merged([&cube, &cube.translated(Vec3::X * 5.0)]);
    assert_counts(&two, 16, 24);
    assert_eq!(two.closedness().components, 2);
    assert_eq!(two.closedness().genus(), None); // genus is asked of one piece only
}

#[test]
fn empty_mesh_has_empty_bounds() {
    assert!(Mesh::default().bounds().is_empty());
    assert!(!cube(1.0).bounds().is_empty());
}

// ---- validation --------------------------------------------------------------------

#[test]
fn validation_counts_degenerate_triangles() {
    let positions = vec![
        Vec3::ZERO,
        Vec3::X,
        Vec3::Y,
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::X,
    ];
    let mesh = Mesh::new(
        positions,
        vec![
            [0, 1, 2], // fine
            [0, 0, 2], // repeated index
            [0, 1, 3], // collinear
            [1, 4, 2], // 1 and 4 coincide
        ],
    );
    let r = mesh.validate();
    assert!(r.is_usable());
    assert_eq!((r.repeated_index_triangles, r.zero_area_triangles), (1, 2));
    assert_eq!(r.degenerate_triangles(), 3);
    assert_eq!(r.unreferenced_vertices, 0);
    let text = r.to_string();
    assert!(
        text.contains("3 degenerate triangles (1 repeat a vertex, 2 have zero area)"),
        "{text}"
    );
    assert!(load_bunny()
        .validate()
        .to_string()
        .ends_with("closed, genus 0"));
    // A thin but real triangle is not degenerate.
    let sliver = Mesh::new(
        vec![Vec3::ZERO, Vec3::X, Vec3::new(0.5, 1e-4, 0.0)],
        vec![[0, 1, 2]],
    );
    assert_eq!(sliver.validate().degenerate_triangles(), 0);
}

#[test]
fn validation_reports_non_finite_and_out_of_range() {
    let mesh = Mesh::new(
        vec![Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0), Vec3::Y],
        vec![[0, 1, 2], [0, 2, 7]],
    );
    let r = mesh.validate();
    assert_eq!(r.non_finite_vertices, vec![1]);
    assert_eq!(r.out_of_range_triangles, vec![1]);
    assert!(!r.is_usable() && r.closedness.is_none());
    let err = mesh.check("probe").unwrap_err();
    assert!(
        matches!(err, MeshError::NonFinite { vertex: 1, .. }),
        "{err}"
    );
    assert!(
        err.to_string().contains("probe") && err.to_string().contains("vertex 1"),
        "{err}"
    );

    let bad_index = Mesh::new(
        vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let err = bad_index.check("probe").unwrap_err();
    assert!(
        matches!(
            err,
            MeshError::IndexOutOfRange {
                face: 1,
                index: 3,
                vertex_count: 3,
                ..
            }
        ),
        "{err}"
    );
    assert!(matches!(
        Mesh::default().check("probe"),
        Err(MeshError::Empty { .. })
    ));
    assert!(cube(1.0).check("cube").is_ok());
}

#[test]
fn closedness_finds_holes_flips_and_non_manifold_edges() {
    let cube = cube(1.0);
    let mut holed = cube.clone();
    holed.triangles.pop();
    let c = holed.closedness();
    assert_eq!((c.boundary_edges, c.is_closed()), (3, false));

    let mut flipped = cube.clone();
    let [a, b, c3] = flipped.triangles[0];
    flipped.triangles[0] = [a, c3, b];
    let c = flipped.closedness();
    assert_eq!((c.misoriented_edges, c.is_closed()), (3, false));

    let mut doubled = cube.clone();
    doubled.triangles.push(cube.triangles[0]);
    let c = doubled.closedness();
    assert_eq!((c.non_manifold_edges, c.is_closed()), (3, false));

    // Split along a seam (vertex 0 duplicated for some faces) and still closed: welding.
    let mut seamed = cube.clone();
    seamed.positions.push(seamed.positions[0]);
    let copy = seamed.positions.len() as u32 - 1;
    for t in seamed.triangles.iter_mut().take(2) {
        t.iter_mut().filter(|i| **i == 0).for_each(|i| *i = copy);
    }
    assert!(seamed.is_closed());
}

// ---- OBJ ---------------------------------------------------------------------------

#[test]
fn obj_round_trip_keeps_every_triangle() {
    let original = torus_knot(&TorusKnot {
        tubular_segments: 30,
        radial_segments: 5,
        ..TorusKnot::default()
    });
    let path = temp_dir("round_trip").join("knot.obj");
    write_obj(&original, &path).unwrap();
    let back = load_obj(&path).unwrap();
    assert_eq!(back, original); // same ids, bit-exact positions
    let text = to_obj_string(&original, "made by a test\nsecond line");
    assert!(text.starts_with("# made by a test\n# second line\nv "));
    assert_eq!(parse_obj(&text, "inline").unwrap(), back);
}

#[test]
fn obj_polygons_are_fanned_in_file_order_across_groups() {
    let text = "\
# a quad, a triangle and a pentagon in two objects
o first
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0.5 1.5 0
vn 0 0 1
f 1//1 2//1 3//1 4//1
g second
usemtl whatever
f -5 -4 -1
f 1/1 2/1 3/1 5/1 4/1
l 1 2
";
    let mesh = parse_obj(text, "polygons.obj").unwrap();
    assert_eq!(mesh.triangle_count(), 2 + 1 + 3);
    let p = |x: f32, y: f32| Vec3::new(x, y, 0.0);
    let expected = [
        [p(0., 0.), p(1., 0.), p(1., 1.)],
        [p(0., 0.), p(1., 1.), p(0., 1.)],
        [p(0., 0.), p(1., 0.), p(0.5, 1.5)],
        [p(0., 0.), p(1., 0.), p(1., 1.)],
        [p(0., 0.), p(1., 1.), p(0.5, 1.5)],
        [p(0., 0.), p(0.5, 1.5), p(0., 1.)],
    ];
    for (t, want) in expected.iter().enumerate() {
        assert_eq!(&mesh.triangle(t), want, "triangle {t}");
    }
    // One shared vertex list across objects, in file order, unused ones kept.
    assert_eq!(
        mesh.positions,
        vec![p(0., 0.), p(1., 0.), p(1., 1.), p(0., 1.), p(0.5, 1.5)]
    );
    assert_eq!(mesh.triangles[..2], [[0, 1, 2], [0, 2, 3]]);
    let unused = parse_obj(
        "v 9 9 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 2 3 4\n",
        "unused.obj",
    )
    .unwrap();
    assert_eq!((unused.vertex_count(), unused.triangles[0]), (4, [1, 2, 3]));
    assert_eq!(unused.validate().unreferenced_vertices, 1);
}

#[test]
fn obj_with_crlf_line_ends_and_w_coordinates_loads() {
    let mesh = parse_obj("v 0 0 0\r\nv 2 0 0 2\r\nv 0 1 0\r\nf 1 2 3\r\n", "crlf.obj").unwrap();
    assert_eq!(mesh.triangle(0), [Vec3::ZERO, Vec3::X, Vec3::Y]);
    // Faces listing vertices out of order still get the file's numbering.
    let mixed = parse_obj(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 4 2 3\nf -1 -4 -3\n",
        "mixed.obj",
    )
    .unwrap();
    assert_eq!(mixed.triangles, vec![[3, 1, 2], [3, 0, 1]]);
}

fn load_error(test: &str, text: &str) -> (MeshError, String) {
    let path = write_temp(test, "bad.obj", text);
    let err = load_obj(&path).unwrap_err();
    let message = err.to_string();
    assert!(message.contains("bad.obj"), "no file name in: {message}");
    (err, message)
}

#[test]
fn obj_missing_file_is_named() {
    let path = temp_dir("missing").join("nowhere.obj");
    let err = load_obj(&path).unwrap_err();
    assert!(matches!(err, MeshError::Io { .. }));
    assert!(err.to_string().contains("nowhere.obj"), "{err}");
}

#[test]
fn obj_malformed_vertex_names_file_and_line() {
    let (err, message) = load_error("bad_vertex", "v 0 0 0\nv 1 0 0\n\nv 0 one 0\nf 1 2 3\n");
    assert_eq!(err.line(), Some(4), "{message}");
    assert!(
        message.contains("bad.obj:4") && message.contains("v 0 one 0"),
        "{message}"
    );
    let (err, _) = load_error("short_vertex", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n");
    assert_eq!(err.line(), Some(2));
}

#[test]
fn obj_malformed_face_names_file_and_line() {
    let (err, message) = load_error(
        "bad_face",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 two 3\n",
    );
    assert_eq!(err.line(), Some(5), "{message}");
    assert!(message.contains("bad.obj:5"), "{message}");
    let (err, message) = load_error(
        "short_face",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n# c\nf 1 2\n",
    );
    assert_eq!(err.line(), Some(6), "{message}");
    assert!(message.contains("three vertices"), "{message}");
}

#[test]
fn obj_out_of_range_index_names_face_and_line() {
    let (err, message) = load_error("range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
    assert!(
        matches!(
            err,
            MeshError::IndexOutOfRange {
                face: 2,
                index: 9,
                vertex_count: 3,
                ..
            }
        ),
        "{message}"
    );
    assert!(message.contains("bad.obj:5"), "{message}");
    let (err, _) = load_error("zero", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    assert!(matches!(
        err,
        MeshError::IndexOutOfRange {
            face: 1,
            index: 0,
            ..
        }
    ));
    let (err, _) = load_error("negative", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n");
    assert!(matches!(err, MeshError::IndexOutOfRange { index: -3, .. }));
    assert_eq!(err.line(), Some(3));
}

#[test]
fn obj_non_finite_vertex_is_rejected_with_vertex_and_line() {
    for word in ["nan", "inf", "-inf", "NaN"] {
        let text = format!("v 0 0 0\nv 1 0 0\nv 0 {word} 0\nf 1 2 3\n");
        let (err, message) = load_error("non_finite", &text);
        assert!(
            matches!(err, MeshError::NonFinite { vertex: 3, .. }),
            "{message}"
        );
        assert_eq!(err.line(), Some(3));
        assert!(
            message.contains("bad.obj:3") && message.contains("vertex 3"),
            "{message}"
        );
    }
}

#[test]
fn obj_without_faces_is_empty() {
    let (err, message) = load_error("empty", "# nothing\nv 0 0 0\nv 1 0 0\n");
    assert!(
        matches!(
            err,
            MeshError::Empty {
                vertices: 2,
                triangles: 0,
                ..
            }
        ),
        "{message}"
    );
    let (err, _) = load_error("blank", "");
    assert!(matches!(err, MeshError::Empty { .. }));
}

// ---- retessellation ----------------------------------------------------------------

#[test]
fn bunny_retessellates_to_paper_1_sizes_keeping_the_surface() {
    let bunny = load_bunny();
    for target in [15_000, 20_000, 50_000] {
        let fine = retessellate(&bunny, target).unwrap();
        assert_eq!(fine.triangle_count(), target);
        assert_closed_solid("bunny", &fine, 0);
        assert!(relative_error(fine.signed_volume(), bunny.signed_volume()) < 1e-6);
        assert!(relative_error(fine.surface_area(), bunny.surface_area()) < 1e-6);
        // Longest first: the longest edge got shorter.
        assert!(longest_edge(&fine) < longest_edge(&bunny));
    }
}

fn longest_edge(mesh: &Mesh) -> f32 {
    let mut longest = 0.0f32;
    for t in 0..mesh.triangle_count() {
        let [a, b, c] = mesh.triangle(t);
        longest = longest
            .max(a.distance(b))
            .max(b.distance(c))
            .max(c.distance(a));
    }
    longest
}

#[test]
fn retessellation_welds_seams_and_handles_parity() {
    // The seam-duplicated torus refines on both sides of its seams.
    let torus = torus(1.0, 0.4, 31, 31);
    let fine = retessellate(&torus, 4000).unwrap();
    assert_eq!(fine.triangle_count(), 4000);
    assert_closed_solid("torus", &fine, 1);
    // Closed meshes have an even count: an odd target gives one less.
    assert_eq!(retessellate(&torus, 4001).unwrap().triangle_count(), 4000);
    // An open mesh can split a boundary edge and hit odd targets.
    let teapot = teapot(5);
    let fine = retessellate(&teapot, 1629).unwrap();
    assert_eq!(fine.triangle_count(), 1629);
    assert!(relative_error(fine.signed_volume(), teapot.signed_volume()) < 1e-5);
    // Same count: nothing to split.
    assert_eq!(retessellate(&cube(1.0), 12).unwrap().triangle_count(), 12);
    // Only refines.
    let err = retessellate(&cube(1.0), 10).unwrap_err();
    assert!(err.to_string().contains("only refines"), "{err}");
}

#[test]
fn retessellation_refuses_non_manifold_meshes() {
    let mut doubled = cube(1.0);
    doubled.triangles.push(doubled.triangles[0]);
    assert!(matches!(
        retessellate(&doubled, 100),
        Err(MeshError::Retessellate { .. })
    ));
}

#[test]
fn uniform_subdivision_quadruples_and_keeps_the_solid() {
    let knot = torus_knot(&TorusKnot::default());
    let fine = subdivide(&knot).unwrap();
    assert_counts(&fine, 1440 + 4320, 4 * 2880);
    assert_closed_solid("knot", &fine, 1);
    assert!(relative_error(fine.signed_volume(), knot.signed_volume()) < 1e-5);
}

// ---- the bunny ---------------------------------------------------------------------

#[test]
fn bunny_asset_is_closed_genus_0_and_outward() {
    let bunny = load_bunny();
    assert_counts(&bunny, 1839, 3674);
    assert_closed_solid("bunny", &bunny, 0);
    // Paper 4's bunny (Table 1: 2557 vertices, 5110 faces) is ours refined.
    let paper_4 = retessellate(&bunny, 5110).unwrap();
    assert_counts(&paper_4, 2557, 5110);
    assert_closed_solid("paper 4 bunny", &paper_4, 0);
    let from_file = load_obj(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/bunny.obj")).unwrap();
    assert_eq!(from_file, bunny);
}

#[test]
fn teapot_faces_point_out_of_every_part() {
    // Body, lid, spout and handle are oriented independently (they share no edge), so
    // check each: side walls of the body and the tubes (spout, handle) face away from
    // their plane of symmetry y = 0 where they are widest; the top of the lid faces up.
    let n = 4;
    let pot = teapot(n);
    let per_patch = 2 * n * n; // patches 0..20 lose no collapsed triangles
    let normals = pot.face_normals();
    let centroid = |t: usize| pot.triangle(t).iter().sum::<Vec3>() / 3.0;
    let part =
        |patches: std::ops::Range<usize>| (patches.start * per_patch)..(patches.end * per_patch);
    for (name, patches) in [("body", 4..12), ("handle", 12..16), ("spout", 16..20)] {
        let tris: Vec<usize> = part(patches).collect();
        let widest = tris
            .iter()
            .map(|&t| centroid(t).y.abs())
            .fold(0.0, f32::max);
        let sides: Vec<usize> = tris
            .iter()
            .copied()
            .filter(|&t| centroid(t).y.abs() > 0.9 * widest)
            .collect();
        assert!(!sides.is_empty());
        for t in sides {
            assert!(
                normals[t].y * centroid(t).y > 0.0,
                "{name} triangle {t} faces in"
            );
        }
    }
    let top: Vec<usize> = (0..pot.triangle_count())
        .filter(|&t| centroid(t).z > 3.1)
        .collect();
    assert!(
        !top.is_empty() && top.iter().all(|&t| normals[t].z > 0.0),
        "lid top faces down"
    );
    let bottom: Vec<usize> = (0..pot.triangle_count())
        .filter(|&t| centroid(t).z < 0.01)
        .collect();
    assert!(
        !bottom.is_empty() && bottom.iter().all(|&t| normals[t].z < 0.0),
        "bottom faces up"
    );
}

const TETRAHEDRON: &str =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";

#[test]
fn obj_with_a_byte_order_mark_loads() {
    let path = write_temp("bom", "bom.obj", &format!("\u{feff}{TETRAHEDRON}"));
    let mesh = load_obj(&path).unwrap();
    assert_counts(&mesh, 4, 4);
}

#[test]
fn obj_non_utf8_comment_is_accepted_and_a_non_utf8_vertex_names_its_line() {
    let dir = temp_dir("latin1");
    let comment = dir.join("comment.obj");
    let mut bytes = b"# caf\xe9 model\n".to_vec();
    bytes.extend_from_slice(TETRAHEDRON.as_bytes());
    std::fs::write(&comment, &bytes).unwrap();
    assert_counts(&load_obj(&comment).unwrap(), 4, 4);

    let vertex = dir.join("vertex.obj");
    std::fs::write(&vertex, b"v 0 0 0\nv 1 0 \xe9\nv 0 1 0\nf 1 2 3\n").unwrap();
    let err = load_obj(&vertex).unwrap_err();
    assert_eq!(err.line(), Some(2), "{err}");
    assert!(err.to_string().contains("not UTF-8"), "{err}");
}

#[test]
fn obj_error_quotes_at_most_the_start_of_a_huge_line() {
    let line = format!("f 1 2 {}", "x".repeat(100_000));
    let (err, message) = load_error("huge_line", &format!("v 0 0 0\nv 1 0 0\nv 0 1 0\n{line}\n"));
    assert_eq!(err.line(), Some(4), "{message}");
    assert!(message.len() < 300, "{} bytes of error", message.len());
    assert!(message.contains("100006 bytes"), "{message}");
}

#[test]
fn obj_io_errors_say_read_or_write_and_give_the_os_message_once() {
    let dir = temp_dir("io_errors");
    let missing = dir.join("missing.obj");
    let read = load_obj(&missing).unwrap_err().to_string();
    assert!(read.contains("cannot read"), "{read}");
    // Missing folders are made, so the write fails where a file stands in for the folder.
    std::fs::write(dir.join("a_file"), "not a folder").unwrap();
    let write = write_obj(&generate::cube(1.0), dir.join("a_file/x.obj"))
        .unwrap_err()
        .to_string();
    assert!(write.contains("cannot write"), "{write}");
    // The write names the part of the path that is a file instead of a raw OS error.
    assert!(write.contains("a_file is a file, not a folder"), "{write}");
    assert_eq!(read.matches("os error").count(), 1, "{read}");
    assert!(write.matches("os error").count() <= 1, "{write}");
}

/// Degeneracy is relative to the triangle's size: a cube scaled by 1e30 or 1e-30 (squares
/// beyond f32's range either way) has no zero-area triangle, and a collinear triangle at
/// those scales is still zero-area.
#[test]
fn degeneracy_is_scale_aware() {
    for scale in [1e30f32, 1e-30, 1e-19, 1e19] {
        let mut cube = generate::cube(1.0);
        for p in &mut cube.positions {
            *p *= scale;
        }
        let r = cube.validate();
        assert_eq!(r.zero_area_triangles, 0, "scale {scale}: {r}");
        assert!(r.is_usable(), "scale {scale}: {r}");
        let collinear = Mesh::new(
            vec![Vec3::ZERO, Vec3::X * scale, Vec3::X * (2.0 * scale)],
            vec![[0, 1, 2]],
        );
        assert_eq!(collinear.validate().zero_area_triangles, 1, "scale {scale}");
    }
}
