//! Feedback that points at the mistake, the terminal that teaches, and `view learn`'s reload:
//! a wrongly filled exercise names its wrong texels with the GPU's and the CPU's values (those
//! of the buffer the pass wrote and of the CPU reference), writes the difference picture and
//! names the viewer command; the hints come in three different steps for every exercise;
//! `--solution` prints the shipped shader and a run of it says so; `learn <id>` prints the idea
//! first and the next lesson last; a shader saved broken while `view learn ping-pong` runs
//! leaves it stepping with the last good one, and a probe over no buffer draws nothing.

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
    // a x - y misses a x + y by 2 |y|, y drawn from [-1, 1): nearly every element is wrong.
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
