//! Lessons 0-5 of `learn`: each passes against its CPU reference (with its compute counterpart
//! where OpenGL 4.3 is there), each exercise's solution passes, each unfilled template fails
//! with its hint, and a broken lesson shader from a shader folder fails its check. Then the
//! command line: `learn --list`, `learn <id> --json --png DIR`, and its refusals.

use classic_gpgpu::gl::Context;
use classic_gpgpu::learn::{self, LessonOptions, LessonRun};
use common::{classic_gpgpu, json_of};
use std::path::{Path, PathBuf};

mod common;

const LESSONS: [&str; 6] = [
    "texture-is-array",
    "quad-is-loop",
    "ping-pong",
    "reduction",
    "several-outputs",
    "scatter-and-blend",
];

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("learn_basics_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(ctx: &Context, id: &str, exercise: Option<u32>) -> LessonRun {
    let opts = LessonOptions {
        exercise,
        ..LessonOptions::default()
    };
    learn::find(id)
        .unwrap()
        .run(ctx, &opts)
        .unwrap_or_else(|e| panic!("{id}: {e:#}"))
}

/// The shipped text of a lesson shader (`glsl/learn/...`).
fn shipped(path: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap()
}

/// Put `text` at `dir/path`, where `set_glsl_dir(dir)` makes programs read it.
fn put(dir: &Path, path: &str, text: &str) {
    classic_gpgpu::files::write_bytes(&dir.join(path), text.as_bytes()).unwrap();
}

#[test]
fn lessons_are_numbered_in_order_and_name_real_files() {
    let all = learn::all();
    for (k, id) in LESSONS.iter().enumerate() {
        let info = learn::find(id).unwrap().info();
        assert_eq!(info.number, k as u32, "{id}");
        assert_eq!(all[k].info().id, *id);
        assert_eq!(learn::find(&k.to_string()).unwrap().info().id, *id);
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        for step in info.paper_steps {
            assert!(root.join(step.file).is_file(), "{id}: {}", step.file);
        }
        for shader in info.shaders {
            assert!(root.join(shader).is_file(), "{id}: {shader}");
        }
        assert!(!info.exercises.is_empty(), "{id} has no exercise");
        for e in info.exercises {
            let template = e.shader.replace("glsl/learn/", "glsl/learn/exercises/");
            let text = std::fs::read_to_string(root.join(&template)).unwrap();
            assert!(text.contains("// EXERCISE:"), "{template} marks no gap");
            assert!(info.shaders.contains(&e.shader), "{id}: {}", e.shader);
        }
    }
    let err = learn::find("no-such-lesson").err().unwrap().to_string();
    assert!(err.contains("ping-pong"), "{err}");
}

#[test]
fn every_lesson_passes_against_the_cpu_with_its_compute_counterpart() {
    let ctx = common::context();
    for id in LESSONS {
        let r = run(&ctx, id, None);
        let failed: Vec<_> = r.checks.iter().filter(|c| !c.passed).collect();
        assert!(r.passed, "{id} on {}: {failed:#?}", r.renderer);
        assert!(r.checks.len() >= 2, "{id}: {:?}", r.checks);
        assert!(r.max_error.is_finite());
        assert!(r.hint.is_none());
        let info = learn::find(id).unwrap().info();
        for shader in &r.shaders {
            assert!(info.shaders.contains(&shader.as_str()), "{id} ran {shader}");
        }
        let compute = r.compute.as_deref().unwrap();
        if ctx.has_compute() {
            assert!(compute.starts_with("ran"), "{id}: {compute}");
            assert!(
                r.checks.iter().any(|c| c.what.starts_with("compute:")),
                "{id}: no compute check"
            );
        } else {
            assert!(compute.contains("4.3"), "{id}: {compute}");
        }
        // Every pass that shows a buffer shows one of its own size.
        for b in &r.buffers {
            assert_eq!(b.values.len(), (b.width * b.height) as usize * b.channels);
        }
    }
}

