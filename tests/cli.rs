//! The command line as a user meets it.

use common::classic_gpgpu;

mod common;

#[test]
fn info_json_names_renderer_and_limits() {
    let out = classic_gpgpu(&["info", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let info: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(info["renderer"].as_str().is_some_and(|r| !r.is_empty()));
    assert!(info["limits"]["max_texture_size"].as_u64().unwrap() >= 1024);
    assert!(info["why"].as_str().is_some());
}

#[test]
fn a_renderer_that_is_not_there_is_a_clear_error() {
    // No libOSMesa on the CI machine: the message names the package. (Where OSMesa is
    // installed, the command succeeds and there is nothing to check.)
    let out = classic_gpgpu(&["info", "--renderer", "osmesa"]);
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("libosmesa6"), "{err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

#[test]
fn mesh_generate_then_check_round_trips_the_papers_sizes() {
    let dir = std::env::temp_dir().join(format!("classic-gpgpu-cli-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("sphere.obj");
    let path_text = path.to_str().unwrap();
    let out = classic_gpgpu(&["mesh", "generate", "sphere", "--out", path_text]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = classic_gpgpu(&["mesh", "check", path_text, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["vertices"], 422);
    assert_eq!(report["triangles"], 840);
    assert_eq!(report["closed"], true);
    // The user's file is not overwritten without --force.
    let again = classic_gpgpu(&["mesh", "generate", "cube", "--out", path_text]);
    assert!(!again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("--force"));
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn bad_obj_files_are_named_with_their_line() {
    let dir = std::env::temp_dir().join(format!("classic-gpgpu-cli-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        (
            "nan.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 nan\nf 1 2 3\n",
            "nan.obj:3",
        ),
        (
            "face.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n",
            "face.obj:4",
        ),
        ("empty.obj", "", "empty"),
        (
            "range.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
            "range.obj:4",
        ),
    ];
    for (name, text, expected) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let out = classic_gpgpu(&["mesh", "check", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{name} was accepted");
        assert!(err.contains(expected), "{name}: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn mesh_generate_refuses_a_triangle_count_it_cannot_make() {
    let dir = std::env::temp_dir().join(format!("classic-gpgpu-cli-odd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cube13.obj");
    let out = classic_gpgpu(&[
        "mesh",
        "generate",
        "cube",
        "--triangles",
        "13",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("13") && err.contains("even"), "{err}");
    assert!(!path.exists(), "a file was written");
    let os_errors = classic_gpgpu(&["mesh", "check", dir.join("none.obj").to_str().unwrap()]);
    let err = String::from_utf8_lossy(&os_errors.stderr);
    assert_eq!(err.matches("os error").count(), 1, "{err}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn reproduce_help_lists_every_section_only_takes() {
    let out = classic_gpgpu(&["reproduce", "--help"]);
    assert!(out.status.success());
    let help = String::from_utf8_lossy(&out.stdout);
    for stage in classic_gpgpu::report::reproduce::stages() {
        assert!(
            help.contains(stage.id),
            "{} missing from:\n{help}",
            stage.id
        );
    }
    let out = classic_gpgpu(&["reproduce", "--only", "paper9", "--out", "/nonexistent"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("paper9") && err.contains("lecture3"), "{err}");
}

#[test]
fn view_collide_scene_without_a_scene_lists_the_scenes() {
    for args in [
        &["view", "collide-scene"][..],
        &["view", "collide-scene", "tori"],
    ] {
        let out = classic_gpgpu(args);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        for scene in classic_gpgpu::collide::scenes::SCENES {
            assert!(err.contains(scene), "{scene} missing: {err}");
        }
        assert!(!err.contains("panicked"), "{err}");
    }
}

#[test]
fn collide_scene_ends_with_a_summary_line() {
    let out = classic_gpgpu(&[
        "collide-scene",
        "touching-tori",
        "--frames",
        "2",
        "--triangles",
        "300",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    let last = stdout.lines().last().unwrap();
    assert!(
        last.starts_with("touching-tori: 2 frames of ") && last.contains("median frame"),
        "{last}"
    );
}
