//! The lessons of the second half (counting and masks, depth peeling, readback and upload,
//! render to vertex buffer, compute reduction): each passes against its CPU reference, each
//! exercise's solution passes, each unfilled template fails, and the guide built from the
//! runs has no dead link or picture.

mod common;

use classic_gpgpu::learn::{self, LessonOptions};
use std::path::{Path, PathBuf};

const LESSONS: [&str; 5] = [
    "count-and-mask",
    "depth-peeling",
    "readback-and-upload",
    "render-to-vertex-buffer",
    "compute-reduction",
];

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("learn-advanced-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn print_run(run: &learn::LessonRun) {
    println!("{} on {}: passed {}", run.id, run.renderer, run.passed);
    for c in &run.checks {
        println!(
            "  {} {}: {} (tolerance {})",
            if c.passed { "ok  " } else { "FAIL" },
            c.what,
            c.max_error,
            c.tolerance
        );
    }
    println!("  compute: {:?}", run.compute);
}

#[test]
fn every_lesson_passes_against_the_cpu() {
    let ctx = common::context();
    let pictures = temp_dir("pictures");
    for id in LESSONS {
        let lesson = learn::find(id).unwrap();
        let opts = LessonOptions {
            png_dir: Some(pictures.join(id)),
            exercise: None,
        };
        let run = lesson.run(&ctx, &opts).unwrap();
        print_run(&run);
        assert!(run.passed, "{id} failed: {:?}", run.checks);
        assert!(!run.checks.is_empty());
        assert!(run.max_error.is_finite());
        for pass in &run.passes {
            if let Some(p) = &pass.picture {
                assert!(pictures.join(id).join(p).is_file(), "{id}: {p} missing");
            }
        }
        for shader in &run.shaders {
            assert!(Path::new(env!("CARGO_MANIFEST_DIR")).join(shader).is_file());
        }
        // The compute counterpart ran exactly where the context has compute shaders.
        let compute = run.compute.as_deref().unwrap_or("");
        assert_eq!(
            compute.starts_with("ran"),
            ctx.has_compute(),
            "{id}: {compute}"
        );
        if !ctx.has_compute() {
            assert!(compute.contains("4.3"), "{id}: {compute}");
            assert!(run.checks.iter().all(|c| !c.what.starts_with("compute")));
        }
    }
}

/// Every exercise of these lessons: the shipped solution passes, the template (given through
/// a glsl folder, as a learner would) fails its check and gives the hint.
#[test]
fn solutions_pass_and_templates_fail() {
    let ctx = common::context();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for id in LESSONS {
        let lesson = learn::find(id).unwrap();
        for exercise in lesson.info().exercises {
            let opts = LessonOptions {
                png_dir: None,
                exercise: Some(exercise.number),
            };
            let template = exercise
                .shader
                .replacen("glsl/learn/", "glsl/learn/exercises/", 1);
            let template_text = std::fs::read_to_string(root.join(&template)).unwrap();
            assert!(template_text.contains("// EXERCISE:"), "{template}");
            if !ctx.has_compute() && exercise.shader.ends_with(".comp") {
                ctx.set_glsl_dir(None);
                let err = lesson.run(&ctx, &opts).err().expect("an error without 4.3");
                assert!(err.to_string().contains("4.3"), "{err}");
                println!("{id} exercise {}: needs 4.3 here", exercise.number);
                continue;
            }
            ctx.set_glsl_dir(None);
            let solved = lesson.run(&ctx, &opts).unwrap();
            assert!(solved.passed, "{id} solution {}", exercise.number);
            assert!(solved.hint.is_none());

            let dir = temp_dir(&format!("{id}-{}", exercise.number));
            let learner = dir.join(exercise.shader);
            std::fs::create_dir_all(learner.parent().unwrap()).unwrap();
            std::fs::write(&learner, &template_text).unwrap();
            ctx.set_glsl_dir(Some(dir.clone()));
            let unfilled = lesson.run(&ctx, &opts);
            ctx.set_glsl_dir(None);
            let unfilled = unfilled.unwrap();
            print_run(&unfilled);
            assert!(
                !unfilled.passed,
                "{id}: the unfilled template {template} passed"
            );
            assert_eq!(unfilled.hint.as_deref(), Some(exercise.hint));
        }
    }
}