#[test]
fn what_the_formats_keep_and_the_reduction_ladders_are_measured() {
    let ctx = common::context();
    let r = run(&ctx, "texture-is-array", None);
    let note = |name: &str| {
        r.notes
            .iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("no note {name}: {:?}", r.notes))
            .1
            .clone()
    };
    // 2049 is a tie between the half floats 2048 and 2050.
    assert!(
        note("R16F keeps").contains("2049 came back as 2048"),
        "{}",
        note("R16F keeps")
    );
    assert!(note("RGBA8 keeps").contains("values outside [0, 1] came back clamped"));
    // 48 -> 24 -> 12 -> 6 -> 3 -> 2 -> 1, and 48 -> 12 -> 3 -> 1.
    let r = run(&ctx, "reduction", None);
    let passes = |name: &str| r.notes.iter().find(|(n, _)| n == name).unwrap().1.clone();
    assert!(
        passes("2x2 passes").starts_with("6 ("),
        "{}",
        passes("2x2 passes")
    );
    assert!(
        passes("4x4 passes").starts_with("3 ("),
        "{}",
        passes("4x4 passes")
    );
}

#[test]
fn every_solution_passes_and_every_unfilled_template_fails_with_its_hint() {
    let ctx = common::context();
    let templates = learn::templates();
    for id in LESSONS {
        let info = learn::find(id).unwrap().info();
        for e in info.exercises {
            ctx.set_glsl_dir(None);
            let solution = run(&ctx, id, Some(e.number));
            assert!(
                solution.passed,
                "{id} exercise {}: {:#?}",
                e.number, solution.checks
            );
            let name = e.shader.replace("glsl/learn/", "glsl/learn/exercises/");
            let template = templates
                .iter()
                .find(|t| t.name == name)
                .unwrap_or_else(|| panic!("no template {name} in learn::templates()"));
            let dir = scratch(&format!("template_{id}_{}", e.number));
            put(&dir, e.shader, template.source);
            ctx.set_glsl_dir(Some(dir.clone()));
            let attempt = run(&ctx, id, Some(e.number));
            ctx.set_glsl_dir(None);
            assert!(!attempt.passed, "{id}: the unfilled template {name} passed");
            assert_eq!(attempt.hint.as_deref(), Some(e.hints[0]), "{id}");
            let _ = std::fs::remove_dir_all(&dir);
        }
    }
    let err = learn::find("reduction")
        .unwrap()
        .run(
            &ctx,
            &LessonOptions {
                exercise: Some(9),
                ..LessonOptions::default()
            },
        )
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("--exercise 9") && err.contains("exercise 1"),
        "{err}"
    );
}

#[test]
fn a_broken_lesson_shader_fails_its_check() {
    let ctx = common::context();
    // The 2x2 reduction dropping one texel of each block: the sum falls short, the maximum may
    // miss the largest value.
    let path = "glsl/learn/reduce_2x2.frag";
    let broken = shipped(path).replace("+ d.x,", ",");
    assert_ne!(broken, shipped(path));
    let dir = scratch("broken_reduce");
    put(&dir, path, &broken);
    ctx.set_glsl_dir(Some(dir.clone()));
    let r = run(&ctx, "reduction", None);
    ctx.set_glsl_dir(None);
    assert!(!r.passed);
    let failed: Vec<&str> = r
        .checks
        .iter()
        .filter(|c| !c.passed)
        .map(|c| c.what.as_str())
        .collect();
    assert!(
        failed.iter().any(|w| w.starts_with("2x2: sum")),
        "{failed:?}"
    );
    assert!(!failed.iter().any(|w| w.starts_with("4x4")), "{failed:?}");
    assert!(r.hint.is_some());
    // The Jacobi step with weights 0.24: off after the first step.
    let path = "glsl/learn/jacobi.frag";
    let broken = shipped(path).replace("o_value = 0.25 *", "o_value = 0.24 *");
    assert_ne!(broken, shipped(path));
    let dir = scratch("broken_jacobi");
    put(&dir, path, &broken);
    ctx.set_glsl_dir(Some(dir.clone()));
    let r = run(&ctx, "ping-pong", None);
    let failed = r.checks.iter().filter(|c| !c.passed).count();
    assert!(!r.passed && failed >= 1, "{:#?}", r.checks);
    // A shader that does not compile is an error naming the file.
    put(
        &dir,
        path,
        &shipped(path).replace("float here", "flot here"),
    );
    let err = learn::find("ping-pong")
        .unwrap()
        .run(&ctx, &LessonOptions::default())
        .err()
        .unwrap();
    ctx.set_glsl_dir(None);
    assert!(format!("{err:#}").contains("jacobi.frag"), "{err:#}");
}

