//! `classic-gpgpu mlp run | detect` and `mlp-bench` as a user meets them: JSON output, and
//! bad files giving a clear message and a non-zero exit without a panic.

use common::{classic_gpgpu, json_of};
use std::path::PathBuf;
use std::process::Output;

mod common;

/// A scratch directory for this test binary.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mlp_cli_{}_{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &std::path::Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

const NET: &str = r#"{"layers":[
    {"weights":[[1,2,3],[0.5,-1,0.25]],"bias":[0.5,-1],"activation":"sigmoid"},
    {"weights":[[2,-3]],"bias":[0.25],"activation":"identity"}]}"#;

fn expected(x: [f64; 3]) -> f64 {
    let sig = |v: f64| 1.0 / (1.0 + (-v).exp());
    let h0 = sig(x[0] + 2.0 * x[1] + 3.0 * x[2] + 0.5);
    let h1 = sig(0.5 * x[0] - x[1] + 0.25 * x[2] - 1.0);
    2.0 * h0 - 3.0 * h1 + 0.25
}

#[test]
fn run_prints_outputs_and_timings_as_json() {
    let dir = scratch("run");
    let net = write(&dir, "net.json", NET);
    let input = write(&dir, "x.json", "[[1,0,2],[0,1,4],[-1,0.5,0]]");
    let xs = [[1.0, 0.0, 2.0], [0.0, 1.0, 4.0], [-1.0, 0.5, 0.0]];
    for extra in [
        &["--formulation", "faithful"][..],
        &["--formulation", "packed"],
        &["--cpu", "plain"],
    ] {
        let mut args = vec!["mlp", "run", "--network", &net, "--input", &input, "--json"];
        args.extend_from_slice(extra);
        let v = json_of(&args);
        assert!(v["renderer"].as_str().is_some_and(|r| !r.is_empty()));
        for key in ["texture_creation", "matmul", "activation"] {
            assert!(
                v["timings_ms"][key].as_f64().is_some_and(|t| t >= 0.0),
                "{key}"
            );
        }
        let outputs = v["outputs"].as_array().unwrap();
        assert_eq!(outputs.len(), 3);
        for (row, x) in outputs.iter().zip(xs) {
            let got = row[0].as_f64().unwrap();
            assert!(
                (got - expected(x)).abs() < 1e-5,
                "{extra:?}: {got} vs {}",
                expected(x)
            );
        }
    }
}

fn assert_clear_failure(out: &Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "should fail: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "missing {n:?} in: {err}");
    }
}

#[test]
fn bad_network_and_input_files_are_named_in_the_error() {
    let dir = scratch("bad");
    let input = write(&dir, "x.json", "[[1,2]]");
    let cases = [
        (
            r#"{"layers":[{"weights":[[1,2],[3]],"bias":[0,0],"activation":"sigmoid"}]}"#,
            "row 1 has 1 values",
        ),
        (
            r#"{"layers":[{"weights":[[1,2]],"bias":[0],"activation":"relu"}]}"#,
            "unknown variant `relu`",
        ),
        (
            r#"{"layers":[{"weights":[[1,NaN]],"bias":[0],"activation":"sigmoid"}]}"#,
            "NaN",
        ),
        (
            r#"{"layers":[{"weights":[[1,2]],"bias":[0],"activation":"sigmoid"},{"weights":[[1,2]],"bias":[0],"activation":"sigmoid"}]}"#,
            "layer 1 takes 2 inputs",
        ),
    ];
    for (i, (text, needle)) in cases.iter().enumerate() {
        let net = write(&dir, &format!("net{i}.json"), text);
        let out = classic_gpgpu(&[
            "mlp",
            "run",
            "--network",
            &net,
            "--input",
            &input,
            "--cpu",
            "plain",
        ]);
        assert_clear_failure(&out, &[&format!("net{i}.json"), needle]);
    }
    let net = write(
        &dir,
        "good.json",
        r#"{"layers":[{"weights":[[1,2,3]],"bias":[0],"activation":"sigmoid"}]}"#,
    );
    let out = classic_gpgpu(&["mlp", "run", "--network", &net, "--input", &input]);
    assert_clear_failure(&out, &["x.json", "input vector 0 has 2 values", "takes 3"]);
    let out = classic_gpgpu(&[
        "mlp",
        "run",
        "--network",
        "/nonexistent/net.json",
        "--input",
        &input,
    ]);
    assert_clear_failure(&out, &["/nonexistent/net.json"]);
}

#[test]
fn detect_writes_a_mask_and_refuses_a_non_image() {
    let dir = scratch("detect");
    let photo = image::open(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/mlp/text.png"))
        .unwrap()
        .to_luma8();
    let crop = image::imageops::crop_imm(&photo, 100, 30, 64, 48).to_image();
    let input = dir.join("crop.png");
    crop.save(&input).unwrap();
    let mask = dir.join("mask.png");
    let (input, mask_arg) = (input.display().to_string(), mask.display().to_string());
    let v = json_of(&["mlp", "detect", &input, "--out", &mask_arg, "--json"]);
    let written = image::open(&mask).unwrap().to_luma8();
    assert_eq!(written.dimensions(), (64, 48));
    let black = written.pixels().filter(|p| p.0[0] == 0).count() as u64;
    assert_eq!(v["text_pixels"].as_u64(), Some(black));
    assert!(written.pixels().all(|p| p.0[0] == 0 || p.0[0] == 255));

    let not_image = write(&dir, "x.png", "not a png");
    let out = classic_gpgpu(&["mlp", "detect", &not_image]);
    assert_clear_failure(&out, &["x.png"]);
}

#[test]
fn bench_quick_reports_table_1_beside_the_paper() {
    let dir = scratch("bench");
    let v = json_of(&[
        "mlp-bench",
        "--quick",
        "--out",
        &dir.display().to_string(),
        "--json",
    ]);
    assert_eq!(v["id"], "paper3");
    let table1 = &v["tables"][0];
    assert!(table1["header"].to_string().contains("paper GPU"));
    assert_eq!(table1["rows"][1][1], "0.03"); // the paper's matrix multiplication time
    let methods: Vec<&str> = v["results"]["measurements"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["method"].as_str().unwrap())
        .collect();
    for m in ["GpuFaithful", "GpuPacked", "CpuPlain", "CpuOptimised"] {
        assert!(methods.contains(&m), "{methods:?}");
    }
    assert!(dir.join("paper3_fig2b_mask.png").exists());
}

/// The shipped detector is what `mlp train` writes (about 15 s in release; run with
/// `cargo test --release -- --ignored`).
#[test]
#[ignore = "trains the full detector"]
fn mlp_train_reproduces_the_shipped_weights() {
    let dir = scratch("train");
    let out = dir.join("detector.json");
    let result = classic_gpgpu(&[
        "mlp",
        "train",
        "--out",
        &out.display().to_string(),
        "--json",
    ]);
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let shipped = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/mlp/text_detector.json"
    ))
    .unwrap();
    assert!(
        std::fs::read(&out).unwrap() == shipped,
        "retrained weights differ from assets/mlp/text_detector.json"
    );
}
