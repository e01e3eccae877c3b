//! `--formulation classic|compute` on each paper's command: the JSON says which ran, and the
//! compute run gives the classic run's answer. Below OpenGL 4.3 (softpipe) asking for compute
//! is a clear error with a non-zero exit, and the classic default still runs.

use common::{classic_gpgpu, compute_context, json_of};

mod common;

/// The compute run, or on a context below 4.3 its clear error (then `None`).
fn compute_json(args: &[&str], has_compute: bool) -> Option<serde_json::Value> {
    if has_compute {
        return Some(json_of(args));
    }
    let out = classic_gpgpu(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} must fail below OpenGL 4.3");
    assert!(stderr.contains("needs OpenGL 4.3"), "{args:?}: {stderr}");
    None
}

#[test]
fn collide_scene_same_pairs_in_both_formulations() {
    let (_, compute) = compute_context();
    let args = [
        "--json",
        "collide-scene",
        "interlocking-tori",
        "--frames",
        "3",
        "--triangles",
        "800",
    ];
    let classic = json_of(&args);
    assert_eq!(classic["formulation"], "classic");
    let with = [&args[..], &["--formulation", "compute"]].concat();
    let Some(now) = compute_json(&with, compute) else {
        return;
    };
    assert_eq!(now["formulation"], "compute");
    for f in 0..3 {
        for key in ["caps", "ctps", "pctps"] {
            assert_eq!(
                now["frames"][f][key], classic["frames"][f][key],
                "frame {f} {key}"
            );
        }
    }
}

