//! The `mass`, `buoyancy` and `mass-bench` commands as a user meets them.

use common::{classic_gpgpu, json_of};
use std::path::PathBuf;

mod common;

fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("classic-gpgpu-mass-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write_obj(dir: &std::path::Path, name: &str, faces: &str) -> String {
    let verts =
        "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n";
    let path = dir.join(name);
    std::fs::write(&path, format!("{verts}{faces}")).unwrap();
    path.to_string_lossy().into_owned()
}

/// A 2x2x2 cube, counter-clockwise outward (1-based OBJ indices).
const CUBE_FACES: &str = "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";

#[test]
fn mass_json_has_every_documented_field() {
    let dir = scratch("fields");
    let cube = write_obj(&dir, "cube.obj", CUBE_FACES);
    let v = json_of(&[
        "mass",
        &cube,
        "--resolution",
        "32",
        "--density",
        "3",
        "--json",
    ]);
    assert!(v["renderer"].as_str().is_some_and(|r| !r.is_empty()));
    assert_eq!(v["resolution"], 32);
    assert_eq!(v["peels"], 2);
    // An axis-aligned box on pixel boundaries is exact up to fp32: V = 8, m = 24,
    // I = m (b² + c²) / 12 = 16.
    assert!((v["volume"].as_f64().unwrap() - 8.0).abs() < 1e-4);
    assert!((v["mass"].as_f64().unwrap() - 24.0).abs() < 1e-3);
    let inertia = &v["inertia"];
    assert!(
        (inertia[0][0].as_f64().unwrap() - 16.0).abs() < 0.05,
        "{inertia}"
    );
    assert!((v["analytic"]["inertia"][2][2].as_f64().unwrap() - 16.0).abs() < 1e-4);
    assert_eq!(v["center_of_mass"].as_array().unwrap().len(), 3);
    // Timed as the report times: the median of at least 3 runs after an untimed one,
    // with the spread and the load beside it.
    for key in ["gpu", "gpu_wall", "analytic"] {
        let runs = &v["timings_ms"]["runs"][key];
        let (min, median, max) = (
            runs["min"].as_f64().unwrap(),
            runs["median"].as_f64().unwrap(),
            runs["max"].as_f64().unwrap(),
        );
        assert!(runs["runs"].as_u64().unwrap() >= 3, "{key}: {runs}");
        assert!(0.0 < min && min <= median && median <= max, "{key}: {runs}");
        assert_eq!(v["timings_ms"][key].as_f64(), Some(median), "{key}");
    }
    assert!(v["timings_ms"]["load"]["cores"].as_u64().unwrap() >= 1);
    // Where the wall time goes: one run with the stopping test by pass, and the same
    // passes timed with the layer count given in advance, by pass too.
    let names = |passes: &serde_json::Value| -> Vec<String> {
        passes
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p[0].as_str().unwrap().to_string())
            .collect()
    };
    let with_test = &v["timings_ms"]["stop_test_waits"];
    let with_names = names(&with_test["passes"]);
    assert!(
        with_names.contains(&"occlusion queries".to_string()),
        "{with_test}"
    );
    let known = &v["timings_ms"]["known_layers"];
    assert!(known["runs"]["runs"].as_u64().unwrap() >= 3, "{known}");
    assert!(known["runs"]["median"].as_f64().unwrap() > 0.0, "{known}");
    let known_names = names(&known["passes"]);
    assert!(
        known_names.contains(&"one peel (all bodies)".to_string()),
        "{known}"
    );
    assert!(
        !known_names.contains(&"occlusion queries".to_string()),
        "{known}"
    );
    // The same passes with no arithmetic (the integrands written as constants): their floor,
    // timed as they are.
    let turns = &v["timings_ms"]["no_arithmetic"];
    for key in ["passes", "floor"] {
        assert!(turns[key]["runs"].as_u64().unwrap() >= 3, "{turns}");
        assert!(turns[key]["median"].as_f64().unwrap() > 0.0, "{turns}");
    }
    assert!(v["framing"]["pixel_size"].as_f64().unwrap() > 0.0);
    assert_eq!(v["analytic"]["reliable"], true);
}

