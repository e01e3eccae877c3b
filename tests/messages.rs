//! Every message true and complete: it names the input, the value and what to do, never a
//! raw OS error alone, and a command a hint suggests runs as written. Each case here was
//! once false or bare (issue 43).

mod common;

use common::{assert_refused, classic_gpgpu, stderr};
use std::path::Path;
use std::process::Command;

fn text(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn the_no_display_hint_runs_as_written() {
    let dir = common::temp_dir("messages", "hint");
    let out = Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(["view", "mass", "cube", "--resolution", "32"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let err = assert_refused(&out, &["DISPLAY"]);
    let hint = err.split('`').nth(1).expect("a command in backticks");
    let words: Vec<&str> = hint.split_whitespace().collect();
    assert_eq!(words[0], "classic-gpgpu", "{hint}");
    let run = Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(&words[1..])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(run.status.success(), "`{hint}`: {}", stderr(&run));
    let png = image::open(dir.join("frame.png")).unwrap();
    assert!(png.width() > 0);
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn compare_takes_the_triangle_counts_as_its_help_writes_them() {
    let out = classic_gpgpu(&["lecture1", "compare", "--triangles", "300", "600", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        v.as_array()
            .map(Vec::len)
            .or(v["rows"].as_array().map(Vec::len)),
        Some(2),
        "{v}"
    );
}

#[test]
fn a_png_whose_header_claims_too_many_pixels_is_refused_with_its_size() {
    let dir = common::temp_dir("messages", "png");
    // A valid PNG signature and header for 2,000,000 x 2,000,000 grey pixels, no data.
    let chunk = |kind: &[u8], data: &[u8]| {
        let mut c = (data.len() as u32).to_be_bytes().to_vec();
        let mut body = kind.to_vec();
        body.extend_from_slice(data);
        c.extend_from_slice(&body);
        c.extend_from_slice(&crc32(&body).to_be_bytes());
        c
    };
    let mut header = Vec::new();
    header.extend_from_slice(&2_000_000u32.to_be_bytes());
    header.extend_from_slice(&2_000_000u32.to_be_bytes());
    header.extend_from_slice(&[8, 0, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend(chunk(b"IHDR", &header));
    // An empty zlib stream: the decoder reads up to the first data chunk.
    png.extend(chunk(
        b"IDAT",
        &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01],
    ));
    png.extend(chunk(b"IEND", &[]));
    let path = dir.join("huge.png");
    std::fs::write(&path, png).unwrap();
    let out = classic_gpgpu(&[
        "mlp",
        "detect",
        text(&path),
        "--out",
        text(&dir.join("m.png")),
    ]);
    assert_refused(
        &out,
        &["huge.png", "2000000 x 2000000", "512 MiB", "smaller image"],
    );
    std::fs::remove_dir_all(dir).ok();
}

/// CRC-32 (PNG's), bit by bit.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[test]
fn huge_and_degenerate_models_get_the_right_answer_or_the_real_reason() {
    let dir = common::temp_dir("messages", "models");
    // Two unit cubes in the same place: B moves by their side to touch A, at any scale.
    for scale in [1.0, 1e30, 1e-30] {
        let cube = common::scaled_cube_obj(&dir, "cube.obj", scale);
        let out = classic_gpgpu(&[
            "lecture1",
            "penetration",
            text(&cube),
            text(&cube),
            "--json",
        ]);
        assert!(out.status.success(), "scale {scale}: {}", stderr(&out));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let depth = v["depth"].as_f64().unwrap();
        assert!(
            (depth / scale - 1.0).abs() < 1e-3,
            "scale {scale}: depth {depth}"
        );
    }
    let point = common::scaled_cube_obj(&dir, "point.obj", 0.0);
    let unit = common::scaled_cube_obj(&dir, "unit.obj", 1.0);
    let out = classic_gpgpu(&["lecture1", "penetration", text(&point), text(&unit)]);
    assert_refused(&out, &["point.obj", "repeats a vertex"]);
    let err = stderr(&out);
    assert!(!err.contains("0 boundary"), "{err}");

    let out = classic_gpgpu(&[
        "lecture1",
        "distance-field",
        text(&unit),
        "--margin",
        "1e308",
        "--npy",
        text(&dir.join("d.npy")),
    ]);
    let err = assert_refused(&out, &["margin", "1e308", "smaller margin"]);
    assert!(!err.contains("single point"), "{err}");

    // The light's scene is scaled to the room: a cube 1e30 across lights as one 1 across.
    let light = |scene: &Path| {
        let out = classic_gpgpu(&[
            "lecture3",
            "light",
            "--scene",
            text(scene),
            "--vpls",
            "8",
            "--size",
            "16",
            "--json",
        ]);
        assert!(
            out.status.success(),
            "{}: {}",
            scene.display(),
            stderr(&out)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        v["light"]["rows"][0]["relative_rms_error"]
            .as_f64()
            .unwrap()
    };
    let big = common::scaled_cube_obj(&dir, "big.obj", 1e30);
    let (small, large) = (light(&unit), light(&big));
    assert!((small - large).abs() < 1e-3, "{small} vs {large}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_failed_write_names_the_file_once_and_the_reason() {
    let dir = common::temp_dir("messages", "full");
    let unit = common::scaled_cube_obj(&dir, "unit.obj", 1.0);
    let png = dir.join("t.png");
    // A file-size limit stands in for a full disk (its signal ignored: the write fails).
    let out = Command::new("bash")
        .arg("-c")
        .arg("trap '' XFSZ; ulimit -f 1; exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args([
            "lecture1",
            "penetration",
            text(&unit),
            text(&unit),
            "--png",
            text(&png),
        ])
        .output()
        .unwrap();
    let err = assert_refused(&out, &["t.png", "too large"]);
    assert_eq!(err.matches("t.png").count(), 1, "{err}");
    assert!(!png.exists());
    std::fs::remove_dir_all(dir).ok();
}
