//! The viewer's live loop on a lesson that iterates (`view learn ping-pong`), headless through
//! the same `Demo` and `LiveDemo` code the window runs: a step is one more pass from the
//! current iterate (counted in the GL trace, the same at any iteration); the buffers keep their
//! numbers at every iteration, the numbers `learn` names; the viewer opens on the latest
//! iterate, which changes under the probe; `--buffer` takes a buffer a later iteration makes;
//! a reload builds once and replays the steps taken at once, and a fixed shader's frame shows
//! its passing checks. The window's side (Xvfb) is in tests/view.rs.

use classic_gpgpu::gl::trace::TracedCall;
use classic_gpgpu::gl::Context;
use classic_gpgpu::learn::{self, Iteration, LessonOptions, Slot};
use classic_gpgpu::view::live::LiveDemo;
use classic_gpgpu::view::{draw_frame, first_shown, Canvas, DemoSpec, ViewState};
use std::path::Path;

mod common;

const JACOBI: &str = "glsl/learn/jacobi.frag";

fn ping_pong() -> DemoSpec {
    DemoSpec::Learn {
        id: "ping-pong".into(),
    }
}

fn iteration(ctx: &Context) -> Box<dyn Iteration> {
    learn::find("ping-pong")
        .unwrap()
        .iteration(ctx, &LessonOptions::default())
        .unwrap()
        .expect("ping-pong iterates")
}

/// How many draws and dispatches `calls` made under each pass name, and the programs linked.
fn count(calls: &[TracedCall], function: &str, pass: Option<&str>) -> usize {
    calls
        .iter()
        .filter(|c| c.function.starts_with(function))
        .filter(|c| pass.is_none() || c.pass.as_deref() == pass)
        .count()
}

/// The calls `f` makes on `ctx`.
fn traced<T>(ctx: &Context, f: impl FnOnce() -> T) -> (T, Vec<TracedCall>) {
    ctx.trace_start();
    let out = f();
    (out, ctx.trace_stop())
}

/// The shipped Jacobi step with its weights changed from 1/4 to `weight`: it compiles, and
/// any weight but 0.25 fails the checks from the first step.
fn jacobi_weighted(weight: &str) -> String {
    let shipped = classic_gpgpu::gl::shaders::find(JACOBI).unwrap().source;
    assert!(shipped.contains("o_value = 0.25 *"), "the shipped step");
    shipped.replace("o_value = 0.25 *", &format!("o_value = {weight} *"))
}

/// Write `text` to `DIR/<path>` with a modification time `seconds` after `base`, so that each
/// save is a new stamp for the watch whatever the file system's clock resolution.
fn save(dir: &Path, path: &str, text: &str, base: std::time::SystemTime, seconds: u64) {
    let file = dir.join(path);
    std::fs::create_dir_all(file.parent().unwrap()).unwrap();
    std::fs::write(&file, text).unwrap();
    std::fs::File::options()
        .write(true)
        .open(&file)
        .unwrap()
        .set_modified(base + std::time::Duration::from_secs(seconds))
        .unwrap();
}

#[test]
fn a_step_is_one_more_pass_from_the_current_iterate_at_any_iteration() {
    let ctx = common::context();
    let compute = ctx.has_compute() as usize;
    let mut jacobi = iteration(&ctx);
    for before in [0, 1, 5, 40] {
        let target = before;
        while jacobi.iterations() < target {
            jacobi.advance(1).unwrap();
        }
        let (result, calls) = traced(&ctx, || jacobi.advance(1));
        result.unwrap();
        // One Jacobi pass, one in place and one compute dispatch: never the earlier steps
        // again, and nothing compiled.
        assert_eq!(count(&calls, "glDrawArrays", Some("jacobi step")), 1);
        assert_eq!(count(&calls, "glDrawArrays", Some("jacobi in place")), 1);
        assert_eq!(count(&calls, "glDispatchCompute", None), compute);
        assert_eq!(count(&calls, "glLinkProgram", None), 0);
        assert_eq!(jacobi.iterations(), before + 1);
    }
    // Step by step, it reaches the iterate that `advance(n)` at once reaches, and the CPU's
    // (every check passes: fp32 tolerance stated in the lesson). The texture read and drawn
    // into at once is left out: GL leaves its result undefined (softpipe's differs between
    // two runs of the same steps).
    let (by_steps, _) = jacobi.record().unwrap();
    let mut at_once = iteration(&ctx);
    at_once.advance(41).unwrap();
    let (at_once, _) = at_once.record().unwrap();
    assert!(by_steps.passed, "{:#?}", by_steps.checks);
    assert_eq!(by_steps.buffers.len(), at_once.buffers.len());
    for (a, b) in by_steps.buffers.iter().zip(&at_once.buffers) {
        let name = &by_steps.passes[a.pass].name;
        if !name.contains("undefined") {
            assert_eq!(a.values, b.values, "{name}");
        }
    }
}