#[test]
fn mass_below_a_plane_uses_the_submerged_part() {
    let v = json_of(&["mass", "cube", "--below", "-0.5", "--json"]);
    // The paper's cube (edge 2) below z = -0.5: a 2 x 2 x 0.5 slab.
    assert!(
        (v["volume"].as_f64().unwrap() - 2.0).abs() < 1e-3,
        "{}",
        v["volume"]
    );
    assert!((v["analytic"]["volume"].as_f64().unwrap() - 2.0).abs() < 1e-6);
    assert!((v["center_of_mass"][2].as_f64().unwrap() + 0.75).abs() < 1e-3);
}

#[test]
fn inverted_mesh_is_reported_never_a_silent_positive_mass() {
    let dir = scratch("inverted");
    let flipped: String = CUBE_FACES
        .lines()
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            format!("f {} {} {}\n", f[1], f[3], f[2])
        })
        .collect();
    let cube = write_obj(&dir, "inside_out.obj", &flipped);
    let out = classic_gpgpu(&["mass", &cube, "--json"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["mass"].as_f64().unwrap() < 0.0);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("inside out"), "{err}");
}

#[test]
fn open_mesh_is_reported_and_its_analytic_result_marked_unreliable() {
    let dir = scratch("open");
    let open: String = CUBE_FACES
        .lines()
        .skip(2)
        .map(|l| format!("{l}\n"))
        .collect();
    let mesh = write_obj(&dir, "open.obj", &open);
    let out = classic_gpgpu(&["mass", &mesh, "--json"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["closed"], false);
    assert_eq!(v["analytic"]["reliable"], false);
    assert!(String::from_utf8_lossy(&out.stderr).contains("open"));
}

#[test]
fn bad_input_is_a_clear_error() {
    for (args, needle) in [
        (vec!["mass", "no-such-model.obj"], "no-such-model.obj"),
        (vec!["mass", "cube", "--resolution", "1"], "--resolution 1"),
        (vec!["mass", "cube", "--density", "-2"], "--density"),
        (vec!["buoyancy", "--bodies", "0"], "--bodies 0"),
        (
            vec!["buoyancy", "--png-every", "x", "/tmp"],
            "--png-every x",
        ),
    ] {
        let out = classic_gpgpu(&args);
        assert!(!out.status.success(), "{args:?} should fail");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    let dir = scratch("garbage");
    let path = dir.join("garbage.obj");
    std::fs::write(&path, "v 0 0 0\nf 1 2 9\n").unwrap();
    let out = classic_gpgpu(&["mass", path.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("garbage.obj"));
}

#[test]
fn dump_writes_the_integrands_of_each_peel() {
    let dir = scratch("dump");
    let v = json_of(&[
        "mass",
        "torus",
        "--resolution",
        "16",
        "--dump",
        dir.to_str().unwrap(),
        "--json",
    ]);
    let peels = v["peels"].as_u64().unwrap();
    for k in 1..=peels {
        for t in 0..3 {
            assert!(
                dir.join(format!("peel{k}_target{t}.png")).is_file(),
                "peel {k} target {t}"
            );
        }
    }
    // Where each peel reaches, in one picture: the deep peels of a few texels show there.
    assert!(dir.join("layers.png").is_file());
}

#[test]
fn buoyancy_runs_and_writes_frames() {
    let dir = scratch("frames");
    let v = json_of(&[
        "buoyancy",
        "--bodies",
        "5",
        "--steps",
        "4",
        "--resolution",
        "16",
        "--png-every",
        "2",
        dir.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["bodies"], 5);
    assert_eq!(v["state"].as_array().unwrap().len(), 5);
    assert!(v["steps_per_second"].as_f64().unwrap() > 0.0);
    assert!(v["state"][0]["orientation_xyzw"].as_array().unwrap().len() == 4);
    assert!(dir.join("frame00000.png").is_file() && dir.join("frame00002.png").is_file());
}

#[test]
fn mass_bench_quick_regenerates_the_tables_and_figures() {
    let dir = scratch("bench");
    let v = json_of(&[
        "mass-bench",
        "--quick",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(v["id"], "paper4");
    let tables = v["tables"].as_array().unwrap();
    assert!(tables.len() >= 4);
    assert_eq!(
        tables[0]["rows"].as_array().unwrap().len(),
        7,
        "Table 1 has the seven objects"
    );
    for f in v["figures"].as_array().unwrap() {
        assert!(dir.join(f["file"].as_str().unwrap()).is_file(), "{f}");
    }
    assert!(
        v["results"]["buoyancy"]["steps_per_second"]
            .as_f64()
            .unwrap()
            > 0.0
    );
}

/// A box turned off the axes: the JSON's principal moments are the eigenvalues of the
/// inertia tensor (the closed form m (b² + c²) / 12 ...), not its diagonal.
#[test]
fn mass_json_reports_principal_moments_of_a_rotated_box() {
    let dir = scratch("principal");
    let (a, b, c) = (2.0f64, 1.0, 0.5);
    let q = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.7, -0.4, 1.1);
    let mut obj = String::new();
    for i in 0..8 {
        let p = glam::DVec3::new(
            if i & 1 == 0 { -a } else { a },
            if i & 2 == 0 { -b } else { b },
            if i & 4 == 0 { -c } else { c },
        ) / 2.0;
        let w = q * p;
        obj += &format!("v {} {} {}\n", w.x, w.y, w.z);
    }
    let path = dir.join("box.obj");
    std::fs::write(&path, format!("{obj}{CUBE_FACES}")).unwrap();
    let v = json_of(&["mass", path.to_str().unwrap(), "--density", "2", "--json"]);
    let m = 2.0 * a * b * c;
    let mut want = [
        m * (b * b + c * c) / 12.0,
        m * (a * a + c * c) / 12.0,
        m * (a * a + b * b) / 12.0,
    ];
    want.sort_by(f64::total_cmp);
    for k in 0..3 {
        let exact = v["analytic"]["principal_moments"][k].as_f64().unwrap();
        let gpu = v["principal_moments"][k].as_f64().unwrap();
        assert!(
            (exact - want[k]).abs() < 1e-6 * want[2],
            "{exact} vs {}",
            want[k]
        );
        assert!(
            ((gpu - want[k]) / want[k]).abs() < 0.05,
            "{gpu} vs {}",
            want[k]
        );
    }
    let diagonal = v["analytic"]["inertia"][0][0].as_f64().unwrap();
    assert!(want.iter().all(|w| (w - diagonal).abs() > 0.01 * want[2]));
}

/// `--max-peels` below the knot's layers warns (stderr and JSON) and says it stopped;
/// zero is refused; `--order keep-layers` agrees with the default.
#[test]
fn max_peels_warns_and_order_is_selectable() {
    let out = classic_gpgpu(&["mass", "knot", "--max-peels", "2", "--json"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["peeling"]["truncated"], true);
    assert_eq!(v["peels"], 2);
    assert!(String::from_utf8_lossy(&out.stderr).contains("--max-peels"));
    assert!(v["warnings"][0].as_str().unwrap().contains("limit of 2"));
    let all = json_of(&["mass", "knot", "--json"]);
    assert_eq!(all["peeling"]["truncated"], false);
    assert!(all["warnings"].as_array().unwrap().is_empty());
    let kept = json_of(&["mass", "knot", "--order", "keep-layers", "--json"]);
    assert_eq!(kept["peeling"]["order"], "keep-layers");
    let (x, y) = (
        all["volume"].as_f64().unwrap(),
        kept["volume"].as_f64().unwrap(),
    );
    assert!((x - y).abs() < 1e-5 * x, "{x} vs {y}");
    let out = classic_gpgpu(&["mass", "knot", "--max-peels", "0"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--max-peels 0"));
}

/// `--profile` lists the passes with GPU and wall times, and the buoyancy table adds the
/// CPU steps.
#[test]
fn profile_lists_every_pass() {
    let v = json_of(&["mass", "torus", "--below", "0.1", "--profile", "--json"]);
    let rows = v["profile"]["rows"].as_array().unwrap();
    let names: Vec<&str> = rows.iter().map(|r| r["name"].as_str().unwrap()).collect();
    for pass in [
        "depth peel",
        "fluid surface depth",
        "fluid surface patch",
        "reduction",
    ] {
        assert!(names.iter().any(|n| n.contains(pass)), "{pass}: {names:?}");
    }
    assert!(rows.iter().all(|r| r["wall_ms"].as_f64().unwrap() >= 0.0));
    let v = json_of(&[
        "buoyancy",
        "--bodies",
        "3",
        "--steps",
        "2",
        "--resolution",
        "16",
        "--profile",
        "--json",
    ]);
    let rows = v["profile"]["rows"].as_array().unwrap();
    assert!(rows
        .iter()
        .any(|r| r["name"] == "buoyancy: rigid-body step"));
    assert!(rows
        .iter()
        .any(|r| r["name"].as_str().unwrap().starts_with("wait: ")));
    assert!(
        v["warnings"].as_array().unwrap().is_empty(),
        "the scene's shapes are closed"
    );
}
