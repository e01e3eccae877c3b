//! Feedback that points at the mistake, the terminal that teaches, and `view learn`'s reload:
//! a wrongly filled exercise names its wrong texels with the GPU's and the CPU's values (those
//! of the buffer the pass wrote and of the CPU reference), writes the difference picture and
//! names the viewer command; the hints come in three different steps for every exercise;
//! `--solution` prints the shipped shader and a run of it says so; `learn <id>` prints the idea
//! first and the next lesson last; a shader saved broken while `view learn ping-pong` runs
//! leaves it stepping with the last good one, and a probe over no buffer draws nothing. Then
//! feedback per cell in every lesson, each shown by a mistake planted in one place: saxpy's
//! ramp shows a read one texel off as a pattern, the compute reduction names the work group
//! whose partial is wrong (with a picture of the partials), the readback lesson the block
//! whose flag is wrong, depth peeling the pixels whose layer count is; and no template holds
//! its exercise's answer.

mod common;

use classic_gpgpu::learn::{self, LessonOptions};
use classic_gpgpu::view::live::LiveDemo;
use classic_gpgpu::view::{Canvas, DemoSpec, ViewState};
use common::classic_gpgpu;
use std::path::Path;

/// The saxpy solution filled in wrongly: `a x - y` for `a x + y`.
fn wrong_saxpy() -> String {
    let shipped = classic_gpgpu::gl::shaders::find("glsl/learn/saxpy.frag")
        .unwrap()
        .source;
    let wrong = shipped.replace("o_y = u_a * x + y;", "o_y = u_a * x - y;");
    assert_ne!(wrong, shipped);
    wrong
}

fn put(dir: &Path, path: &str, text: &str) {
    classic_gpgpu::files::write_bytes(&dir.join(path), text.as_bytes()).unwrap();
}

