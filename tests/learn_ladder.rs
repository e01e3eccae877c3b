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
        let expected = if compute { 11 } else { 4 };
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
    // The fragment rungs first, then the compute ones: Harris's kernels 1 to 7, in order.
    let first_compute = rungs.iter().position(|r| r.is_compute()).unwrap();
    assert!(rungs[first_compute..].iter().all(|r| r.is_compute()));
    assert_eq!(rungs.len() - first_compute, 7);
    for (k, r) in rungs[first_compute..].iter().enumerate() {
        assert!(
            r.name.starts_with(&format!("compute {}: ", k + 1)),
            "{}",
            r.name
        );
        assert_eq!(r.published().unwrap().kernel, k as u32 + 1);
    }
    // Kernel 5 unrolls the last warp only; kernel 6 the whole tree; both keep their barriers
    // (GLSL promises no lock step) and say so.
    let k5 = rungs[first_compute + 4].shader.source;
    let k6 = rungs[first_compute + 5].shader.source;
    assert!(k5.contains("s > 32u") && k5.contains("STEP(32)"), "{k5}");
    assert!(!k6.contains("for ("), "kernel 6 has a loop left: {k6}");
    for k in [k5, k6] {
        assert!(k.contains("barrier();") && k.contains("lock step"), "{k}");
    }
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

