//! Nothing of the user's is lost: outputs are checked before any work, written whole or not at
//! all (a file-size limit stands in for a full disk), and options that would be ignored are
//! refused.

mod common;

use common::{assert_refused, classic_gpgpu};
use std::path::Path;
use std::process::Command;

fn text(p: &Path) -> String {
    p.to_str().unwrap().to_string()
}

/// Runs the binary with every file it writes limited to `kib` KiB (`ulimit -f`, with the
/// signal that limit sends ignored so the write fails as on a full disk).
fn with_file_limit(kib: u32, args: &[&str]) -> std::process::Output {
    Command::new("bash")
        .arg("-c")
        .arg(format!("trap '' XFSZ; ulimit -f {kib}; exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(args)
        .output()
        .expect("bash runs")
}

/// Only `names` are in `dir` (no temporary file left behind).
fn assert_only(dir: &Path, names: &[&str]) {
    let mut found: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    found.sort();
    let mut want: Vec<String> = names.iter().map(|n| n.to_string()).collect();
    want.sort();
    assert_eq!(found, want);
}

#[test]
fn crowd_png_is_checked_before_the_run() {
    let dir = common::temp_dir("safe-writes", "crowd");
    let existing = dir.join("frame.png");
    std::fs::write(&existing, "keep me").unwrap();
    let small = [
        "crowd",
        "--characters",
        "2",
        "--frames",
        "1",
        "--size",
        "32x32",
    ];
    let run = |extra: &[&str]| {
        let mut args = small.to_vec();
        args.extend(extra);
        classic_gpgpu(&args)
    };
    let e = text(&existing);
    assert_refused(&run(&["--png", &e]), &["frame.png", "exists", "--force"]);
    let jpg = dir.join("frame.jpg");
    std::fs::write(&jpg, "keep me too").unwrap();
    assert_refused(
        &run(&["--png", &text(&jpg), "--force"]),
        &["frame.jpg", ".png"],
    );
    assert_eq!(std::fs::read(&existing).unwrap(), b"keep me");
    assert_eq!(std::fs::read(&jpg).unwrap(), b"keep me too");
    let out = run(&["--png", &e, "--force"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(image::open(&existing).unwrap().width(), 32);
    assert_only(&dir, &["frame.jpg", "frame.png"]);
}

#[test]
fn png_outputs_refuse_other_formats_before_touching_the_file() {
    let dir = common::temp_dir("safe-writes", "formats");
    let jpg = dir.join("mask.jpg");
    let bmp = dir.join("map.bmp");
    std::fs::write(&jpg, "mine").unwrap();
    std::fs::write(&bmp, "mine").unwrap();
    let image = dir.join("page.png");
    image::GrayImage::from_fn(24, 16, |x, _| image::Luma([(x * 10) as u8]))
        .save(&image)
        .unwrap();
    let out = classic_gpgpu(&[
        "mlp",
        "detect",
        &text(&image),
        "--out",
        &text(&jpg),
        "--force",
    ]);
    assert_refused(&out, &["mask.jpg", "must end in .png"]);
    let out = classic_gpgpu(&[
        "lecture3",
        "height-map",
        "--size",
        "8",
        "--out",
        &text(&bmp),
        "--force",
    ]);
    assert_refused(&out, &["map.bmp", "must end in .png"]);
    assert_eq!(std::fs::read(&jpg).unwrap(), b"mine");
    assert_eq!(std::fs::read(&bmp).unwrap(), b"mine");
    // A folder is not a file name.
    let out = classic_gpgpu(&["lecture3", "height-map", "--out", &text(&dir), "--force"]);
    assert_refused(&out, &["is a folder"]);
}

#[test]
fn a_screenshot_never_replaces_the_demos_input() {
    let dir = common::temp_dir("safe-writes", "view");
    let image = dir.join("page.png");
    image::GrayImage::from_fn(24, 16, |x, _| image::Luma([(x * 10) as u8]))
        .save(&image)
        .unwrap();
    let before = std::fs::read(&image).unwrap();
    let i = text(&image);
    let out = classic_gpgpu(&[
        "view",
        "mlp",
        "detect",
        &i,
        "--headless",
        "--frames",
        "0",
        "--size",
        "32x32",
        "--screenshot",
        &i,
        "--force",
    ]);
    assert_refused(&out, &["is the input", "never overwritten"]);
    assert_eq!(std::fs::read(&image).unwrap(), before);
}

#[test]
fn a_write_that_fails_leaves_the_old_file_and_exits_non_zero() {
    let dir = common::temp_dir("safe-writes", "full");
    // The network is several KiB of JSON; the limit lets 1 KiB through.
    let network = dir.join("net.json");
    std::fs::write(&network, "the old network").unwrap();
    let n = text(&network);
    let quick = ["--images", "2", "--epochs", "1"];
    let mut args = vec!["mlp", "train", "--out", &n, "--force"];
    args.extend(quick);
    let out = with_file_limit(1, &args);
    assert_refused(&out, &["net.json"]);
    assert_eq!(std::fs::read(&network).unwrap(), b"the old network");
    // A PNG that does not fit: an error, and no empty file.
    let map = dir.join("map.png");
    let out = with_file_limit(
        1,
        &[
            "lecture3",
            "height-map",
            "--size",
            "128",
            "--out",
            &text(&map),
        ],
    );
    assert_refused(&out, &["map.png"]);
    assert_only(&dir, &["net.json"]);
    // The same commands without the limit write the files.
    let out = classic_gpgpu(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    classic_gpgpu::mlp::Network::from_json(&std::fs::read_to_string(&network).unwrap())
        .expect("a network");
}

/// A unit cube at `offset` as OBJ lines, its vertices numbered from `first` (1-based).
fn cube_obj(offset: [f32; 3], first: usize) -> String {
    let mut s = String::new();
    for k in 0..8 {
        let (x, y, z) = ((k & 1) as f32, ((k >> 1) & 1) as f32, ((k >> 2) & 1) as f32);
        s += &format!("v {} {} {}\n", x + offset[0], y + offset[1], z + offset[2]);
    }
    // Outward faces (vertex k at x = k & 1, y = k >> 1 & 1, z = k >> 2 & 1).
    for [a, b, c, d] in [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ] {
        let v = |i: usize| i + first;
        s += &format!(
            "f {} {} {}\nf {} {} {}\n",
            v(a),
            v(b),
            v(c),
            v(a),
            v(c),
            v(d)
        );
    }
    s
}

fn json(out: &std::process::Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}

#[test]
fn overlapping_pieces_are_not_called_reliable() {
    let dir = common::temp_dir("safe-writes", "overlap");
    let path = dir.join("two_cubes.obj");
    std::fs::write(
        &path,
        cube_obj([0.0; 3], 1) + &cube_obj([0.25, 0.25, 0.5], 9),
    )
    .unwrap();
    let p = text(&path);
    let out = classic_gpgpu(&["mass", &p, "--resolution", "64", "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let v = json(&out);
    assert!(
        stderr.contains("pieces 0 and 1 of the mesh overlap"),
        "{stderr}"
    );
    assert_eq!(v["analytic"]["reliable"], false);
    assert_eq!(
        v["analytic"]["overlapping_pieces"],
        serde_json::json!([[0, 1]])
    );
    assert!(v["analytic"]["computes"]
        .as_str()
        .unwrap()
        .contains("sum of the pieces"));
    assert!(stderr.contains("the sum of the pieces"), "{stderr}");
    // Both count the shared 0.75 x 0.75 x 0.5 twice (the union is 1.71875): what is computed
    // is the sum, 2.0; the GPU's within its 64 x 64 resolution error (measured 1.6%).
    let analytic = v["analytic"]["volume"].as_f64().unwrap();
    assert!((analytic - 2.0).abs() < 1e-9, "{analytic}");
    let gpu = v["volume"].as_f64().unwrap();
    assert!((gpu - 2.0).abs() < 0.03 * 2.0, "{gpu}");
    // Apart, the same cubes are one reliable answer.
    std::fs::write(&path, cube_obj([0.0; 3], 1) + &cube_obj([3.0, 0.0, 0.0], 9)).unwrap();
    let v = json(&classic_gpgpu(&[
        "mass",
        &p,
        "--resolution",
        "64",
        "--json",
    ]));
    assert_eq!(v["analytic"]["reliable"], true);
    // A face given twice is named as such.
    let doubled = cube_obj([0.0; 3], 1) + "f 1 3 4\n";
    std::fs::write(&path, doubled).unwrap();
    let out = classic_gpgpu(&["mass", &p, "--resolution", "32", "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("1 faces that repeat another face's corners"),
        "{stderr}"
    );
}

#[test]
fn silent_answers_are_errors_naming_the_value() {
    let out = classic_gpgpu(&["mass", "cube", "--density", "1e308", "--resolution", "32"]);
    assert_refused(&out, &["--density 1e308", "smaller --density"]);
    assert!(!String::from_utf8_lossy(&out.stdout).contains("inf"));
    assert_refused(
        &classic_gpgpu(&["selftest", "--only", "gl,bogus"]),
        &["--only bogus"],
    );
    let out = classic_gpgpu(&[
        "crowd",
        "--formulation",
        "compute",
        "--method",
        "vertex-shader",
        "--characters",
        "1",
        "--frames",
        "1",
    ]);
    assert_refused(&out, &["--method vertex-shader", "compute formulation"]);
    let dir = common::temp_dir("safe-writes", "silent");
    let shot = text(&dir.join("shot.png"));
    let out = classic_gpgpu(&[
        "view",
        "mass",
        "cube",
        "--resolution",
        "16",
        "--headless",
        "--frames",
        "0",
        "--size",
        "32x32",
        "--buffer",
        "99",
        "--screenshot",
        &shot,
    ]);
    assert_refused(&out, &["--buffer 99", "0 to"]);
    assert!(!dir.join("shot.png").exists());
}

#[test]
fn collide_refuses_classic_options_under_compute_and_warns_moller_far_from_unit_scale() {
    let dir = common::temp_dir("safe-writes", "collide");
    let (a, b) = (dir.join("a.obj"), dir.join("b.obj"));
    std::fs::write(&a, cube_obj([0.0; 3], 1)).unwrap();
    std::fs::write(&b, cube_obj([0.5, 0.5, 0.5], 1)).unwrap();
    let (a_text, b_text) = (text(&a), text(&b));
    for option in [["--readback", "full"], ["--max-tile", "64"]] {
        let out = classic_gpgpu(&[
            "collide",
            &a_text,
            &b_text,
            "--formulation",
            "compute",
            option[0],
            option[1],
        ]);
        assert_refused(
            &out,
            &[
                &format!("{} {}", option[0], option[1]),
                "compute formulation",
            ],
        );
    }
    // Unit scale: no warning; 1e25: a warning at run time.
    let out = classic_gpgpu(&[
        "collide",
        &a_text,
        &b_text,
        "--predicate",
        "moller",
        "--json",
    ]);
    json(&out);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("warning: --predicate moller"));
    let big = |offset: f32| {
        cube_obj([offset; 3], 1)
            .lines()
            .map(|l| match l.strip_prefix("v ") {
                Some(xyz) => {
                    let v: Vec<f32> = xyz.split(' ').map(|c| c.parse().unwrap()).collect();
                    format!("v {:e} {:e} {:e}\n", v[0] * 1e25, v[1] * 1e25, v[2] * 1e25)
                }
                None => format!("{l}\n"),
            })
            .collect::<String>()
    };
    std::fs::write(&a, big(0.0)).unwrap();
    std::fs::write(&b, big(0.5)).unwrap();
    let out = classic_gpgpu(&[
        "collide",
        &a_text,
        &b_text,
        "--predicate",
        "moller",
        "--json",
    ]);
    json(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--predicate moller") && stderr.contains("1.5e25"),
        "{stderr}"
    );
}

#[test]
fn messages_say_each_thing_once() {
    let dir = common::temp_dir("safe-writes", "messages");
    let fake = dir.join("fake.png");
    std::fs::write(&fake, "not a PNG at all").unwrap();
    let out = classic_gpgpu(&["mlp", "detect", &text(&fake)]);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success());
    let signature = err.matches("signature").count();
    assert!(signature <= 1, "{err}");
    let out = classic_gpgpu(&["collide-scene", "no-such-scene", "--frames", "1"]);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_refused(&out, &["no-such-scene", "interlocking-tori"]);
    assert_eq!(err.matches("interlocking-tori").count(), 1, "{err}");
    let out = classic_gpgpu(&["mesh", "generate", "cube", "--out", &text(&dir), "--force"]);
    assert_refused(&out, &["is a folder"]);
    // serde's own "unknown variant" once, not again through the error's source.
    let network = dir.join("net.json");
    let layer = r#"{"weights":[[1,2]],"bias":[0],"activation":"bogus"}"#;
    std::fs::write(&network, format!(r#"{{"layers":[{layer}]}}"#)).unwrap();
    let input = dir.join("in.json");
    std::fs::write(&input, "[[1,2]]").unwrap();
    let out = classic_gpgpu(&[
        "mlp",
        "run",
        "--network",
        &text(&network),
        "--input",
        &text(&input),
    ]);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_refused(&out, &["net.json", "unknown variant `bogus`"]);
    assert_eq!(err.matches("unknown variant").count(), 1, "{err}");
}

#[test]
fn random_names_the_bad_value() {
    for (flag, value) in [("--steps", "0"), ("--size", "1")] {
        let mut args = vec!["lecture3", "random", "--size", "8", "--steps", "4"];
        let at = args.iter().position(|a| *a == flag).unwrap();
        args[at + 1] = value;
        assert_refused(&classic_gpgpu(&args), &[&format!("{flag} {value}")]);
    }
}
