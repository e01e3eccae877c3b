//! The command line as a user meets it.

use std::process::Command;

fn classic_gpgpu(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(args)
        .output()
        .expect("the binary runs")
}

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
