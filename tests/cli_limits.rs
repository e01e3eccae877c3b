//! Counts beyond what this machine can hold, zero counts, non-finite thresholds and images in
//! formats this build does not read: each a clear error naming the option, before any work.

use common::classic_gpgpu;

mod common;

/// Runs the binary, requires failure without a panic, and returns stderr.
fn refused(args: &[&str]) -> String {
    let out = classic_gpgpu(args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!out.status.success(), "{args:?} succeeded");
    assert_eq!(
        out.status.code(),
        Some(if err.contains("For more information") {
            2
        } else {
            1
        }),
        "{args:?}: {err}"
    );
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    err
}

/// usize::MAX of anything is more than any machine holds: refused at once, naming the option
/// and the limit, instead of aborting in the allocator or growing without output.
#[test]
fn counts_beyond_memory_are_refused_before_allocating() {
    let dir = common::temp_dir("cli-limits", "counts");
    let out = dir.join("net.json");
    let out = out.to_str().unwrap();
    // Outputs are checked for their format first, so the mesh goes to an .obj name.
    let obj = dir.join("torus.obj");
    let obj = obj.to_str().unwrap();
    let max = "18446744073709551615";
    for (args, option) in [
        (vec!["crowd", "--characters", max], "--characters"),
        (vec!["crowd", "--characters", "4294967295"], "--characters"),
        (
            vec!["mlp", "train", "--epochs", max, "--out", out],
            "--epochs",
        ),
        (
            vec!["mlp", "train", "--images", max, "--out", out],
            "--images",
        ),
        (
            vec!["collide-scene", "interlocking-tori", "--triangles", max],
            "--triangles",
        ),
        (
            vec!["collide-scene", "interlocking-tori", "--frames", max],
            "--frames",
        ),
        (vec!["crowd", "--frames", max], "--frames"),
        (vec!["buoyancy", "--steps", max], "--steps"),
        (
            vec![
                "mesh",
                "generate",
                "torus",
                "--triangles",
                max,
                "--out",
                obj,
            ],
            "--triangles",
        ),
        (
            vec!["mlp", "train", "--windows-per-class", max, "--out", out],
            "--windows-per-class",
        ),
    ] {
        let start = std::time::Instant::now();
        let err = refused(&args);
        assert!(
            err.contains(&format!("{option} "))
                && err.contains("it is above")
                && err.contains("give a whole number from"),
            "{args:?}: {err}"
        );
        // Not a speed check: a count that was not refused would run for days (--epochs,
        // --frames) or allocate beyond memory, so a refusal that took minutes did work first.
        // The bound is far above a refusal's milliseconds, even on a machine loaded 10x.
        assert!(
            start.elapsed().as_secs() < 120,
            "{args:?} took {:?}",
            start.elapsed()
        );
    }
    assert!(!std::path::Path::new(out).exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn zero_counts_are_refused() {
    for (args, option) in [
        (
            vec!["collide-scene", "interlocking-tori", "--frames", "0"],
            "--frames",
        ),
        (
            vec!["collide-scene", "interlocking-tori", "--triangles", "0"],
            "--triangles",
        ),
        (
            vec!["collide-bench", "--quick", "--frames", "0"],
            "--frames",
        ),
        (
            vec!["collide-bench", "--quick", "--triangles", "0"],
            "--triangles",
        ),
        (vec!["mlp", "train", "--images", "0"], "--images"),
        (vec!["crowd", "--characters", "0"], "--characters"),
    ] {
        let err = refused(&args);
        assert!(
            err.contains(option) && err.contains("it is below 1"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("plot"), "{args:?}: {err}");
    }
}

#[test]
fn a_threshold_that_is_not_a_finite_number_is_refused() {
    for value in ["nan", "inf", "-inf"] {
        let err = refused(&["mlp", "detect", "assets/mlp/text.png", "--threshold", value]);
        assert!(
            err.contains("--threshold") && err.contains("not a threshold"),
            "{value}: {err}"
        );
    }
}

/// A JPEG (here its signature and header, which is how the format is recognised) is named as
/// such, with what to do, instead of the decoder's "format not supported".
#[test]
fn a_jpeg_image_is_refused_naming_the_format() {
    let dir = common::temp_dir("cli-limits", "jpeg");
    let jpeg = dir.join("page.jpg");
    let mut bytes = vec![0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x10];
    bytes.extend_from_slice(b"JFIF\0\x01\x01\0\0\x01\0\x01\0\0");
    std::fs::write(&jpeg, &bytes).unwrap();
    let err = refused(&["mlp", "detect", jpeg.to_str().unwrap()]);
    assert!(
        err.contains("page.jpg") && err.contains("JPEG") && err.contains("PNG only"),
        "{err}"
    );
    let mask = dir.join("mask.png");
    std::fs::write(&mask, b"").unwrap();
    let err = refused(&[
        "mlp",
        "train",
        "--pair",
        jpeg.to_str().unwrap(),
        mask.to_str().unwrap(),
        "--out",
        dir.join("n.json").to_str().unwrap(),
    ]);
    assert!(
        err.contains("training image") && err.contains("PNG only"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Values far from 1 are printed in scientific notation, not as 30-digit fixed point.
#[test]
fn mass_prints_huge_values_in_scientific_notation() {
    let dir = common::temp_dir("cli-limits", "mass");
    let obj = dir.join("big.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 3e6 0 0\nv 0 3e6 0\nv 0 0 3e6\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let out = classic_gpgpu(&["mass", obj.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let volume = text.lines().find(|l| l.starts_with("volume")).unwrap();
    assert!(volume.contains("e18"), "{volume}");
    let inertia = text.lines().find(|l| l.starts_with("I[xx]")).unwrap();
    assert!(inertia.contains("e30"), "{inertia}");
    assert!(
        text.lines()
            .skip_while(|l| !l.starts_with("volume"))
            .take(11)
            .all(|l| !l.split_whitespace().any(|w| w.len() > 16)),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Counts within their documented ranges whose product is beyond memory, and the lecture-1
/// counts, are refused before anything is allocated: `lecture3 random --size 4096 --steps
/// 1024` (64 GiB of numbers and several times that in the lists its tests compare) names
/// both options and the memory it would need.
#[test]
fn sizes_and_counts_beyond_memory_are_refused_before_allocating() {
    let start = std::time::Instant::now();
    let err = refused(&["lecture3", "random", "--size", "4096", "--steps", "1024"]);
    assert!(
        err.contains("--size 4096 --steps 1024")
            && err.contains("GiB")
            && err.contains("this machine may use"),
        "{err}"
    );
    let max = "18446744073709551615";
    for (args, option) in [
        (
            vec![
                "lecture1",
                "self-collision",
                "--scene",
                "knotted-tube",
                "--triangles",
                max,
            ],
            "--triangles",
        ),
        (
            vec![
                "lecture1",
                "self-collision",
                "--scene",
                "knotted-tube",
                "--frames",
                max,
            ],
            "--frames",
        ),
        (
            vec!["lecture1", "compare", "--triangles", max],
            "--triangles",
        ),
    ] {
        let err = refused(&args);
        assert!(
            err.contains(&format!("{option} ")) && err.contains("it is above"),
            "{args:?}: {err}"
        );
    }
    assert!(
        start.elapsed().as_secs() < 60,
        "the refusals took {:?}",
        start.elapsed()
    );
}
