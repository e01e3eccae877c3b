//! Issue 43's wrong answers with exit 0, each now a right answer or a clear refusal: options
//! a run would ignore, screenshots too small to show their demo, degeneracy at any scale,
//! underflowing masses, `--glsl-dir` entries that are not shader files, and a report made with
//! `--glsl-dir` that says so.

use common::{classic_gpgpu, json_of};
use std::path::Path;

mod common;

/// Runs the binary, requires a refusal (exit 1, or clap's 2) without a panic, returns stderr.
fn refused(args: &[&str]) -> String {
    let out = classic_gpgpu(args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!out.status.success(), "{args:?} succeeded: {err}");
    assert!(matches!(out.status.code(), Some(1 | 2)), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    err
}

fn text(p: &Path) -> String {
    p.to_str().unwrap().to_string()
}

/// Each combination where one option would be ignored is refused, naming it.
#[test]
fn options_a_run_would_ignore_are_refused() {
    let dir = common::temp_dir("input-refusals", "ignored");
    let png = text(&dir.join("pictures"));
    for (args, needles) in [
        (
            vec!["learn", "--list", "--png", &png],
            vec!["--list", "--png"],
        ),
        (
            vec!["learn", "--list", "--exercise", "1"],
            vec!["--list", "--exercise"],
        ),
        (
            vec![
                "mass",
                "cube",
                "--order",
                "keep-layers",
                "--formulation",
                "compute",
            ],
            vec!["--order", "compute formulation"],
        ),
        (
            vec![
                "buoyancy",
                "--bodies",
                "2",
                "--steps",
                "2",
                "--order",
                "keep-layers",
                "--cpu",
            ],
            vec!["--order", "--cpu"],
        ),
        (
            vec![
                "crowd",
                "--characters",
                "2",
                "--frames",
                "1",
                "--vs-batch",
                "4",
            ],
            vec!["--vs-batch", "two-pass", "--method vertex-shader"],
        ),
        (
            vec![
                "crowd",
                "--characters",
                "2",
                "--frames",
                "1",
                "--method",
                "vertex-shader",
                "--skin-batch",
                "4",
            ],
            vec!["--skin-batch", "vertex-shader"],
        ),
    ] {
        let err = refused(&args);
        for needle in needles {
            assert!(err.contains(needle), "{args:?}: no {needle:?} in {err}");
        }
    }
    assert!(!dir.join("pictures").exists());
}

/// A screenshot below 256x192 holds little but the caption: refused, saying the minimum, and
/// nothing is written; at the minimum it is written.
#[test]
fn screenshots_too_small_to_show_the_demo_are_refused() {
    let dir = common::temp_dir("input-refusals", "screenshot");
    let shot = dir.join("small.png");
    let s = text(&shot);
    let args = |size: &'static str| {
        vec![
            "view",
            "lecture3",
            "random",
            "--headless",
            "--frames",
            "1",
            "--size",
            size,
            "--screenshot",
            &s,
        ]
    };
    for size in ["64x48", "255x192", "256x191"] {
        let err = refused(&args(size));
        assert!(err.contains(size) && err.contains("256x192"), "{err}");
        assert!(!shot.exists());
    }
    let out = classic_gpgpu(&args("256x192"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(image::open(&shot).unwrap().width(), 256);
}

/// `mesh check` of a cube scaled by 1e30 and by 1e-30: no triangle is zero-area.
#[test]
fn mesh_check_finds_no_degenerate_triangle_in_a_scaled_cube() {
    let dir = common::temp_dir("input-refusals", "scaled");
    for scale in ["1e30", "1e-30"] {
        let path =
            common::scaled_cube_obj(&dir, &format!("cube-{scale}.obj"), scale.parse().unwrap());
        let v = json_of(&["mesh", "check", &text(&path), "--json"]);
        assert_eq!(v["zero_area_triangles"], 0, "{scale}: {v}");
        assert_eq!(v["triangles"], 12, "{scale}: {v}");
        assert_eq!(v["closed"], true, "{scale}: {v}");
    }
}

/// A density whose mass underflows to a subnormal or zero is refused, like one that overflows.
#[test]
fn a_mass_that_underflows_is_refused() {
    let err = refused(&["mass", "cube", "--resolution", "8", "--density", "1e-320"]);
    assert!(
        err.contains("--density 1e-320") && err.contains("smallest normal number"),
        "{err}"
    );
    let v = json_of(&[
        "mass",
        "cube",
        "--resolution",
        "8",
        "--density",
        "1e-300",
        "--json",
    ]);
    // 8e-300, a normal number: printed as such, not refused.
    let mass = v["mass"].as_f64().unwrap();
    assert!(
        mass.is_normal() && (mass / 8e-300 - 1.0).abs() < 0.05,
        "{v}"
    );
}

/// A `--glsl-dir` entry at a shader's path that is a folder, a dangling link or a FIFO is an
/// error naming it (never the compiled-in copy in silence).
#[test]
fn glsl_dir_entries_that_are_not_files_are_errors() {
    let shader = "glsl/lecture3/random_step.frag";
    let run = |dir: &Path| {
        refused(&[
            "--glsl-dir",
            &text(dir),
            "lecture3",
            "random",
            "--size",
            "8",
            "--steps",
            "2",
        ])
    };
    let root = common::temp_dir("input-refusals", "glsl-dir");
    let folder = root.join("folder");
    std::fs::create_dir_all(folder.join(shader)).unwrap();
    let err = run(&folder);
    assert!(err.contains(shader) && err.contains("a folder"), "{err}");
    let dangling = root.join("dangling");
    std::fs::create_dir_all(dangling.join("glsl/lecture3")).unwrap();
    std::os::unix::fs::symlink(root.join("nowhere.frag"), dangling.join(shader)).unwrap();
    let err = run(&dangling);
    assert!(err.contains(shader) && err.contains("dangling"), "{err}");
    let fifo = root.join("fifo");
    std::fs::create_dir_all(fifo.join("glsl/lecture3")).unwrap();
    let made = std::process::Command::new("mkfifo")
        .arg(fifo.join(shader))
        .status()
        .unwrap();
    assert!(made.success());
    let err = run(&fifo);
    assert!(
        err.contains(shader) && err.contains("not a regular file"),
        "{err}"
    );
}

/// A report made with `--glsl-dir` records the folder in results.json and marks its results
/// as from modified shaders in the HTML; it is not merged with a run on the shipped shaders.
#[test]
fn a_report_made_with_glsl_dir_says_so() {
    let root = common::temp_dir("input-refusals", "report");
    let shaders = root.join("shaders");
    std::fs::create_dir_all(&shaders).unwrap();
    let out = root.join("report");
    let _ = std::fs::remove_dir_all(&out);
    let run = |glsl_dir: Option<&Path>| {
        let mut args: Vec<String> = Vec::new();
        if let Some(dir) = glsl_dir {
            args.extend(["--glsl-dir".to_string(), text(dir)]);
        }
        args.extend(["reproduce", "--quick", "--only", "blocks", "--out"].map(String::from));
        args.push(text(&out));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        classic_gpgpu(&args)
    };
    let made = run(Some(&shaders));
    assert!(
        made.status.success(),
        "{}",
        String::from_utf8_lossy(&made.stderr)
    );
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    assert_eq!(
        results["glsl_dir"],
        text(&shaders).as_str(),
        "{}",
        results["glsl_dir"]
    );
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(
        html.contains("Modified shaders") && html.contains("--glsl-dir"),
        "no mark"
    );
    let mixed = run(None);
    assert!(!mixed.status.success());
    let err = String::from_utf8_lossy(&mixed.stderr);
    assert!(
        err.contains("--glsl-dir") && err.contains("compiled-in"),
        "{err}"
    );
}
