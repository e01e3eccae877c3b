//! Lecture 1, the 3D distance field by Hoff et al.'s distance meshes (`distance-field
//! --method mesh`): every value within the meshes' stated bound of brute force in f64 (the
//! exact field) and of parry3d's closest points (an independent reference), on convex,
//! non-convex and random meshes, with and without a clamp; and the command's report.
//!
//! The bound (`MeshBound::tolerance`): a value is at least the exact distance less the
//! rasterizer's coverage error (2^-8 pixel snapping, 0.016 voxel on llvmpipe and softpipe)
//! and at most the tessellation bound (the asked error) above it, plus fp32 rounding.

use classic_gpgpu::lecture1::distance_field::independent::parry_field;
use classic_gpgpu::lecture1::distance_field::mesh_slices::MeshSlices;
use classic_gpgpu::lecture1::distance_field::reference::brute_force;
use classic_gpgpu::lecture1::distance_field::{DistanceField, Grid};
use classic_gpgpu::mesh::generate::{cube, torus_closed};
use classic_gpgpu::mesh::Mesh;
use common::{classic_gpgpu, context, json_of, soup};

mod common;

/// The lowest and highest (mesh - exact) over the grid, voxels.
fn range(meshes: &DistanceField, exact: &DistanceField) -> (f64, f64) {
    let h = exact.grid.spacing;
    meshes
        .values
        .iter()
        .zip(&exact.values)
        .map(|(&m, &e)| (m as f64 - e as f64) / h)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        })
}

/// The meshes' field of `mesh` at `n`^3 within `error` voxels against brute force and
/// parry3d; returns the highest (mesh - exact), voxels.
fn check(name: &str, mesh: &Mesh, n: usize, clamp: Option<f64>, error: f64) -> f64 {
    let ctx = context();
    let grid = Grid::around(mesh, n, Grid::default_margin(mesh)).unwrap();
    let (field, timings, bound) = MeshSlices::new(&ctx)
        .unwrap()
        .field(mesh, &grid, clamp, error)
        .unwrap();
    assert!(timings.triangles_drawn > 0);
    assert!(
        bound.tessellation_voxels <= error + 1e-12,
        "{name}: {bound:?}"
    );
    let exact = brute_force(mesh, &grid, clamp);
    let deepest = exact.values.iter().fold(0.0f64, |a, &v| a.max(v as f64)) / grid.spacing;
    let (below, above) = bound.tolerance(deepest);
    let (lo, hi) = range(&field, &exact);
    assert!(
        lo >= -below && hi <= above,
        "{name} at {n}^3, clamp {clamp:?}, error {error}: mesh - exact in [{lo}, {hi}] voxels, \
         outside [-{below}, {above}]"
    );
    // parry3d's fp32 projection adds its own rounding (coordinates of order 1).
    let parry = parry_field(mesh, &grid, clamp).unwrap();
    let slack = 1e-5 / grid.spacing;
    let (lo, hi) = range(&field, &parry);
    assert!(
        lo >= -below - slack && hi <= above + slack,
        "{name}: mesh - parry3d in [{lo}, {hi}] voxels"
    );
    hi
}

#[test]
fn meshes_stay_within_their_bound_of_the_exact_field() {
    check("cube", &cube(1.0), 12, None, 0.5);
    check("torus", &torus_closed(0.6, 0.25, 10, 6), 12, None, 0.5);
    check("soup", &soup(6, 0.5, 7), 12, None, 0.5);
}

#[test]
fn meshes_with_a_clamp_and_a_finer_error() {
    check("cube, clamped", &cube(1.0), 11, Some(0.2), 0.5);
    check("soup, clamped", &soup(5, 0.5, 3), 11, Some(0.15), 0.5);
    // A finer error is kept too (the meshes get more sectors and rings).
    let fine = check("soup, fine", &soup(5, 0.5, 3), 11, None, 0.05);
    assert!(fine <= 0.05 + 0.02, "{fine}");
}

#[test]
fn a_bad_error_is_refused() {
    let ctx = context();
    let mesh = cube(1.0);
    let grid = Grid::around(&mesh, 8, 0.1).unwrap();
    let meshes = MeshSlices::new(&ctx).unwrap();
    for bad in [0.0, -1.0, f64::NAN] {
        let e = meshes.field(&mesh, &grid, None, bad).err().unwrap();
        assert!(e.to_string().contains("error"), "{e}");
    }
}

#[test]
fn distance_field_command_by_meshes_reports_its_error_against_the_exact_field() {
    let dir = common::temp_dir("lecture1", "mesh-field-command");
    let obj = dir.join("soup.obj");
    classic_gpgpu::mesh::write_obj(&soup(4, 0.5, 5), &obj).unwrap();
    let npy = dir.join("field.npy");
    let npy_arg = npy.to_str().unwrap();
    let base = [
        "lecture1",
        "distance-field",
        obj.to_str().unwrap(),
        "--resolution",
        "12",
        "--npy",
        npy_arg,
        "--force",
    ];
    let mut args = vec!["--json"];
    args.extend(base);
    args.extend(["--method", "mesh", "--mesh-error", "0.25"]);
    let report = json_of(&args);
    assert_eq!(report["method"], "mesh");
    let m = &report["mesh"];
    assert_eq!(m["within_bound"], true, "{m}");
    assert_eq!(m["asked_error_voxels"], 0.25);
    let max = m["max_error_vs_exact_voxels"].as_f64().unwrap();
    let mean = m["mean_error_vs_exact_voxels"].as_f64().unwrap();
    assert!(mean <= max && max <= 0.25 + 0.02, "{m}");
    assert_eq!(m["features"]["faces"], 4);
    assert_eq!(m["features"]["edges"], 12);
    // The plain text names both errors; bad combinations are refused with the flag named.
    let mut plain = base.to_vec();
    plain.extend(["--method", "mesh"]);
    let out = classic_gpgpu(&plain);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && text.contains("max") && text.contains("mean"),
        "{text}"
    );
    for (extra, words) in [
        (&["--mesh-error", "0.5"][..], "--method mesh"),
        (
            &["--method", "mesh", "--mesh-error", "0"][..],
            "--mesh-error",
        ),
        (
            &["--method", "mesh", "--formulation", "compute"][..],
            "compute",
        ),
    ] {
        let mut bad = base.to_vec();
        bad.extend(extra);
        let out = classic_gpgpu(&bad);
        let err = common::stderr(&out);
        assert!(
            !out.status.success() && err.contains(words),
            "{extra:?}: {err}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