#[test]
fn mass_compute_matches_the_analytic_volume_whole_and_below_a_plane() {
    let (_, compute) = compute_context();
    let classic = json_of(&["--json", "mass", "torus"]);
    assert_eq!(classic["formulation"], "classic");
    assert_eq!(classic["peeling"]["max_peels"], 64);
    let Some(now) = compute_json(
        &["--json", "mass", "torus", "--formulation", "compute"],
        compute,
    ) else {
        return;
    };
    assert_eq!(now["formulation"], "compute");
    assert_eq!(now["peels"], 0);
    // No peeling ran, so no peel settings are reported for it.
    assert!(now["peeling"].is_null(), "{}", now["peeling"]);
    let (v, exact) = (
        now["volume"].as_f64().unwrap(),
        now["analytic"]["volume"].as_f64().unwrap(),
    );
    assert!((v - exact).abs() <= 1e-5 * exact, "{v} vs {exact}");
    // Below a plane through the torus (tilted by the paper object's pose or not, the plane
    // cuts it): the compute run clips in the kernel and gives the clipped solid's volume and
    // centre, as the classic run does within its resolution error.
    let below = ["--json", "mass", "torus", "--below", "0.1"];
    let classic_below = json_of(&below);
    let now = json_of(&[&below[..], &["--formulation", "compute"]].concat());
    assert_eq!(now["below"], 0.1);
    let (v, exact) = (
        now["volume"].as_f64().unwrap(),
        now["analytic"]["volume"].as_f64().unwrap(),
    );
    assert!(
        exact > 0.0 && (v - exact).abs() <= 1e-5 * exact,
        "{v} vs {exact}"
    );
    let c = classic_below["volume"].as_f64().unwrap();
    assert!((c - v).abs() <= 0.05 * v, "classic {c} vs compute {v}");
    for k in 0..3 {
        let (g, w) = (
            now["center_of_mass"][k].as_f64().unwrap(),
            now["analytic"]["center_of_mass"][k].as_f64().unwrap(),
        );
        assert!((g - w).abs() <= 1e-5, "centre {k}: {g} vs {w}");
    }
    // --dump still needs the classic formulation's images.
    let dump = std::env::temp_dir().join(format!("compute_cli_dump_{}", std::process::id()));
    let out = classic_gpgpu(&[
        "mass",
        "torus",
        "--formulation",
        "compute",
        "--dump",
        dump.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--dump") && err.contains("classic formulation"),
        "{err}"
    );
}

#[test]
fn mlp_run_compute_gives_the_faithful_outputs() {
    let (_, compute) = compute_context();
    let dir = std::env::temp_dir().join(format!("compute_cli_mlp_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let network = dir.join("net.json");
    let input = dir.join("in.json");
    std::fs::write(
        &network,
        r#"{"layers":[{"weights":[[0.5,-1.0,0.25],[1.5,0.5,-0.75]],"bias":[0.1,-0.2],
            "activation":"sigmoid"},{"weights":[[1.0,-2.0]],"bias":[0.3],"activation":"identity"}]}"#,
    )
    .unwrap();
    std::fs::write(&input, "[[1,2,3],[0.5,-1,0],[0,0,0]]").unwrap();
    let (n, i) = (network.to_str().unwrap(), input.to_str().unwrap());
    let classic = json_of(&["--json", "mlp", "run", "--network", n, "--input", i]);
    assert_eq!(classic["formulation"], "classic");
    let args = [
        "--json",
        "mlp",
        "run",
        "--network",
        n,
        "--input",
        i,
        "--formulation",
        "compute",
    ];
    if let Some(now) = compute_json(&args, compute) {
        assert_eq!(now["formulation"], "compute");
        assert_eq!(now["evaluated_by"], "gpu-compute");
        for (a, b) in now["outputs"]
            .as_array()
            .unwrap()
            .iter()
            .zip(classic["outputs"].as_array().unwrap())
        {
            let (a, b) = (a[0].as_f64().unwrap(), b[0].as_f64().unwrap());
            // Three-term sums of values near 1: a few fp32 ulps.
            assert!((a - b).abs() < 1e-5, "{a} vs {b}");
        }
        let out = classic_gpgpu(&[&args[1..], &["--max-vectors", "2"]].concat());
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("--max-vectors"), "{err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn crowd_compute_reports_its_formulation() {
    let (_, compute) = compute_context();
    let args = [
        "--json",
        "crowd",
        "--characters",
        "4",
        "--frames",
        "1",
        "--size",
        "64x48",
    ];
    assert_eq!(json_of(&args)["formulation"], "classic");
    let with = [&args[..], &["--formulation", "compute"]].concat();
    if let Some(now) = compute_json(&with, compute) {
        assert_eq!(now["formulation"], "compute");
        assert_eq!(now["run"]["characters"], 4);
        assert_eq!(now["run"]["passes"]["skinned"], 4);
    }
    let out = classic_gpgpu(&["crowd", "--formulation", "compute", "--skin-batch", "2"]);
    assert!(!out.status.success());
}

#[test]
fn buoyancy_compute_follows_the_cpu_solver_and_the_classic_one() {
    let (_, compute) = compute_context();
    let args = ["--json", "buoyancy", "--bodies", "3", "--steps", "12"];
    let classic = json_of(&args);
    assert_eq!(classic["formulation"], "classic");
    let cpu = json_of(&[&args[..], &["--cpu"]].concat());
    // One solver at a time.
    let out = classic_gpgpu(&[&args[..], &["--cpu", "--formulation", "compute"]].concat());
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--cpu") && err.contains("--formulation compute"),
        "{err}"
    );
    let Some(now) = compute_json(
        &[&args[..], &["--formulation", "compute"]].concat(),
        compute,
    ) else {
        return;
    };
    assert_eq!(now["formulation"], "compute");
    let position = |v: &serde_json::Value, k: usize| -> Vec<f64> {
        (0..3)
            .map(|i| v["state"][k]["position"][i].as_f64().unwrap())
            .collect()
    };
    let distance = |a: Vec<f64>, b: Vec<f64>| -> f64 {
        a.iter()
            .zip(&b)
            .map(|(x, y)| (x - y).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    for k in 0..3 {
        // fp32 sums against the CPU's f64 clip (1e-4 m after 12 steps, see
        // tests/mass_buoyancy_compute.rs); the classic 32x32 tiles within 5 cm.
        let d = distance(position(&now, k), position(&cpu, k));
        assert!(d <= 1e-4, "body {k}: compute {d} m from the CPU run");
        let d = distance(position(&now, k), position(&classic, k));
        assert!(d <= 0.05, "body {k}: compute {d} m from the classic run");
    }
}
