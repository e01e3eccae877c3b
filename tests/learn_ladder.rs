//! The reduction ladder after Harris (`classic_gpgpu::learn::ladder`): every rung sums
//! exactly what the CPU sums, at small sizes including ones that are not powers of two (the
//! compute rungs where OpenGL 4.3 is there, skipped with the reason elsewhere); a rung made
//! wrong on purpose through a shader folder is caught; and the command line: `learn <id>
//! --bench --size N` prints its table (no time asserted), `--out FILE.json` writes the
//! ladder's results once, and `--bench` on a lesson without one is refused.

use classic_gpgpu::learn::ladder::{self, Input};
use common::{assert_ok, assert_refused, classic_gpgpu};
use std::path::Path;

mod common;

/// Sizes: a power of two, one more, a prime, a few values, and one past two cascading groups.
const SIZES: [u32; 5] = [4096, 4097, 3001, 7, 8192 * 2 + 5];

#[test]
fn every_rung_sums_what_the_cpu_sums() {
    let (ctx, compute) = common::compute_context();
    for n in SIZES {
        let checked = ladder::check_all(&ctx, n).unwrap();
        let expected = if compute { 10 } else { 4 };
        assert_eq!(checked.len(), expected, "rungs run at n = {n}");
        for c in &checked {
            println!(
                "n = {n}: rung {} ({}) {} passes: GPU {} CPU {}",
                c.rung, c.name, c.passes, c.gpu, c.cpu
            );
            // Integers 0-3 below 2^24 in all: exact in fp32 in any order of addition.
            assert!(
                c.passed(),
                "rung {} at n = {n}: {} vs {}",
                c.rung,
                c.gpu,
                c.cpu
            );
            assert_eq!(c.gpu, c.cpu);
            assert!(c.cpu > 0.0, "the data are not all zero");
        }
    }
    match ladder::compute_skipped(&ctx) {
        None => assert!(compute),
        Some(why) => {
            assert!(!compute);
            assert!(why.contains("4.3"), "{why}");
        }
    }
}

#[test]
fn the_ladder_is_harris_order_one_shader_file_per_rung_kind() {
    let rungs = &ladder::RUNGS;
    for (k, r) in rungs.iter().enumerate() {
        assert_eq!(r.number, k as u32 + 1);
        assert!(
            r.shader.name.starts_with("glsl/learn/ladder/"),
            "{}",
            r.name
        );
        assert!(
            Path::new(env!("CARGO_MANIFEST_DIR"))
                .join(r.shader.name)
                .is_file(),
            "{}",
            r.shader.name
        );
        assert!(!r.change.is_empty());
    }
    // The fragment rungs first, then the compute ones.
    let first_compute = rungs.iter().position(|r| r.is_compute()).unwrap();
    assert!(rungs[first_compute..].iter().all(|r| r.is_compute()));
    assert!(rungs[0].shader.source.contains("2"));
    assert!(rungs[first_compute]
        .shader
        .source
        .contains("t % (2u * s) == 0u"));
    // Every shader of the ladder is one the lesson lists.
    let info = classic_gpgpu::learn::find("compute-reduction")
        .unwrap()
        .info();
    for r in rungs {
        assert!(info.shaders.contains(&r.shader.name), "{}", r.shader.name);
    }
}

/// Copy a rung's shader into `dir` with `from` replaced by `to` (a mistake made on purpose).
fn broken(dir: &Path, shader: &str, (from, to): (&str, &str)) {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(shader)).unwrap();
    assert!(text.contains(from), "{shader} has no '{from}'");
    let path = dir.join(shader);
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text.replacen(from, to, 1)).unwrap();
}

#[test]
fn a_rung_made_wrong_on_purpose_is_caught() {
    let (ctx, compute) = common::compute_context();
    let dir = common::temp_dir("learn-ladder", "broken");
    // The fragment fan-in's block starts at the wrong place: a stride of fan - 1.
    broken(
        &dir,
        "glsl/learn/ladder/f2_fan.frag",
        (
            "ivec2(gl_FragCoord.xy) * u_fan",
            "ivec2(gl_FragCoord.xy) * (u_fan - 1)",
        ),
    );
    if compute {
        // Sequential addressing with the wrong stride: adds the value s + 1 up.
        broken(
            &dir,
            "glsl/learn/ladder/c3_sequential.comp",
            (
                "s_sum[t] += s_sum[t + s];",
                "s_sum[t] += s_sum[t + s + 1u];",
            ),
        );
    }
    ctx.set_glsl_dir(Some(dir.clone()));
    let values = ladder::values(4097);
    let cpu = ladder::cpu_sum(&values);
    let input = Input::new(&ctx, &values).unwrap();
    let result: Vec<_> = ladder::runnable(&ctx)
        .map(|rung| (rung, ladder::check(&ctx, rung, &input, cpu).unwrap()))
        .collect();
    ctx.set_glsl_dir(None);
    for (rung, c) in result {
        let replaced = dir.join(rung.shader.name).is_file();
        println!(
            "rung {} from the folder: {replaced}: {} vs {}",
            c.rung, c.gpu, c.cpu
        );
        assert_eq!(!c.passed(), replaced, "rung {} ({})", c.rung, rung.name);
    }
    // The lesson itself fails on the broken rung, naming it.
    let out = classic_gpgpu(&[
        "--glsl-dir",
        dir.to_str().unwrap(),
        "learn",
        "compute-reduction",
    ]);
    let err = assert_refused(&out, &["checks failed"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("FAIL ladder rung 2 (fragment 4x4)"),
        "{text}\n{err}"
    );
}