#[test]
fn learn_lists_runs_and_writes_pictures_through_the_binary() {
    let list = json_of(&["learn", "--list", "--json"]);
    let list = list.as_array().unwrap();
    for (k, id) in LESSONS.iter().enumerate() {
        let l = list.iter().find(|l| l["id"] == *id).unwrap();
        assert_eq!(l["number"], k);
        assert!(!l["paper_steps"].as_array().unwrap().is_empty());
        assert!(!l["shaders"].as_array().unwrap().is_empty());
        assert_eq!(l["exercises"][0]["hints"].as_array().unwrap().len(), 3);
    }
    let dir = scratch("cli_png");
    let pictures = dir.join("pictures");
    let v = json_of(&[
        "learn",
        "reduction",
        "--json",
        "--png",
        pictures.to_str().unwrap(),
    ]);
    assert_eq!(v["passed"], true);
    assert!(v["max_error"].as_f64().unwrap().is_finite());
    assert!(v["shaders"]
        .as_array()
        .unwrap()
        .iter()
        .any(|s| s == "glsl/learn/reduce_wide.frag"));
    let picture = v["passes"][1]["picture"].as_str().unwrap();
    // A 24x20 level of two channels: two panels, enlarged (nearest texel) with titles and
    // colour keys, so the picture is bigger than the buffer.
    let png = image::open(pictures.join(picture)).unwrap();
    assert!(
        png.width() >= 2 * 24 * 8 && png.height() > 20 * 8,
        "{png:?}"
    );
    let npy = pictures.join(picture.replace(".png", ".npy"));
    let (shape, values) = classic_gpgpu::files::read_npy(&npy).unwrap();
    assert_eq!(shape, vec![20, 24, 2]);
    assert!(values.iter().all(|v| v.is_finite()));
    // The pictures exist now: a rerun of the same lesson replaces its own pictures (the
    // folder's marker says they are its own); another lesson's run is refused, even with
    // --force (the folder is the other lesson's: its marker is never replaced), and the
    // user's file in it is never touched.
    let out = classic_gpgpu(&["learn", "reduction", "--png", pictures.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(pictures.join(picture).is_file());
    let notes = pictures.join("notes.txt");
    std::fs::write(&notes, "the learner's notes").unwrap();
    let out = classic_gpgpu(&["learn", "1", "--png", pictures.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && stderr.contains("--force"),
        "{stderr}"
    );
    assert!(pictures.join(picture).is_file());
    let forced = classic_gpgpu(&["learn", "1", "--png", pictures.to_str().unwrap(), "--force"]);
    let stderr = String::from_utf8_lossy(&forced.stderr);
    assert!(
        !forced.status.success()
            && stderr.contains("`classic-gpgpu learn reduction --png`'s")
            && stderr.contains("not even with --force"),
        "{stderr}"
    );
    assert!(pictures.join(picture).is_file());
    // A folder of the user's takes the pictures with --force, beside the user's file.
    let mine = dir.join("mine");
    std::fs::create_dir_all(&mine).unwrap();
    std::fs::write(mine.join("notes.txt"), "the learner's notes").unwrap();
    let out = classic_gpgpu(&[
        "learn",
        "1",
        "--png",
        mine.to_str().unwrap(),
        "--force",
        "--exercise",
        "1",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("pass 1: saxpy") && stdout.contains("passed"),
        "{stdout}"
    );
    for notes in [notes, mine.join("notes.txt")] {
        assert_eq!(
            std::fs::read_to_string(&notes).unwrap(),
            "the learner's notes"
        );
    }
    // Every lesson's passes get their pictures from the command line, the second half's too.
    for id in ["count-and-mask", "depth-peeling", "render-to-vertex-buffer"] {
        let folder = dir.join(id);
        let v = json_of(&["learn", id, "--json", "--png", folder.to_str().unwrap()]);
        let named: Vec<&str> = v["passes"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|p| p["picture"].as_str())
            .collect();
        assert!(!named.is_empty(), "{id}: no pass named a picture");
        for picture in named {
            assert!(folder.join(picture).is_file(), "{id}: {picture} missing");
        }
    }
    // Bad input: a clear message, a non-zero exit, no panic.
    for (args, expect) in [
        (vec!["learn", "no-such-lesson"], "texture-is-array"),
        (
            vec!["learn", "ping-pong", "--exercise", "7"],
            "--exercise 7",
        ),
        (vec!["learn"], "<ID>"),
    ] {
        let out = classic_gpgpu(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(stderr.contains(expect), "{args:?}: {stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn view_learn_shows_each_pass_and_steps_the_iterations() {
    use classic_gpgpu::view::{self, DemoSpec, ViewState};
    let ctx = common::context();
    let spec = DemoSpec::Learn {
        id: "ping-pong".into(),
    };
    let frame = |frames: usize, shown: usize| {
        let state = ViewState {
            shown,
            ..ViewState::default()
        };
        view::headless(&spec, &ctx, (160, 120), frames, &state, "").unwrap()
    };
    let mut demo = spec.build(&ctx, (160, 120)).unwrap();
    let buffers = demo.buffers();
    assert_eq!(buffers[0], "start");
    assert!(buffers.iter().any(|b| b == "step 1"), "{buffers:?}");
    assert!(demo.overlay().iter().any(|l| l.contains("1 iteration [")));
    demo.step().unwrap();
    assert!(demo.overlay().iter().any(|l| l.contains("2 iterations")));
    assert!(demo
        .overlay()
        .iter()
        .any(|l| l.contains("checks against the CPU") && l.contains("passed")));
    for _ in 0..3 {
        demo.step().unwrap();
    }
    assert!(
        demo.buffers().iter().any(|b| b == "step 5 (the latest)"),
        "{:?}",
        demo.buffers()
    );
    // Tab shows another pass's buffer.
    assert_ne!(frame(1, 0), frame(1, 1));
    // A lesson that does not iterate keeps its run: the same buffers after any step.
    let mut demo = DemoSpec::Learn {
        id: "reduction".into(),
    }
    .build(&ctx, (160, 120))
    .unwrap();
    let before = demo.buffers();
    demo.step().unwrap();
    assert_eq!(before, demo.buffers());
    let err = DemoSpec::Learn { id: "nope".into() }
        .build(&ctx, (160, 120))
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("scatter-and-blend"), "{err}");
}

/// The learner's path through the binary: `glsl export DIR --exercises` writes the template in
/// place of the solution, `learn <id> --exercise N --glsl-dir DIR` runs it and fails with the
/// hint (exit non-zero); the same command without `--glsl-dir` runs the shipped solution.
#[test]
fn an_exported_template_fails_through_the_binary_and_the_solution_passes() {
    let dir = scratch("cli_exercise");
    let mine = dir.join("mine");
    let export = classic_gpgpu(&["glsl", "export", mine.to_str().unwrap(), "--exercises"]);
    assert!(
        export.status.success(),
        "{}",
        String::from_utf8_lossy(&export.stderr)
    );
    let info = learn::find("reduction").unwrap().info();
    let exercise = info.exercises[0];
    assert!(mine.join(exercise.shader).is_file(), "{}", exercise.shader);
    let number = exercise.number.to_string();
    let attempt = classic_gpgpu(&[
        "--glsl-dir",
        mine.to_str().unwrap(),
        "learn",
        "reduction",
        "--exercise",
        &number,
    ]);
    let stderr = String::from_utf8_lossy(&attempt.stderr);
    assert!(!attempt.status.success(), "the unfilled template passed");
    assert!(stderr.contains(exercise.hints[0]), "no hint in: {stderr}");
    let solution = classic_gpgpu(&["learn", "reduction", "--exercise", &number]);
    assert!(
        solution.status.success(),
        "{}",
        String::from_utf8_lossy(&solution.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
