//! `learn`: the lessons of the basic approach (`classic_gpgpu::learn`). `learn --list` shows
//! them in order; `learn <id>` runs one, says what each pass does, checks it against the CPU,
//! writes each pass's buffer with `--png DIR`, and exits non-zero (with the exercise's hint)
//! when a check fails.

use anyhow::Context as _;
use classic_gpgpu::gl::Context;
use classic_gpgpu::learn::{self, LessonOptions, LessonRun};
use classic_gpgpu::report::report_folder::Staged;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct LearnArgs {
    /// The lesson to run: its id (e.g. texture-is-array) or its number.
    #[arg(required_unless_present_any = ["list", "guide"])]
    pub id: Option<String>,
    /// List the lessons: id, number, title, the paper steps, the shader files, the exercises.
    #[arg(long, conflicts_with = "id")]
    pub list: bool,
    /// Write each pass's buffer into this folder as PNG (and .npy for float buffers). A
    /// folder holding files this lesson's --png did not write is refused without --force; a
    /// rerun replaces the pictures of the earlier one.
    #[arg(long, value_name = "DIR")]
    pub png: Option<PathBuf>,
    /// Run with exercise N's shader: the learner's file where the shader folder has it, else
    /// the shipped solution.
    #[arg(long, value_name = "N")]
    pub exercise: Option<u32>,
    /// Write the offline HTML guide into this folder: every lesson run on this renderer, one
    /// page each with its passes, pictures and checks, the reading order into the papers, and
    /// a glossary.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["id", "list", "png", "exercise"])]
    pub guide: Option<PathBuf>,
    /// Write the --png pictures (or the --guide) into a folder that holds other files (they
    /// are never removed or replaced).
    #[arg(long)]
    pub force: bool,
}

pub fn run(
    args: &LearnArgs,
    json: bool,
    context: impl FnOnce() -> anyhow::Result<Context>,
) -> anyhow::Result<()> {
    if args.list {
        return list(json);
    }
    if let Some(dir) = &args.guide {
        return guide(dir, args.force, json, context()?);
    }
    let id = args
        .id
        .as_deref()
        .context("name a lesson, or pass --list")?;
    let lesson = learn::find(id)?;
    // The one rule of every folder writer (report_folder), checked before any work.
    let folder = match &args.png {
        Some(dir) => Some(Staged::begin(
            "--png",
            &format!("learn {} --png", lesson.info().id),
            dir,
            args.force,
        )?),
        None => None,
    };
    let ctx = context()?;
    let opts = LessonOptions {
        png_dir: None,
        exercise: args.exercise,
    };
    let mut run = lesson.run(&ctx, &opts)?;
    if let Some(folder) = folder {
        run.write_pictures(folder.path())?;
        folder.finish()?;
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&run)?);
    } else {
        print_run(&run, args.png.as_ref());
    }
    if run.passed {
        return Ok(());
    }
    let failed = run.checks.iter().filter(|c| !c.passed).count();
    let mut message = format!(
        "lesson {}: {failed} of {} checks failed",
        run.id,
        run.checks.len()
    );
    if let Some(hint) = &run.hint {
        message.push_str(&format!("\nhint: {hint}"));
    }
    anyhow::bail!(message)
}

/// `learn --list`.
fn list(json: bool) -> anyhow::Result<()> {
    let infos: Vec<_> = learn::all().iter().map(|l| l.info()).collect();
    if json {
        println!("{}", serde_json::to_string_pretty(&infos)?);
        return Ok(());
    }
    for info in infos {
        println!("{:>2}  {:<20} {}", info.number, info.id, info.title);
        for step in info.paper_steps {
            println!(
                "      paper step  {}: {} ({})",
                step.paper, step.step, step.file
            );
        }
        println!("      shaders     {}", info.shaders.join(", "));
        for e in info.exercises {
            println!("      exercise {}  {} [{}]", e.number, e.task, e.shader);
        }
    }
    Ok(())
}

/// The run as text: each pass, each check, the notes, the compute counterpart.
fn print_run(run: &LessonRun, png: Option<&PathBuf>) {
    println!("lesson {}: {} ({})", run.id, run.title, run.renderer);
    for (k, pass) in run.passes.iter().enumerate() {
        let shader = if pass.shader.is_empty() {
            String::new()
        } else {
            format!(" [{}]", pass.shader)
        };
        println!("  pass {k}: {}{shader}", pass.name);
        println!("          {}", pass.what);
        if let (Some(dir), Some(picture)) = (png, &pass.picture) {
            println!("          wrote {}", dir.join(picture).display());
        }
    }
    for check in &run.checks {
        println!(
            "  {} {}: error {:.3e} (tolerance {:.3e})",
            if check.passed { "ok  " } else { "FAIL" },
            check.what,
            check.max_error,
            check.tolerance
        );
    }
    for (name, value) in &run.notes {
        println!("  note {name}: {value}");
    }
    if let Some(compute) = &run.compute {
        println!("  compute counterpart: {compute}");
    }
    println!(
        "{}: largest error {:.3e}",
        if run.passed { "passed" } else { "FAILED" },
        run.max_error
    );
}

/// `learn --guide DIR`: run every lesson and write the guide; fails when a lesson failed.
fn guide(dir: &std::path::Path, force: bool, json: bool, ctx: Context) -> anyhow::Result<()> {
    let written = classic_gpgpu::report::guide::write_guide(&ctx, dir, force)?;
    let failed: Vec<&str> = written
        .lessons
        .iter()
        .filter(|(_, passed)| !passed)
        .map(|(id, _)| id.as_str())
        .collect();
    if json {
        let lessons: Vec<serde_json::Value> = written
            .lessons
            .iter()
            .map(|(id, passed)| serde_json::json!({ "id": id, "passed": passed }))
            .collect();
        println!(
            "{}",
            serde_json::json!({
                "guide": dir.join("index.html"),
                "pages": written.pages.len(),
                "lessons": lessons,
            })
        );
    } else {
        println!(
            "wrote the guide: {} pages under {}; open {}",
            written.pages.len(),
            dir.display(),
            dir.join("index.html").display()
        );
    }
    anyhow::ensure!(
        failed.is_empty(),
        "the guide was written, but these lessons failed on this renderer: {}",
        failed.join(", ")
    );
    Ok(())
}
