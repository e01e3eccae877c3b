//! `classic-gpgpu lecture3 ...` as a user meets it: JSON output with the GPU checked against
//! its CPU reference and timings beside the renderer's name; bad input (missing or non-image
//! height maps, 1x1 maps, NaN parameters, outputs that exist or are the input) giving a
//! clear message and a non-zero exit, with nothing overwritten.

use common::{classic_gpgpu, json_of};
use std::path::PathBuf;

mod common;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lecture3_cli_{}_{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the binary, requires failure, returns stderr.
fn fails(args: &[&str]) -> String {
    let out = classic_gpgpu(args);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!out.status.success(), "{args:?} succeeded: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?} panicked: {stderr}");
    stderr
}

#[test]
fn pyramid_and_displace_report_agreement_with_the_cpu_and_timings() {
    let v = json_of(&["lecture3", "pyramid", "--json"]);
    assert_eq!(v["pyramid"]["equal_to_cpu"], true);
    assert!(v["renderer"].as_str().unwrap().contains("OpenGL"));
    assert!(v["pyramid"]["gpu_ms"].as_f64().unwrap() > 0.0);
    let dir = scratch("displace");
    let png = dir.join("frame.png");
    let v = json_of(&[
        "lecture3",
        "displace",
        "--size",
        "48",
        "--elevation",
        "10",
        "--png",
        png.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["comparison"]["wrong_surface"], 0);
    assert_eq!(v["comparison"]["outside_tolerance"], 0);
    assert!(v["cpu_over_gpu"].as_f64().unwrap() > 0.0);
    assert_eq!(image::open(&png).unwrap().width(), 48);
    let v = json_of(&[
        "lecture3",
        "displace",
        "--size",
        "48",
        "--frames",
        "3",
        "--method",
        "relief",
        "--no-check",
        "--out",
        dir.join("frames").to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["written"].as_array().unwrap().len(), 3);
    assert!(v["comparison"].is_null());
}

#[test]
fn each_technique_runs_and_agrees_with_its_reference() {
    let v = json_of(&[
        "lecture3", "light", "--vpls", "8", "--size", "32", "--theta", "0.4", "--json",
    ]);
    assert!(v["light"]["brute_gpu_vs_cpu"].as_f64().unwrap() < 1e-3);
    let v = json_of(&[
        "lecture3",
        "function",
        "--texels",
        "64",
        "--per-pixel",
        "4",
        "--json",
    ]);
    let e = &v["error"];
    assert!(e["max_error"].as_f64().unwrap() <= e["bound"].as_f64().unwrap() + 1e-6);
    let v = json_of(&[
        "lecture3", "random", "--size", "32", "--steps", "4", "--json",
    ]);
    assert_eq!(v["random"]["bit_exact"], true);
    let v = json_of(&[
        "lecture3",
        "depth-mask",
        "--size",
        "32",
        "--iterations",
        "16",
        "--fraction",
        "0.3",
        "--json",
    ]);
    let d = &v["depth_mask"];
    assert_eq!(d["masked_fragments"], d["active"]);
    let v = json_of(&[
        "lecture3",
        "histogram",
        "--image",
        concat!(env!("CARGO_MANIFEST_DIR"), "/assets/lecture3/height.png"),
        "--json",
    ]);
    let counts: f64 = v["counts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_f64().unwrap())
        .sum();
    assert_eq!(
        counts,
        64.0 * 64.0,
        "every grey level of the shipped map in a bin"
    );
    assert_eq!(v["outside"], 0);
}

#[test]
fn bad_height_maps_are_named() {
    let dir = scratch("maps");
    let missing = dir.join("missing.png");
    let err = fails(&[
        "lecture3",
        "displace",
        "--height",
        missing.to_str().unwrap(),
    ]);
    assert!(
        err.contains("missing.png") && err.contains("cannot open"),
        "{err}"
    );
    let text = dir.join("text.png");
    std::fs::write(&text, "not a picture").unwrap();
    let err = fails(&["lecture3", "pyramid", "--height", text.to_str().unwrap()]);
    assert!(
        err.contains("text.png") && err.contains("not a readable image"),
        "{err}"
    );
    let one = dir.join("one.png");
    image::save_buffer(&one, &[9], 1, 1, image::ColorType::L8).unwrap();
    let err = fails(&["lecture3", "displace", "--height", one.to_str().unwrap()]);
    assert!(err.contains("1x1") && err.contains("2x2"), "{err}");
}

#[test]
fn nan_and_out_of_range_parameters_are_named() {
    for (args, name) in [
        (&["lecture3", "displace", "--depth", "NaN"][..], "--depth"),
        (
            &["lecture3", "displace", "--elevation", "NaN"][..],
            "--elevation",
        ),
        (
            &["lecture3", "displace", "--elevation", "90"][..],
            "--elevation",
        ),
        (&["lecture3", "light", "--theta", "NaN"][..], "--theta"),
        (&["lecture3", "light", "--vpls", "256"][..], "--vpls"),
        (
            &["lecture3", "depth-mask", "--fraction", "NaN"][..],
            "--fraction",
        ),
        (
            &["lecture3", "depth-mask", "--iterations", "100000"][..],
            "--iterations",
        ),
        (&["lecture3", "function", "--texels", "1"][..], "--texels"),
        (&["lecture3", "histogram", "--bins", "0"][..], "--bins"),
        (
            &["lecture3", "octree", "--resolution", "33"][..],
            "--resolution",
        ),
        (
            &["lecture3", "displace", "--prefilter", "--method", "relief"][..],
            "--prefilter",
        ),
    ] {
        let err = fails(args);
        assert!(err.contains(name), "{args:?}: {err}");
    }
}

#[test]
fn outputs_are_not_overwritten() {
    let dir = scratch("outputs");
    let png = dir.join("exists.png");
    std::fs::write(&png, "keep me").unwrap();
    let err = fails(&["lecture3", "pyramid", "--png", png.to_str().unwrap()]);
    assert!(err.contains("--force"), "{err}");
    assert_eq!(std::fs::read_to_string(&png).unwrap(), "keep me");
    let out = classic_gpgpu(&[
        "lecture3",
        "pyramid",
        "--png",
        png.to_str().unwrap(),
        "--force",
    ]);
    assert!(out.status.success());
    assert!(image::open(&png).is_ok());
    // The input is never the output, not even with --force.
    let map = dir.join("map.png");
    let m = classic_gpgpu(&[
        "lecture3",
        "height-map",
        "--size",
        "8",
        "--out",
        map.to_str().unwrap(),
    ]);
    assert!(m.status.success());
    let before = std::fs::read(&map).unwrap();
    let err = fails(&[
        "lecture3",
        "displace",
        "--height",
        map.to_str().unwrap(),
        "--png",
        map.to_str().unwrap(),
        "--force",
    ]);
    assert!(err.contains("never overwritten"), "{err}");
    assert_eq!(std::fs::read(&map).unwrap(), before);
}

#[test]
fn prefiltered_displacement_and_the_octree_check_themselves_against_the_cpu() {
    let v = json_of(&[
        "lecture3",
        "displace",
        "--size",
        "48",
        "--distance",
        "9",
        "--prefilter",
        "--json",
    ]);
    let c = &v["comparison"];
    for k in [
        "wrong_surface",
        "outside_tolerance",
        "wrong_kind",
        "wrong_normal",
        "wrong_colour",
    ] {
        assert_eq!(c[k], 0, "{k}: {v}");
    }
    let q = &v["prefilter_quality"];
    assert!(q["prefiltered_error"].as_f64().unwrap().is_finite(), "{v}");
    let v = json_of(&[
        "lecture3",
        "octree",
        "--resolution",
        "16",
        "--points",
        "2000",
        "--size",
        "32",
        "--json",
    ]);
    for search in v["searches"].as_array().unwrap() {
        let c = &search["comparison"];
        assert_eq!(c["wrong_voxel"], 0, "{v}");
        assert_eq!(c["cpu_octree_vs_flat"], 0, "{v}");
    }
}

/// `pyramid --npy DIR`: one float32 file per kind and level, as the GPU drew them, equal to
/// the CPU pyramid (max and min bit for bit; the mean within a few fp32 ulps of the f64 means
/// of the pixels each node covers, as `lecture3_pyramid.rs` states); existing files only with
/// --force.
#[test]
fn pyramid_npy_writes_every_level_equal_to_the_cpu_pyramid() {
    use classic_gpgpu::lecture3::height_map::{HeightMap, SHIPPED_SIZE};
    use classic_gpgpu::lecture3::pyramid::{cpu_pyramid, Extreme};
    let dir = scratch("pyramid_npy").join("levels");
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().unwrap();
    let v = json_of(&["lecture3", "pyramid", "--npy", d, "--json"]);
    let map = HeightMap::generated(SHIPPED_SIZE);
    let levels = (SHIPPED_SIZE.trailing_zeros() + 1) as usize;
    assert_eq!(v["written"].as_array().unwrap().len(), 3 * levels, "{v}");
    for (kind, extreme) in [
        ("max", Extreme::Max),
        ("min", Extreme::Min),
        ("mean", Extreme::Mean),
    ] {
        let cpu = cpu_pyramid(map.width(), map.height(), map.heights(), extreme);
        assert_eq!(cpu.len(), levels);
        for (l, want) in cpu.iter().enumerate() {
            let path = dir.join(format!("{kind}_{l}.npy"));
            let (shape, got) = classic_gpgpu::files::read_npy(&path).unwrap();
            assert_eq!(
                shape,
                [want.height as usize, want.width as usize],
                "{kind} {l}"
            );
            for (g, w) in got.iter().zip(&want.values) {
                let tol = if extreme == Extreme::Mean {
                    4.0 * f32::EPSILON
                } else {
                    0.0
                };
                assert!((g - w).abs() <= tol, "{kind} level {l}: GPU {g}, CPU {w}");
            }
        }
    }
    // The folder rule of every writer: a rerun replaces its own files; a file of the user's
    // is refused without --force, kept with it, and never replaced even when it has the name
    // of a level.
    json_of(&["lecture3", "pyramid", "--npy", d, "--json"]);
    let theirs = scratch("pyramid_npy").join("theirs");
    std::fs::create_dir_all(&theirs).unwrap();
    std::fs::write(theirs.join("max_0.npy"), "mine").unwrap();
    let t = theirs.to_str().unwrap();
    let err = fails(&["lecture3", "pyramid", "--npy", t]);
    assert!(
        err.contains("max_0.npy") && err.contains("--force"),
        "{err}"
    );
    let err = fails(&["lecture3", "pyramid", "--npy", t, "--force"]);
    assert!(
        err.contains("max_0.npy") && err.contains("move that file"),
        "{err}"
    );
    assert_eq!(std::fs::read(theirs.join("max_0.npy")).unwrap(), b"mine");
}

/// The pyramid method agrees with its exact tracer down to the closest camera accepted (the
/// near plane no longer clips the box's near faces: the far faces are drawn), and a camera
/// behind the far plane is refused.
#[test]
fn displace_agrees_at_the_closest_distance_and_refuses_beyond_the_far_plane() {
    for distance in ["0.5", "0.55"] {
        let v = json_of(&[
            "lecture3",
            "displace",
            "--size",
            "64",
            "--distance",
            distance,
            "--json",
        ]);
        let c = &v["comparison"];
        assert!(c["compared"].as_u64().unwrap() > 1000, "{distance}: {c}");
        for key in [
            "wrong_surface",
            "outside_tolerance",
            "wrong_kind",
            "wrong_normal",
        ] {
            assert_eq!(c[key], 0, "{distance}: {key} in {c}");
        }
    }
    let err = fails(&["lecture3", "displace", "--size", "16", "--distance", "100"]);
    assert!(
        err.contains("--distance 100") && err.contains("far plane"),
        "{err}"
    );
}

/// Options that the chosen method or input would ignore are refused, naming them.
#[test]
fn options_the_run_would_ignore_are_refused() {
    let err = fails(&[
        "lecture3",
        "displace",
        "--size",
        "16",
        "--linear-steps",
        "8",
    ]);
    assert!(
        err.contains("--linear-steps") && err.contains("--method relief"),
        "{err}"
    );
    let err = fails(&[
        "lecture3",
        "displace",
        "--size",
        "16",
        "--binary-steps",
        "2",
    ]);
    assert!(err.contains("--binary-steps"), "{err}");
    let map = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/lecture3/height.png");
    let err = fails(&["lecture3", "histogram", "--image", map, "--values", "5"]);
    assert!(err.contains("--values") && err.contains("--image"), "{err}");
    // Relief mapping takes them.
    let v = json_of(&[
        "lecture3",
        "displace",
        "--size",
        "16",
        "--method",
        "relief",
        "--linear-steps",
        "8",
        "--no-check",
        "--json",
    ]);
    assert_eq!(v["method"]["relief"]["linear_steps"], 8, "{v}");
}