#[test]
fn a_wrong_exercise_names_its_wrong_texels_with_both_values() {
    let ctx = common::context();
    let dir = common::temp_dir("learn-feedback", "wrong-saxpy");
    put(&dir, "glsl/learn/saxpy.frag", &wrong_saxpy());
    ctx.set_glsl_dir(Some(dir.clone()));
    let opts = LessonOptions {
        exercise: Some(1),
        ..LessonOptions::default()
    };
    let run = learn::find("quad-is-loop").unwrap().run(&ctx, &opts);
    ctx.set_glsl_dir(None);
    let run = run.unwrap();
    assert!(!run.passed);
    let check = run
        .checks
        .iter()
        .find(|c| c.what == "saxpy = the CPU loop")
        .unwrap();
    assert!(!check.passed);
    // a x - y misses a x + y by 2 |y| = 1, y a checkerboard of +-0.5: every element is wrong.
    let buffer = &run.buffers[check.buffer.expect("the check names the saxpy buffer")];
    let total = buffer.values.len();
    let wrong = check.wrong.unwrap();
    assert!(wrong > total * 9 / 10 && wrong <= total, "{check:?}");
    assert_eq!(check.first_wrong.len(), learn::FIRST_WRONG);
    let reference = buffer
        .reference
        .as_ref()
        .expect("saxpy keeps its reference");
    for w in &check.first_wrong {
        let i = (w.y * buffer.width + w.x) as usize * buffer.channels + w.channel;
        assert_eq!(w.gpu, buffer.values[i], "{w:?}: the GPU's value");
        assert_eq!(w.cpu, reference[i], "{w:?}: the CPU's value");
        assert!((w.gpu - w.cpu).abs() as f64 > check.tolerance, "{w:?}");
    }
    let d = check.difference.as_ref().unwrap();
    assert_eq!(d.values.len(), total);
    assert!(run.exercise_ran.as_deref().unwrap().contains("your file"));

    // Through the binary: the message names the first texel with both values, the picture of
    // the difference is written beside --png, and the viewer command is named.
    let png = dir.join("pictures");
    let out = classic_gpgpu(&[
        "--glsl-dir",
        dir.to_str().unwrap(),
        "learn",
        "quad-is-loop",
        "--exercise",
        "1",
        "--png",
        png.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success());
    let w = check.first_wrong[0];
    let named = format!(
        "texel ({}, {}) channel 0: the GPU wrote {}, the CPU expects {}",
        w.x, w.y, w.gpu, w.cpu
    );
    assert!(stderr.contains(&named), "{named} not in: {stderr}");
    assert!(stdout.contains(&named), "{named} not in: {stdout}");
    assert!(
        stderr.contains(&format!("{wrong} of {total} values")),
        "{stderr}"
    );
    assert!(
        stderr.contains("view learn quad-is-loop --buffer"),
        "{stderr}"
    );
    let k = run
        .checks
        .iter()
        .position(|c| c.what == check.what)
        .unwrap();
    let picture = png.join(learn::LessonRun::difference_file(k));
    let image = image::open(&picture).unwrap();
    assert!(image.width() >= 256, "{picture:?}");
    assert!(stderr.contains(picture.to_str().unwrap()), "{stderr}");
    let hints = learn::find("quad-is-loop").unwrap().info().exercises[0].hints;
    assert!(stderr.contains(hints[0]), "{stderr}");
    assert!(stderr.contains("--hint 2"), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_exercise_has_three_different_hints_and_a_printed_solution() {
    for lesson in learn::all() {
        let info = lesson.info();
        for e in info.exercises {
            for (i, h) in e.hints.iter().enumerate() {
                assert!(
                    h.trim().len() > 10,
                    "{} exercise {} hint {}",
                    info.id,
                    e.number,
                    i + 1
                );
                for other in &e.hints[i + 1..] {
                    assert_ne!(h, other, "{} exercise {}", info.id, e.number);
                }
            }
        }
    }
    let e = learn::find("reduction").unwrap().info().exercises[0];
    for n in 1..=3 {
        let out = classic_gpgpu(&["learn", "reduction", "--hint", &n.to_string()]);
        let stdout = String::from_utf8_lossy(&out.stdout).replace("\n  ", " ");
        assert!(out.status.success());
        assert!(stdout.contains(e.hints[n - 1]), "hint {n}: {stdout}");
        assert_eq!(stdout.contains("--hint"), n < 3, "{stdout}");
    }
    let out = classic_gpgpu(&["learn", "reduction", "--hint", "4"]);
    assert!(!out.status.success());
    let out = classic_gpgpu(&["learn", "reduction", "--exercise", "1", "--solution"]);
    let shipped = classic_gpgpu::gl::shaders::find(e.shader).unwrap().source;
    assert_eq!(String::from_utf8_lossy(&out.stdout), shipped);
    // The shipped solution run says it is the shipped one.
    let out = classic_gpgpu(&["learn", "reduction", "--exercise", "1"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}");
    assert!(
        stdout.contains("ran the shipped solution glsl/learn/reduce_wide.frag"),
        "{stdout}"
    );
}

#[test]
fn the_terminal_prints_the_idea_first_and_the_next_step_last() {
    let lessons = learn::all();
    for k in [0, 10] {
        let info = lessons[k].info();
        let out = classic_gpgpu(&["learn", &k.to_string()]);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{stdout}");
        let idea = stdout.find("the idea:").expect("the idea");
        let first_pass = stdout.find("pass 0:").expect("a pass");
        assert!(idea < first_pass, "{stdout}");
        let first_words: String = info.idea.split(' ').take(4).collect::<Vec<_>>().join(" ");
        assert!(stdout.contains(&first_words), "{stdout}");
        let last = stdout.lines().last().unwrap();
        let next = lessons[k + 1].info();
        assert!(
            last.contains(&format!("classic-gpgpu learn {}", next.id)),
            "{last}"
        );
    }
    let last = lessons.last().unwrap().info();
    let out = classic_gpgpu(&["learn", last.id]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}");
    assert!(stdout.contains("next, the papers: Paper"), "{stdout}");
}

/// The viewer's reload of a lesson that iterates, driven headless as the window drives it: a
/// broken Jacobi step saved while it runs is reported and the demo keeps stepping with the
/// last good shader (its checks still pass); mending the file reloads.
#[test]
fn view_learn_ping_pong_keeps_the_last_good_shaders_after_a_failed_reload() {
    let ctx = common::context();
    let dir = common::temp_dir("learn-feedback", "live-ping-pong");
    let path = "glsl/learn/jacobi.frag";
    let good = classic_gpgpu::gl::shaders::find(path).unwrap().source;
    put(&dir, path, good);
    ctx.set_glsl_dir(Some(dir.clone()));
    let spec = DemoSpec::Learn {
        id: "ping-pong".into(),
    };
    let size = (240, 180);
    let canvas = Canvas::new(&ctx, size.0, size.1).unwrap();
    let view = ViewState::default();
    let mut live = LiveDemo::new(&spec, &ctx, size, "").unwrap();
    live.step().unwrap();
    let mut clock = std::time::SystemTime::now();
    let mut touch = |text: &str| {
        put(&dir, path, text);
        clock += std::time::Duration::from_secs(2);
        let file = std::fs::File::options()
            .write(true)
            .open(dir.join(path))
            .unwrap();
        file.set_modified(clock).unwrap();
    };
    touch(&good.replace("float left =", "flot left ="));
    assert_eq!(live.poll(&ctx), Some(false));
    let error = live.error().unwrap().to_string();
    assert!(error.contains("jacobi.frag"), "{error}");
    // The steps go on with the shader that worked.
    for _ in 0..2 {
        live.step().expect("a step after a failed reload");
    }
    live.draw(&canvas, &view).unwrap();
    let overlay = live.demo().overlay();
    assert!(
        overlay.iter().any(|l| l.contains("4 iterations")),
        "{overlay:?}"
    );
    assert!(
        overlay
            .iter()
            .any(|l| l.contains("checks against the CPU") && !l.contains(" 0 of")),
        "{overlay:?}"
    );
    assert!(
        overlay.iter().all(|l| !l.starts_with("FAIL")),
        "{overlay:?}"
    );
    // Mended: it reloads.
    touch(good);
    assert_eq!(live.poll(&ctx), Some(true));
    assert!(live.error().is_none());
    ctx.set_glsl_dir(None);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A probe over no buffer (the text at the top) draws nothing: the frame is the one without a
/// probe; over a buffer it draws its readout.
#[test]
fn a_probe_over_no_buffer_leaves_no_label() {
    let ctx = common::context();
    let spec = DemoSpec::Learn {
        id: "reduction".into(),
    };
    let frame = |probe: Option<(u32, u32)>| {
        let view = ViewState {
            probe,
            ..ViewState::default()
        };
        classic_gpgpu::view::headless_frame(&spec, &ctx, (320, 240), 1, &view, "").unwrap()
    };
    let (plain, _) = frame(None);
    let (nowhere, lines) = frame(Some((300, 4)));
    assert!(lines[0].contains("no buffer here"), "{lines:?}");
    assert_eq!(plain, nowhere, "a label was drawn where no buffer is");
    // Somewhere below the text a buffer is drawn: there the readout is drawn.
    let (over, lines) = (0..12)
        .map(|k| frame(Some((50, 236 - 16 * k))))
        .find(|(_, lines)| lines[0].contains("texel"))
        .expect("a buffer under some probe of the column x = 50");
    assert!(lines.iter().any(|l| l.starts_with("GPU ")), "{lines:?}");
    assert_ne!(plain, over);
}

/// The debugging lesson: each of its seven faults is found by its tool (a check each, with the
/// tool's words in the fault's note), and each fixed program passes against the CPU.
#[test]
fn the_debugging_lesson_finds_every_fault_and_the_fixes_pass() {
    let ctx = common::context();
    let run = learn::find("debugging")
        .unwrap()
        .run(&ctx, &LessonOptions::default())
        .unwrap();
    let failed: Vec<_> = run.checks.iter().filter(|c| !c.passed).collect();
    assert!(run.passed, "on {}: {failed:#?}", run.renderer);
    for k in 1..=7 {
        let found = run
            .checks
            .iter()
            .find(|c| c.what.starts_with(&format!("fault {k}, ")))
            .unwrap_or_else(|| panic!("no check that fault {k} is found"));
        assert!(found.passed, "{found:?}");
        let fixed: Vec<_> = run
            .checks
            .iter()
            .filter(|c| c.what.starts_with(&format!("fault {k} fixed")))
            .collect();
        assert!(
            !fixed.is_empty() && fixed.iter().all(|c| c.passed),
            "{fixed:?}"
        );
        let (_, note) = run
            .notes
            .iter()
            .find(|(n, _)| n.starts_with(&format!("fault {k}: ")))
            .unwrap();
        assert!(
            note.contains("symptom: ") && note.contains("Found by ") && note.contains("Fix: "),
            "{note}"
        );
        assert!(!note.contains("did not find"), "{note}");
    }
    let note = |k: u32| {
        run.notes
            .iter()
            .find(|(n, _)| n.starts_with(&format!("fault {k}: ")))
            .unwrap()
            .1
            .clone()
    };
    // Off-centre: 7 of the 8 texels (texel 0's edge is clamped to itself).
    assert!(note(1).contains("7 of 8 values wrong"), "{}", note(1));
    assert!(note(3).contains("u_current"), "{}", note(3));
    assert!(note(4).contains("NaN"), "{}", note(4));
    assert!(note(5).contains("depth as colour"), "{}", note(5));
    // The compile error names the file and the line of the misspelt type.
    let source = classic_gpgpu::gl::shaders::find("glsl/learn/texture_copy.frag")
        .unwrap()
        .source;
    let line = source
        .lines()
        .position(|l| l.contains("float value ="))
        .unwrap()
        + 1;
    assert!(
        note(6).contains(&format!("glsl/learn/texture_copy.frag:{line}:")),
        "{}",
        note(6)
    );
    assert!(
        note(7).contains("v_texcoord") || note(7).contains("the comparison"),
        "{}",
        note(7)
    );
}

/// A shipped shader with one line replaced: a mistake planted on purpose.
fn planted(path: &str, from: &str, to: &str) -> String {
    let shipped = classic_gpgpu::gl::shaders::find(path).unwrap().source;
    assert!(shipped.contains(from), "{path} has no '{from}'");
    shipped.replacen(from, to, 1)
}

/// Run lesson `id` with `path` replaced by `text` from a shader folder.
fn run_planted(id: &str, path: &str, text: &str, exercise: Option<u32>) -> learn::LessonRun {
    let ctx = common::context();
    let dir = common::temp_dir("learn-feedback", &format!("planted-{id}"));
    put(&dir, path, text);
    ctx.set_glsl_dir(Some(dir.clone()));
    let opts = LessonOptions {
        exercise,
        ..LessonOptions::default()
    };
    let run = learn::find(id).unwrap().run(&ctx, &opts);
    ctx.set_glsl_dir(None);
    let _ = std::fs::remove_dir_all(&dir);
    run.unwrap()
}

fn check<'a>(run: &'a learn::LessonRun, starts: &str) -> &'a learn::Check {
    run.checks
        .iter()
        .find(|c| c.what.starts_with(starts))
        .unwrap_or_else(|| panic!("no check '{starts}': {:#?}", run.checks))
}

/// Saxpy's input is a ramp (x) and a checkerboard (y): a read one texel off along the row is
/// wrong by exactly a / 64 at every texel but the last column, a flat difference picture that
/// names the bug, where random input would have looked like noise.
#[test]
fn an_off_by_one_read_in_saxpy_shows_as_a_pattern() {
    let wrong = planted(
        "glsl/learn/saxpy.frag",
        "float x = texelFetch(u_x, i, 0).r;",
        "float x = texelFetch(u_x, i + ivec2(1, 0), 0).r;",
    );
    let run = run_planted("quad-is-loop", "glsl/learn/saxpy.frag", &wrong, Some(1));
    let c = check(&run, "saxpy = the CPU loop");
    assert!(!c.passed);
    let d = c.difference.as_ref().expect("the difference GPU - CPU");
    let step = 2.5f32 / 64.0;
    for y in 0..d.height {
        for x in 0..d.width - 1 {
            let v = d.values[(y * d.width + x) as usize];
            assert_eq!(
                v, step,
                "texel ({x}, {y}): the read one texel off shows as a / 64"
            );
        }
    }
    // The first wrong texel is the first texel, with the GPU's value a x[1] + y[0].
    let w = c.first_wrong[0];
    assert_eq!((w.x, w.y), (0, 0));
    assert_eq!(w.gpu, 2.5 * (1.0 / 64.0 - 1.5) + 0.5);
    assert_eq!(w.cpu, 2.5 * -1.5 + 0.5);
}

/// A wrong step of the tree in one work group only (group 7 folds its own value instead of
/// its partner's): the feedback names work group 7 and no other, and `--png` writes the
/// picture of the partials beside the difference.
#[test]
fn a_wrong_partner_in_the_compute_reduction_names_its_work_group() {
    let (ctx, compute) = common::compute_context();
    if !compute {
        println!(
            "skipped on {}: the exercise is a compute shader",
            ctx.info().renderer
        );
        return;
    }
    drop(ctx);
    let path = "glsl/learn/compute-reduction/reduce.comp";
    let wrong = planted(
        path,
        "combine(s_partial[local], s_partial[local + stride])",
        "combine(s_partial[local], s_partial[gl_WorkGroupID.x == 7u ? local : local + stride])",
    );
    let run = run_planted("compute-reduction", path, &wrong, Some(1));
    let c = check(&run, "compute pass 1: each work group's partial");
    assert!(!c.passed);
    assert!(c.wrong.unwrap() >= 1 && c.wrong.unwrap() <= 2, "{c:?}");
    assert!(c.first_wrong.iter().all(|w| w.x == 7 && w.y == 0), "{c:?}");
    let lines = c.where_wrong();
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with("work group 7 channel 0: ")),
        "{lines:?}"
    );
    // The partials are a buffer of the run (a picture under --png), the CPU's beside them.
    let b = &run.buffers[c.buffer.expect("the partials' buffer")];
    assert_eq!((b.width, b.height, b.channels), (40, 1, 2));
    assert!(b.reference.is_some());

    let dir = common::temp_dir("learn-feedback", "partials-png");
    put(&dir, path, &wrong);
    let png = dir.join("pictures");
    let out = classic_gpgpu(&[
        "--glsl-dir",
        dir.to_str().unwrap(),
        "learn",
        "compute-reduction",
        "--exercise",
        "1",
        "--png",
        png.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("work group 7 channel 0: the GPU wrote"),
        "{stderr}"
    );
    let partials = png.join(format!("{}.png", b.stem));
    assert!(
        image::open(&partials).unwrap().width() >= 256,
        "{partials:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A flags shader wrong at one block only: the feedback names that block, and the steps after
/// it, each checked on the GPU's own flags, still pass (the pyramid counts what was flagged,
/// the list lists it): the fault is named where it is.
#[test]
fn a_wrong_flag_names_its_block_and_the_pyramid_checks_stay_apart() {
    let path = "glsl/learn/readback-and-upload/block_flags.frag";
    let wrong = planted(
        path,
        "    o_flag = vec4(any_set, 0.0, 0.0, 1.0);",
        "    if (ivec2(gl_FragCoord.xy) == ivec2(5, 3)) any_set = 1.0 - any_set;\n    o_flag = \
         vec4(any_set, 0.0, 0.0, 1.0);",
    );
    let run = run_planted("readback-and-upload", path, &wrong, Some(1));
    let c = check(&run, "block flags:");
    assert!(!c.passed);
    assert_eq!(c.wrong, Some(1), "{c:?}");
    assert_eq!((c.first_wrong[0].x, c.first_wrong[0].y), (5, 3));
    assert!(
        c.where_wrong()[1].starts_with("block (5, 3) channel 0: "),
        "{c:?}"
    );
    for step in ["pyramid level", "the list:"] {
        for k in run.checks.iter().filter(|k| k.what.starts_with(step)) {
            assert!(k.passed, "{k:?}");
        }
    }
    assert!(check(&run, "the list:").passed);
}

/// A peel that stops after two layers left of x = 24: the feedback names pixels there, each
/// with the GPU's two layers against the ray's more.
#[test]
fn a_peel_that_stops_early_names_its_pixels() {
    let path = "glsl/learn/depth-peeling/peel.frag";
    let wrong = planted(
        path,
        "    // The layer's picture",
        "    if (u_layer >= 2 && gl_FragCoord.x < 24.0) { discard; }\n    // The layer's picture",
    );
    let run = run_planted("depth-peeling", path, &wrong, Some(1));
    let c = check(&run, "pixels whose layer count differs");
    assert!(!c.passed);
    let counts = &run.buffers[c.buffer.expect("the layer counts' buffer")];
    let hits = counts.reference.as_ref().expect("the ray's hits");
    let expected = hits
        .iter()
        .enumerate()
        .filter(|(k, &h)| (*k as u32 % counts.width) < 24 && h > 2.0)
        .count();
    let wrong = c.wrong.unwrap();
    assert!(
        expected > 0 && wrong > 0 && wrong <= expected,
        "{wrong} of {expected}"
    );
    for w in &c.first_wrong {
        assert!(w.x < 24 && w.gpu == 2.0 && w.cpu > 2.0, "{w:?}");
    }
    assert!(
        c.where_wrong()[1].starts_with("pixel ("),
        "{:?}",
        c.where_wrong()
    );
}

/// Compact a line of code for comparing: no spaces, no trailing `;`.
fn code(line: &str) -> String {
    line.split("//")
        .next()
        .unwrap()
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .trim_end_matches(';')
        .to_string()
}

/// A template holds the task, never the answer: not the third hint's line, and no line of the
/// solution that the template lacks (nor its right-hand side), in its code or its comments.
#[test]
fn no_template_holds_the_answer() {
    let mut found = Vec::new();
    for lesson in learn::all() {
        for e in lesson.info().exercises {
            let solution = classic_gpgpu::gl::shaders::find(e.shader).unwrap().source;
            let template_path = e.shader.replacen("glsl/learn/", "glsl/learn/exercises/", 1);
            let template = classic_gpgpu::gl::shaders::find(&template_path)
                .unwrap_or_else(|| panic!("{template_path}"))
                .source;
            let compact = code(&template.replace('\n', " ").replace("//", " "));
            let mut answers = vec![code(e.hints[2])];
            for line in solution.lines() {
                if template.lines().any(|t| t.trim() == line.trim()) {
                    continue;
                }
                let whole = code(line);
                if let Some((_, rhs)) = whole.split_once('=') {
                    answers.push(rhs.to_string());
                }
                answers.push(whole);
            }
            for a in answers.iter().filter(|a| a.len() >= 8) {
                if compact.contains(a.as_str()) {
                    found.push(format!("{template_path} holds '{a}'"));
                }
            }
        }
    }
    assert!(found.is_empty(), "{}", found.join("\n"));
}
