//! What the integration tests share: the GL context they run on, and test data they make.
#![allow(dead_code)]

use classic_gpgpu::gl::Context;
use classic_gpgpu::mesh::Mesh;
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A fresh, empty folder for test `name` of suite `suite`, unique to this process.
pub fn temp_dir(suite: &str, name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "classic-gpgpu-{suite}-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The renderer named by `CLASSIC_GPGPU_RENDERER` (see README), with GL errors and
/// framebuffer completeness checked after every pass.
pub fn context() -> Context {
    let ctx = Context::from_env().expect("a headless OpenGL context (see README: renderer)");
    ctx.set_checks(true);
    ctx
}

/// `n` random triangles of size about `size` in the unit cube, no shared vertices.
pub fn soup(n: usize, size: f32, seed: u64) -> Mesh {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut positions = Vec::new();
    for _ in 0..n {
        let c = Vec3::new(rng.gen(), rng.gen(), rng.gen());
        for _ in 0..3 {
            let d = Vec3::new(rng.gen(), rng.gen(), rng.gen()) - 0.5;
            positions.push(c + d * size);
        }
    }
    let triangles = (0..n as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    Mesh::new(positions, triangles)
}

/// Run the `classic-gpgpu` binary with `args`, as a user would.
pub fn classic_gpgpu(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// Run the binary with `args`, require success, and parse its stdout as JSON.
pub fn json_of(args: &[&str]) -> serde_json::Value {
    let out = classic_gpgpu(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

/// The test context if it runs compute shaders (OpenGL 4.3, llvmpipe). On an older one
/// (softpipe is 3.3) `None`, after checking that asking for compute is the clear error that
/// names both versions, so the test can go on to show the classic path still runs.
pub fn compute_context() -> (Context, bool) {
    let ctx = context();
    if ctx.has_compute() {
        return (ctx, true);
    }
    let err = ctx.require_compute("this test").unwrap_err().to_string();
    let (major, minor) = ctx.info().gl_version;
    assert!(
        err.contains("needs OpenGL 4.3") && err.contains(&format!("OpenGL {major}.{minor}")),
        "{err}"
    );
    (ctx, false)
}

/// A unit cube's OBJ with every coordinate times `scale` (0: every vertex at the origin).
pub fn scaled_cube_obj(dir: &std::path::Path, name: &str, scale: f64) -> std::path::PathBuf {
    let path = dir.join(name);
    let mut obj = String::new();
    for v in 0..8 {
        let c = |bit: u32| if v & (1 << bit) != 0 { scale } else { 0.0 };
        obj.push_str(&format!("v {:e} {:e} {:e}\n", c(0), c(1), c(2)));
    }
    // Outward, counter-clockwise seen from outside.
    for f in [
        [1, 3, 4, 2],
        [5, 6, 8, 7],
        [1, 2, 6, 5],
        [3, 7, 8, 4],
        [1, 5, 7, 3],
        [2, 4, 8, 6],
    ] {
        obj.push_str(&format!(
            "f {} {} {}\nf {} {} {}\n",
            f[0], f[1], f[2], f[0], f[2], f[3]
        ));
    }
    std::fs::write(&path, obj).unwrap();
    path
}

/// The standard error of a finished run, as text.
pub fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The run succeeded (its standard error is the message otherwise).
pub fn assert_ok(out: &std::process::Output) {
    assert!(out.status.success(), "{}", stderr(out));
}

/// Failed with every one of `words` in the message, and no panic; the message.
pub fn assert_refused(out: &std::process::Output, words: &[&str]) -> String {
    let err = stderr(out);
    assert!(!out.status.success(), "exit 0: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for w in words {
        assert!(err.contains(w), "'{w}' missing from: {err}");
    }
    err
}