fn stdout(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn the_ladder_bench_prints_its_table_and_writes_json_once() {
    let (_, compute) = common::compute_context();
    let dir = common::temp_dir("learn-ladder", "bench");
    let json = dir.join("ladder.json");
    let json_arg = json.to_str().unwrap();
    let args = [
        "learn",
        "compute-reduction",
        "--bench",
        "--size",
        "3001",
        "--out",
        json_arg,
    ];
    let out = classic_gpgpu(&args);
    assert_ok(&out);
    let text = stdout(&out);
    println!("{text}");
    assert!(text.contains("reduction ladder on "), "{text}");
    assert!(text.contains("load"), "{text}");
    assert!(
        text.contains("readback of that value is excluded"),
        "{text}"
    );
    for rung in ladder::runnable(&common::context()) {
        assert!(text.contains(rung.name), "{} missing: {text}", rung.name);
    }
    assert!(text.contains("CPU: f64 sum"), "{text}");
    assert_eq!(text.contains("compute rungs: not run"), !compute, "{text}");
    // One clock for the whole table, named and explained (both software renderers here:
    // the glFinish wall clock, their timer query missing their worker threads' work).
    let clock_lines: Vec<&str> = text.lines().filter(|l| l.starts_with("clock: ")).collect();
    assert_eq!(clock_lines.len(), 1, "{text}");
    assert!(clock_lines[0].contains("for every rung: "), "{text}");
    let software = text.contains("llvmpipe") || text.contains("softpipe");
    if software {
        assert!(
            clock_lines[0].starts_with("clock: glFinish wall clock for every rung")
                && clock_lines[0].contains("software renderer"),
            "{text}"
        );
    }
    assert!(text.contains("step") && text.contains("total"), "{text}");
    // Harris's kernels 1 and 7 are quoted even at a size that is not his.
    assert!(text.contains("kernel 1 8.054 ms, 2.083 GB/s"), "{text}");
    assert!(
        text.contains("kernel 7 0.268 ms, 62.671 GB/s, 30x"),
        "{text}"
    );
    // The JSON: every rung at the one size, with its time's runs and a bandwidth.
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(written["bench"], "ladder");
    let clock = written["clock"]["clock"].as_str().unwrap();
    assert!(["timer_query", "finished_wall"].contains(&clock), "{clock}");
    assert_eq!(written["harris"].as_array().unwrap().len(), 7);
    assert_eq!(written["sizes"], serde_json::json!([3001]));
    let rungs = written["rungs"].as_array().unwrap();
    assert_eq!(rungs.len(), if compute { 11 } else { 4 });
    for r in rungs {
        assert_eq!(r["n"], 3001);
        assert_eq!(r["error"], 0.0);
        assert!(r["ms"]["runs"].as_u64().unwrap() >= 3, "{r}");
        assert!(r["gb_per_s"].as_f64().is_some(), "{r}");
        // The time shown is the table's clock's, of the same runs.
        let on_clock = if clock == "timer_query" {
            "query"
        } else {
            "wall"
        };
        assert_eq!(r["ms"], r["clocks"][on_clock], "{r}");
    }
    // An existing file is never replaced without --force.
    let before = std::fs::read(&json).unwrap();
    let refused = classic_gpgpu(&args);
    assert_refused(&refused, &["--out", "exists", "--force"]);
    assert_eq!(std::fs::read(&json).unwrap(), before);
    let mut forced = args.to_vec();
    forced.push("--force");
    assert_ok(&classic_gpgpu(&forced));
}

#[test]
fn saxpy_and_readback_benches_print_their_tables() {
    let out = classic_gpgpu(&["learn", "quad-is-loop", "--bench", "--size", "1000"]);
    assert_ok(&out);
    let text = stdout(&out);
    println!("{text}");
    assert!(
        text.contains("saxpy bench") && text.contains("CPU ms"),
        "{text}"
    );
    assert!(text.contains("load"), "{text}");
    // 1000 elements fill a 32x32 texture.
    assert!(text.contains("32x32"), "{text}");

    let out = classic_gpgpu(&["learn", "readback-and-upload", "--bench", "--size", "64"]);
    assert_ok(&out);
    let text = stdout(&out);
    println!("{text}");
    for words in [
        "whole read ms",
        "PBO read ms",
        "compacted read ms",
        "of which passes",
        "of which reads",
        "why these numbers",
    ] {
        assert!(text.contains(words), "{words}: {text}");
    }
    assert!(text.contains("96.97 ms"), "{text}");
}

#[test]
fn bench_refusals_name_the_input_and_what_to_do() {
    let out = classic_gpgpu(&["learn", "ping-pong", "--bench"]);
    let err = assert_refused(
        &out,
        &[
            "ping-pong",
            "no --bench",
            "quad-is-loop",
            "compute-reduction",
        ],
    );
    assert!(
        err.contains("readback-and-upload") && err.contains("reduction"),
        "{err}"
    );
    let out = classic_gpgpu(&["learn", "reduction", "--bench", "--size", "5000000"]);
    assert_refused(&out, &["--size 5000000", "4194304"]);
    let out = classic_gpgpu(&["learn", "readback-and-upload", "--bench", "--size", "100"]);
    assert_refused(&out, &["--size 100", "multiple of 8"]);
    let out = classic_gpgpu(&["learn", "reduction", "--size", "64"]);
    assert_refused(&out, &["--bench"]);
    let dir = common::temp_dir("learn-ladder", "refusals");
    let txt = dir.join("ladder.txt");
    let out = classic_gpgpu(&[
        "learn",
        "reduction",
        "--bench",
        "--size",
        "64",
        "--out",
        txt.to_str().unwrap(),
    ]);
    assert_refused(&out, &["--out", ".json"]);
    assert!(!txt.exists());
}

/// Lesson 8 explains its own numbers: the note quotes this run's warm medians and bytes, and
/// the compacted readback reads three times whatever the number of flagged blocks.
#[test]
fn lesson_8_explains_its_own_warm_numbers() {
    let ctx = common::context();
    let run = classic_gpgpu::learn::find("readback-and-upload")
        .unwrap()
        .run(&ctx, &Default::default())
        .unwrap();
    assert!(run.passed);
    let note = |name: &str| {
        run.notes
            .iter()
            .find(|(n, _)| n.starts_with(name))
            .map(|(n, v)| (n.clone(), v.clone()))
            .unwrap_or_else(|| panic!("no note {name}: {:?}", run.notes))
    };
    let (_, why) = note("why these numbers");
    println!("{why}");
    let (name, full) = note("glReadPixels into client memory, whole array");
    // Warm: the median of the lesson's runs after a warm-up, never one cold sample.
    let runs = classic_gpgpu::learn::LESSON_RUNS;
    assert!(
        name.contains(&format!("median of {runs} runs after a warm-up")),
        "{name}"
    );
    assert!(
        why.contains(&format!("medians of {runs} runs after a warm-up")),
        "{why}"
    );
    let full: f64 = full.parse().unwrap();
    assert!(why.contains(&format!("in {full:.3} ms")), "{why}");
    let (_, compacted) = note("compacted readback: every pass and read");
    let compacted: f64 = compacted.parse().unwrap();
    assert!(why.contains(&format!("it took {compacted:.3} ms")), "{why}");
    let (_, bytes) = note("bytes read: whole array / compacted");
    let (whole, reduced) = bytes.split_once(" / ").unwrap();
    assert!(why.contains(&format!("moved {whole} bytes")), "{why}");
    assert!(
        why.contains(&format!("three reads of {reduced} bytes")),
        "{why}"
    );
    assert!(why.contains("96.97 ms"), "{why}");
    assert_eq!(
        why.contains("software rasterizer"),
        ctx.info().is_software(),
        "{why}"
    );
    // The verdict follows the medians it quotes.
    let won = compacted < full;
    assert_eq!(why.contains("Reading less won here"), won, "{why}");
    assert_eq!(why.contains("Reading less lost here"), !won, "{why}");
}

/// No part is timed longer than its whole: the saxpy bench's pass against the pass with its
/// transfers, and the compacted readback's passes and reads against the whole of it, are
/// steps of the same runs, so this holds by construction, whatever the machine is doing (it
/// compares two sums of the same samples, not a time with a number).
#[test]
fn a_part_is_never_timed_longer_than_its_whole() {
    use classic_gpgpu::learn::bench::{self, Bench};
    let ctx = common::context();
    let runs = classic_gpgpu::timing::Runs::exactly(7);
    let Bench::Saxpy(saxpy) = bench::run(&ctx, "quad-is-loop", Some(4096), runs).unwrap() else {
        panic!("the saxpy bench")
    };
    for r in &saxpy.rows {
        let (part, whole) = (r.pass_ms(), r.with_transfers_ms());
        println!("saxpy {}: pass {part:?}, with transfers {whole:?}", r.n);
        assert_eq!((part.runs, whole.runs), (7, 7));
        assert!(part.median <= whole.median, "{part:?} {whole:?}");
        assert!(part.min <= whole.min && part.max <= whole.max);
    }
    let Bench::Readback(readback) =
        bench::run(&ctx, "readback-and-upload", Some(64), runs).unwrap()
    else {
        panic!("the readback bench")
    };
    for r in &readback.rows {
        let c = &r.compacted;
        for part in [c.passes, c.reads] {
            assert!(part.median <= c.whole.median, "{part:?} {:?}", c.whole);
            assert!(part.max <= c.whole.max);
        }
    }
}

/// The ladder's section of lesson 10's guide page: each rung once in the table, the CPU's
/// row, the plot written; nothing on another lesson's page.
#[test]
fn the_guide_section_has_one_row_per_rung_and_its_plot() {
    use classic_gpgpu::learn::guide::ladder_page;
    let ctx = common::context();
    let dir = common::temp_dir("learn-ladder", "guide");
    assert_eq!(ladder_page::section(&ctx, "reduction", &dir), "");
    let html = ladder_page::section(&ctx, ladder_page::LESSON, &dir);
    for rung in ladder::runnable(&ctx) {
        let row = format!("<tr><td>{}. {}</td>", rung.number, rung.name);
        assert_eq!(html.matches(&row).count(), 1, "{row}: {html}");
    }
    assert_eq!(html.matches("<tr><td>CPU: f64 sum").count(), 1, "{html}");
    assert!(html.contains("learn compute-reduction --bench"), "{html}");
    let picture = dir.join("pictures/compute-reduction/ladder.png");
    let image = image::open(&picture).unwrap();
    assert!(image.width() > 400 && image.height() > 300);
    assert!(
        html.contains("src=\"pictures/compute-reduction/ladder.png\""),
        "{html}"
    );
}