/// The names of the slots, the latest's without its step number.
fn shape(slots: &[Slot]) -> Vec<String> {
    slots
        .iter()
        .map(|s| match s.name.strip_suffix(" (the latest)") {
            Some(_) => "latest".to_string(),
            None => s.name.clone(),
        })
        .collect()
}

#[test]
fn the_buffers_keep_their_numbers_at_every_iteration_the_ones_learn_names() {
    let ctx = common::context();
    let mut jacobi = iteration(&ctx);
    jacobi.advance(1).unwrap();
    let (_, first) = jacobi.record().unwrap();
    for k in 2..=8 {
        jacobi.advance(1).unwrap();
        let (run, slots) = jacobi.record().unwrap();
        assert_eq!(shape(&slots), shape(&first), "iteration {k}");
        // Each slot holds the buffer of its name; the latest, step k's.
        for slot in &slots {
            let b = slot.buffer.expect("every buffer is made by iteration 2");
            let name = &run.passes[run.buffers[b].pass].name;
            let wanted = slot
                .name
                .strip_suffix(" (the latest)")
                .unwrap_or(&slot.name);
            assert_eq!(name, wanted, "iteration {k}");
        }
        let latest = slots.iter().find(|s| s.changes).unwrap();
        assert_eq!(latest.name, format!("step {k} (the latest)"));
    }
    // At the first iteration step 2 is not made yet; its number is kept for it.
    assert_eq!(first[2].name, "step 2");
    assert_eq!(first[2].buffer, None);

    // `learn ping-pong` with the step broken: its failed check names the buffer by the number
    // the viewer gives it, the one the viewer opens on.
    let dir = common::temp_dir("view-live", "numbers");
    save(
        &dir,
        JACOBI,
        &jacobi_weighted("0.24"),
        std::time::SystemTime::now(),
        0,
    );
    ctx.set_glsl_dir(Some(dir.clone()));
    let run = learn::find("ping-pong")
        .unwrap()
        .run(&ctx, &LessonOptions::default())
        .unwrap();
    let demo = ping_pong().build(&ctx, (320, 240)).unwrap();
    ctx.set_glsl_dir(None);
    let failed = run
        .checks
        .iter()
        .find(|c| !c.passed)
        .expect("a failed check");
    let named = failed.buffer.expect("the check names its buffer");
    assert_eq!(first_shown(demo.as_ref(), None).unwrap(), named);
    assert_eq!(demo.buffers().len(), run.buffers.len());
    for (i, b) in run.buffers.iter().enumerate() {
        let learn_name = &run.passes[b.pass].name;
        let view_name = &demo.buffers()[i];
        assert!(
            view_name == learn_name || i == named,
            "buffer {i}: learn {learn_name}, view {view_name}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The probe's GPU value at the first canvas pixel over texel (`x`, `y`) of the buffer shown.
fn probed(canvas: &Canvas, texel: (u32, u32)) -> Option<((u32, u32), String)> {
    let wanted = format!("texel ({}, {})", texel.0, texel.1);
    for y in 0..canvas.height() {
        for x in 0..canvas.width() {
            if let Some(lines) = canvas.probe_buffer((x, y)) {
                if lines[0].ends_with(&wanted) {
                    return Some(((x, y), lines[1].clone()));
                }
            }
        }
    }
    None
}

#[test]
fn the_viewer_opens_on_the_latest_iterate_which_changes_under_the_probe() {
    let ctx = common::context();
    let size = (480, 360);
    let canvas = Canvas::new(&ctx, size.0, size.1).unwrap();
    let value_at = |shown: Option<usize>, frames: usize| {
        let mut demo = ping_pong().build(&ctx, size).unwrap();
        let view = ViewState {
            shown: first_shown(demo.as_ref(), shown).unwrap(),
            ..ViewState::default()
        };
        for _ in 0..frames {
            demo.step().unwrap();
        }
        draw_frame(demo.as_mut(), &canvas, &view, frames).unwrap();
        // An interior texel one row below the held top row: it warms at every step.
        probed(&canvas, (8, 14)).expect("texel (8, 14) drawn")
    };
    let opening = (value_at(None, 1), value_at(None, 3));
    assert_ne!(opening.0 .1, opening.1 .1, "the opening buffer changes");
    let start = (value_at(Some(0), 1), value_at(Some(0), 3));
    assert_eq!(start.0 .1, start.1 .1, "the start grid does not");
    assert_eq!(start.0 .1, "GPU 0");
}

#[test]
fn buffer_takes_any_buffer_the_lesson_makes_and_names_them_when_refused() {
    let ctx = common::context();
    let mut demo = ping_pong().build(&ctx, (320, 240)).unwrap();
    let buffers = demo.buffers();
    // With compute (llvmpipe): start, steps 1 and 2, the latest, in place, compute.
    assert_eq!(buffers.len(), 5 + ctx.has_compute() as usize, "{buffers:?}");
    // At the first frame: a buffer the learner asked for before (`--buffer 4` was refused
    // with 4 buffers made), and step 2, which the next iteration makes.
    assert_eq!(first_shown(demo.as_ref(), Some(4)).unwrap(), 4);
    assert_eq!(first_shown(demo.as_ref(), Some(2)).unwrap(), 2);
    demo.show(2);
    let overlay = demo.overlay();
    assert!(
        overlay.iter().any(|l| l.contains("step 2: not made yet")),
        "{overlay:?}"
    );
    demo.step().unwrap();
    demo.show(2);
    let overlay = demo.overlay();
    assert!(
        overlay.iter().any(|l| l.starts_with("pass 2: step 2")),
        "{overlay:?}"
    );
    assert_eq!(demo.buffers().len(), buffers.len(), "the same numbers");
    let buffers = demo.buffers();
    let err = first_shown(demo.as_ref(), Some(buffers.len()))
        .unwrap_err()
        .to_string();
    for (i, name) in buffers.iter().enumerate() {
        let name = name.split(" (the latest)").next().unwrap();
        assert!(err.contains(&format!("{i} {name}")), "{err}");
    }
    assert!(
        err.starts_with(&format!("--buffer {}", buffers.len())),
        "{err}"
    );

    // Through the binary: the issue's `--buffer 4` at the first frame, and one too many.
    let png = common::temp_dir("view-live", "buffer").join("b.png");
    let view = |buffer: &str| {
        common::classic_gpgpu(&[
            "view",
            "learn",
            "ping-pong",
            "--headless",
            "--frames",
            "0",
            "--buffer",
            buffer,
            "--force",
            "--screenshot",
            png.to_str().unwrap(),
        ])
    };
    let out = view("4");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = view("9");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && stderr.contains("--buffer 9"),
        "{stderr}"
    );
    assert!(
        stderr.contains("0 start") && stderr.contains("4 in place"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn a_reload_builds_once_and_replays_the_steps_taken_at_once() {
    let ctx = common::context();
    let compute = ctx.has_compute() as usize;
    let dir = common::temp_dir("view-live", "reload");
    let base = std::time::SystemTime::now();
    // Saved wrong (weights 0.24): it compiles, its checks fail.
    save(&dir, JACOBI, &jacobi_weighted("0.24"), base, 1);
    ctx.set_glsl_dir(Some(dir.clone()));
    let size = (320, 240);
    let canvas = Canvas::new(&ctx, size.0, size.1).unwrap();
    let mut live = LiveDemo::new(&ping_pong(), &ctx, size, "").unwrap();
    for _ in 0..30 {
        live.step().unwrap();
    }
    let fails = |live: &mut LiveDemo| live.demo().overlay().iter().any(|l| l.starts_with("FAIL"));
    assert!(fails(&mut live));
    assert_eq!(live.take_reload().map(|r| r.steps), None, "no reload yet");

    // Fixed: one build (its programs linked once) and the 31 iterations replayed, one pass
    // each per path, not the lesson again from the start at each step.
    save(&dir, JACOBI, &jacobi_weighted("0.25"), base, 2);
    let (worked, calls) = traced(&ctx, || live.poll(&ctx));
    assert_eq!(worked, Some(true), "{:?}", live.error());
    assert_eq!(count(&calls, "glLinkProgram", None), 1 + compute);
    assert_eq!(count(&calls, "glDrawArrays", Some("jacobi step")), 31);
    assert_eq!(count(&calls, "glDrawArrays", Some("jacobi in place")), 31);
    assert_eq!(count(&calls, "glDispatchCompute", None), 31 * compute);
    // The frame after it: the same iteration, every check passing.
    live.draw(&canvas, &ViewState::default()).unwrap();
    let overlay = live.demo().overlay();
    assert!(
        overlay.iter().any(|l| l.starts_with("31 iterations")),
        "{overlay:?}"
    );
    assert!(!fails(&mut live), "{overlay:?}");
    let reload = live
        .take_reload()
        .expect("the reload, for the window's log");
    assert!(reload.worked && reload.steps == 30, "{reload:?}");
    assert_eq!(reload.files, vec![JACOBI]);
    let line = reload.shown_line();
    assert!(
        line.starts_with("reload shown: glsl/learn/jacobi.frag saved"),
        "{line}"
    );
    assert!(live.take_reload().is_none(), "taken once");

    // Long after the relaxation has reached its fixed point, a reload replays no more than
    // the iterations that led there.
    for _ in 0..1500 {
        live.step().unwrap();
    }
    let overlay = live.demo().overlay();
    let stopped = overlay
        .iter()
        .find(|l| l.contains("a fixed point"))
        .unwrap_or_else(|| panic!("stopped at a fixed point: {overlay:?}"));
    let iterations: usize = stopped.split(' ').next().unwrap().parse().unwrap();
    assert!(iterations < 1500, "{stopped}");
    save(&dir, JACOBI, &jacobi_weighted("0.25"), base, 3);
    let (worked, calls) = traced(&ctx, || live.poll(&ctx));
    assert_eq!(worked, Some(true));
    assert_eq!(
        count(&calls, "glDrawArrays", Some("jacobi step")),
        iterations
    );
    assert_eq!(live.steps(), 1530);
    ctx.set_glsl_dir(None);
    let _ = std::fs::remove_dir_all(&dir);
}
