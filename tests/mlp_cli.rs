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
        for key in ["matmul", "activation"] {
            assert!(
                v["timings_ms"][key].as_f64().is_some_and(|t| t > 0.0),
                "{extra:?} {key}"
            );
        }
        // a step the CPU does not have is null, not a zero that was never measured
        let on_cpu = extra[0] == "--cpu";
        for key in ["texture_creation", "readback"] {
            let t = &v["timings_ms"][key];
            assert_eq!(t.is_null(), on_cpu, "{extra:?} {key}: {t}");
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

/// A 64 x 48 crop of text.png with text and ruled lines, written to `dir/name`.
fn text_crop(dir: &std::path::Path, name: &str) -> PathBuf {
    let photo = image::open(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/mlp/text.png"))
        .unwrap()
        .to_luma8();
    let path = dir.join(name);
    image::imageops::crop_imm(&photo, 100, 30, 64, 48)
        .to_image()
        .save(&path)
        .unwrap();
    path
}

fn path_str(p: &std::path::Path) -> String {
    p.display().to_string()
}

#[test]
fn detect_max_vectors_splits_the_batch_into_tiles() {
    let dir = scratch("max_vectors");
    let input = path_str(&text_crop(&dir, "crop.png"));
    let whole = json_of(&["mlp", "detect", &input, "--json"]);
    let tiled = json_of(&["mlp", "detect", &input, "--max-vectors", "500", "--json"]);
    // 64 x 48 = 3072 windows: one batch, or ceil(3072 / 500) = 7 tiles
    assert_eq!(whole["batches"], 1);
    assert_eq!(tiled["batches"], 7);
    assert_eq!(whole["text_pixels"], tiled["text_pixels"]);
    let out = classic_gpgpu(&["mlp", "detect", &input, "--max-vectors", "0"]);
    assert_clear_failure(&out, &["--max-vectors", "below 1"]);
}

#[test]
fn detect_on_the_cpu_reports_its_times_and_refuses_the_gpu_options() {
    let dir = scratch("cpu");
    let input = path_str(&text_crop(&dir, "crop.png"));
    let v = json_of(&["mlp", "detect", &input, "--cpu", "plain", "--json"]);
    assert_eq!(v["evaluated_by"], "cpu-plain");
    for key in ["matmul", "activation", "wall"] {
        assert!(
            v["timings_ms"][key].as_f64().is_some_and(|t| t > 0.0),
            "{key}: {}",
            v["timings_ms"]
        );
    }
    for key in ["texture_creation", "readback"] {
        assert!(v["timings_ms"][key].is_null(), "{key}: {}", v["timings_ms"]);
    }
    for command in ["detect", "run"] {
        for gpu_option in [
            &["--formulation", "packed"][..],
            &["--max-vectors", "5"],
            &["--inputs-per-pass", "3"],
        ] {
            let mut args = vec!["mlp", command];
            if command == "detect" {
                args.push(&input);
            } else {
                args.extend(["--network", "n.json", "--input", "x.json"]);
            }
            args.extend(["--cpu", "plain"]);
            args.extend_from_slice(gpu_option);
            let out = classic_gpgpu(&args);
            assert_clear_failure(&out, &["--cpu", gpu_option[0], "cannot be used with"]);
        }
    }
}

#[test]
fn detect_splits_the_product_into_passes_when_asked() {
    let dir = scratch("passes");
    let input = path_str(&text_crop(&dir, "crop.png"));
    let one = json_of(&["mlp", "detect", &input, "--json"]);
    let split = json_of(&["mlp", "detect", &input, "--inputs-per-pass", "15", "--json"]);
    assert_eq!(one["product_passes"], serde_json::json!([1, 1]));
    // the detector's 121 and 30 inputs, 15 per pass
    assert_eq!(split["product_passes"], serde_json::json!([9, 2]));
    // the same sums in the same order (tests/mlp_gpu.rs bounds the outputs); a pixel within
    // that bound of the threshold could flip, so allow 1% of the 3072
    let (a, b) = (
        one["text_pixels"].as_i64().unwrap(),
        split["text_pixels"].as_i64().unwrap(),
    );
    assert!((a - b).abs() <= 30, "{a} vs {b}");
    let out = classic_gpgpu(&[
        "mlp",
        "detect",
        &input,
        "--formulation",
        "packed",
        "--inputs-per-pass",
        "3",
    ]);
    assert_clear_failure(&out, &["faithful", "packed"]);
}

#[test]
fn detect_never_overwrites_its_input_and_replaces_an_output_only_with_force() {
    let dir = scratch("overwrite");
    let input = text_crop(&dir, "x.png");
    let before = std::fs::read(&input).unwrap();
    let same = [
        path_str(&input),
        path_str(&dir.join(".").join("x.png")),
        path_str(&dir.join("sub").join("..").join("x.png")),
    ];
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    for out_path in &same {
        for force in [false, true] {
            let mut args = vec!["mlp", "detect", same[0].as_str(), "--out", out_path];
            if force {
                args.push("--force");
            }
            let out = classic_gpgpu(&args);
            assert_clear_failure(&out, &["is the input", "never overwritten"]);
            assert_eq!(std::fs::read(&input).unwrap(), before, "{args:?}");
        }
    }
    let existing = dir.join("mask.png");
    std::fs::write(&existing, "keep me").unwrap();
    let existing_arg = path_str(&existing);
    let out = classic_gpgpu(&["mlp", "detect", &same[0], "--out", &existing_arg]);
    assert_clear_failure(&out, &["mask.png", "exists", "--force"]);
    assert_eq!(std::fs::read(&existing).unwrap(), b"keep me");
    json_of(&[
        "mlp",
        "detect",
        &same[0],
        "--out",
        &existing_arg,
        "--force",
        "--json",
    ]);
    assert_eq!(
        image::open(&existing).unwrap().to_luma8().dimensions(),
        (64, 48)
    );
}

#[test]
fn train_replaces_an_existing_file_only_with_force_and_never_an_input() {
    let dir = scratch("train_force");
    let existing = dir.join("existing.json");
    std::fs::write(&existing, "keep me").unwrap();
    let out_arg = path_str(&existing);
    let quick = ["--images", "2", "--epochs", "1", "--json"];
    let mut args = vec!["mlp", "train", "--out", &out_arg];
    args.extend(quick);
    let out = classic_gpgpu(&args);
    assert_clear_failure(&out, &["existing.json", "exists", "--force"]);
    assert_eq!(std::fs::read(&existing).unwrap(), b"keep me");
    args.push("--force");
    json_of(&args);
    let written = std::fs::read_to_string(&existing).unwrap();
    classic_gpgpu::mlp::Network::from_json(&written).expect("a network file");

    let (image, mask) = labelled_pair(&dir);
    let (image, mask) = (path_str(&image), path_str(&mask));
    let before = std::fs::read(&mask).unwrap();
    let out = classic_gpgpu(&[
        "mlp", "train", "--pair", &image, &mask, "--out", &mask, "--force",
    ]);
    assert_clear_failure(&out, &["is the input", "never overwritten"]);
    assert_eq!(std::fs::read(&mask).unwrap(), before);
    let out = classic_gpgpu(&["mlp", "train", "--images", "0", "--out", "n.json"]);
    assert_clear_failure(&out, &["--images", "below 1"]);
}

/// A 64 x 32 image and its mask, labelled against the shipped detector's habits: the
/// high-contrast 2 x 2 checkerboard of the left half is not text, the smooth grey of the
/// right half is.
fn labelled_pair(dir: &std::path::Path) -> (PathBuf, PathBuf) {
    let image = image::GrayImage::from_fn(64, 32, |x, y| {
        let grey = if x < 32 {
            if (x / 2 + y / 2) % 2 == 0 {
                30
            } else {
                220
            }
        } else {
            100 + (x + y) as u8
        };
        image::Luma([grey])
    });
    let mask =
        image::GrayImage::from_fn(64, 32, |x, _| image::Luma([if x < 32 { 255 } else { 0 }]));
    let (image_path, mask_path) = (dir.join("page.png"), dir.join("page_mask.png"));
    image.save(&image_path).unwrap();
    mask.save(&mask_path).unwrap();
    (image_path, mask_path)
}

/// Share of pixels whose class in `detected` (a mask written by `mlp detect`) is the truth's.
fn agreement(detected: &std::path::Path, truth: &std::path::Path) -> f64 {
    let (a, b) = (
        image::open(detected).unwrap().to_luma8(),
        image::open(truth).unwrap().to_luma8(),
    );
    let same = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| (p.0[0] < 128) == (q.0[0] < 128))
        .count();
    same as f64 / a.len() as f64
}

#[test]
fn train_on_an_image_and_mask_then_detect_with_the_retrained_network() {
    let dir = scratch("train_pair");
    let (image, mask) = labelled_pair(&dir);
    let network = dir.join("mine.json");
    let (image_arg, mask_arg, network_arg) =
        (path_str(&image), path_str(&mask), path_str(&network));
    let v = json_of(&[
        "mlp",
        "train",
        "--pair",
        &image_arg,
        &mask_arg,
        "--epochs",
        "10",
        "--out",
        &network_arg,
        "--json",
    ]);
    assert_eq!(v["data"]["pairs"][0]["text_pixels"], 32 * 32);
    // every pixel is a window: 1024 per class, 1 in 5 held out
    let held_out = v["held_out"]["windows"].as_u64().unwrap();
    assert_eq!(held_out + v["training_windows"].as_u64().unwrap(), 2048);
    assert!(v["held_out"]["accuracy"].as_f64().unwrap() > 0.9, "{v}");

    let (mine, shipped) = (dir.join("mine.png"), dir.join("shipped.png"));
    let d = json_of(&[
        "mlp",
        "detect",
        &image_arg,
        "--network",
        &network_arg,
        "--out",
        &path_str(&mine),
        "--json",
    ]);
    assert_eq!(d["network"], network_arg);
    json_of(&[
        "mlp",
        "detect",
        &image_arg,
        "--out",
        &path_str(&shipped),
        "--json",
    ]);
    let (with_mine, with_shipped) = (agreement(&mine, &mask), agreement(&shipped, &mask));
    assert!(
        with_mine > 0.9 && with_shipped < 0.6,
        "agreement with the mask: retrained {with_mine}, shipped {with_shipped}"
    );

    // a mask of another size, and a mask with no text, are refused naming the files
    let small = dir.join("small_mask.png");
    image::GrayImage::new(8, 8).save(&small).unwrap();
    let out = classic_gpgpu(&[
        "mlp",
        "train",
        "--pair",
        &image_arg,
        &path_str(&small),
        "--out",
        &path_str(&dir.join("a.json")),
    ]);
    assert_clear_failure(&out, &["page.png", "small_mask.png", "8 x 8", "64 x 32"]);
    let blank = dir.join("blank_mask.png");
    image::GrayImage::from_pixel(64, 32, image::Luma([255]))
        .save(&blank)
        .unwrap();
    let out = classic_gpgpu(&[
        "mlp",
        "train",
        "--pair",
        &image_arg,
        &path_str(&blank),
        "--out",
        &path_str(&dir.join("b.json")),
    ]);
    assert_clear_failure(&out, &["no pixel as text"]);
}

/// The sample the README shows: the shipped XOR network on the four corners of the square.
#[test]
fn the_shipped_sample_computes_xor() {
    let root = env!("CARGO_MANIFEST_DIR");
    let net = format!("{root}/assets/mlp/xor_network.json");
    let input = format!("{root}/assets/mlp/xor_inputs.json");
    for extra in [&[][..], &["--cpu", "plain"]] {
        let mut args = vec!["mlp", "run", "--network", &net, "--input", &input, "--json"];
        args.extend_from_slice(extra);
        let v = json_of(&args);
        let outputs: Vec<f64> = v["outputs"]
            .as_array()
            .unwrap()
            .iter()
            .map(|row| row[0].as_f64().unwrap())
            .collect();
        // sigmoid(±10) is 4.5e-5 from 0 or 1; fp32 adds far less.
        for (got, want) in outputs.iter().zip([0.0, 1.0, 1.0, 0.0]) {
            assert!((got - want).abs() < 1e-4, "{extra:?}: {outputs:?}");
        }
        assert_eq!(outputs.len(), 4);
    }
}
