//! `learn`: the lessons of the basic approach (`classic_gpgpu::learn`). `learn --list` shows
//! them in order; `learn <id>` runs one, says what each pass does, checks it against the CPU,
//! writes each pass's buffer with `--png DIR`, and exits non-zero (with the exercise's hint)
//! when a check fails.

use anyhow::Context as _;
use classic_gpgpu::gl::Context;
use classic_gpgpu::learn::{self, LessonOptions, LessonRun};
use classic_gpgpu::page::folder::Staged;
use classic_gpgpu::values::Count;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct LearnArgs {
    /// The lesson to run: its id (e.g. texture-is-array) or its number.
    #[arg(required_unless_present_any = ["list", "guide"])]
    pub id: Option<String>,
    /// List the lessons: id, number, title, the paper steps, the shader files, the exercises
    /// (nothing runs, so --png and --exercise have nothing to apply to).
    #[arg(long, conflicts_with_all = ["id", "png", "exercise"])]
    pub list: bool,
    /// Write each pass's buffer into this folder as PNG (and .npy for float buffers). A
    /// folder holding files this lesson's --png did not write is refused without --force; a
    /// rerun replaces the pictures of the earlier one.
    #[arg(long, value_name = "DIR")]
    pub png: Option<PathBuf>,
    /// Run with exercise N's shader: the learner's file where the shader folder has it, else
    /// the shipped solution.
    #[arg(long, value_name = "N", value_parser = EXERCISE.of::<u32>())]
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
    /// Print hint N of the exercise (--exercise, else the lesson's first) and stop: 1 the idea,
    /// 2 the formula, 3 the line.
    #[arg(
        long,
        value_name = "N",
        value_parser = HINT.of::<u32>(),
        conflicts_with_all = ["list", "guide", "png", "solution"]
    )]
    pub hint: Option<u32>,
    /// Print the shipped solution of the exercise (--exercise, else the lesson's first): the
    /// shader file as the project ships it; then stop.
    #[arg(long, conflicts_with_all = ["list", "guide", "png"])]
    pub solution: bool,
    /// Time the lesson where speed is part of it (quad-is-loop: saxpy over sizes against the
    /// CPU; reduction, compute-reduction: the reduction ladder; readback-and-upload: whole,
    /// PBO and compacted readback): plain-text tables naming the renderer and the load.
    #[arg(long, conflicts_with_all = ["list", "guide", "png", "exercise", "hint", "solution"])]
    pub bench: bool,
    /// With --bench: this one size instead of the lesson's sweep (elements or values; the
    /// array's side for readback-and-upload).
    #[arg(long, value_name = "N", requires = "bench", value_parser = BENCH_SIZE.of::<u32>())]
    pub size: Option<u32>,
    /// With --bench: also write the results as JSON into FILE.json (an existing file only
    /// with --force).
    #[arg(long, value_name = "FILE.json", requires = "bench")]
    pub out: Option<PathBuf>,
}

/// `--exercise N`: a lesson's exercises are few (the lesson refuses a number it lacks).
const EXERCISE: Count = Count::new(
    "an exercise number",
    1,
    99,
    "a lesson has a few; `learn --list` names them",
);

/// `--hint N`: the idea, the formula, the line.
const HINT: Count = Count::new(
    "a hint number",
    1,
    3,
    "1 the idea, 2 the formula, 3 the line",
);

/// `--size N` of a lesson's bench: elements, values, or an array's side, each lesson checking
/// its own range; none times more than 2^24 values.
const BENCH_SIZE: Count = Count::new(
    "a size",
    1,
    1 << 24,
    "the largest a lesson's bench times; each lesson checks its own",
);

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
    if let Some(n) = args.hint {
        let e = exercise_of(lesson.info(), args.exercise)?;
        let what = ["the idea", "the formula", "the line"][n as usize - 1];
        if json {
            let hint = serde_json::json!({
                "lesson": lesson.info().id,
                "exercise": e.number,
                "shader": e.shader,
                "hint": n,
                "of": 3,
                "kind": what,
                "text": e.hints[n as usize - 1],
            });
            println!("{}", serde_json::to_string_pretty(&hint)?);
            return Ok(());
        }
        println!(
            "lesson {} exercise {} [{}], hint {n} of 3 ({what}):",
            lesson.info().id,
            e.number,
            e.shader
        );
        for line in classic_gpgpu::gl::picture::wrap(e.hints[n as usize - 1], 90) {
            println!("  {line}");
        }
        if n < 3 {
            println!(
                "next hint: classic-gpgpu learn {} --exercise {} --hint {}",
                lesson.info().id,
                e.number,
                n + 1
            );
        }
        return Ok(());
    }
    if args.solution {
        let e = exercise_of(lesson.info(), args.exercise)?;
        let shader = classic_gpgpu::gl::shaders::find(e.shader)
            .with_context(|| format!("the shipped shader {} is not compiled in", e.shader))?;
        if json {
            let solution = serde_json::json!({
                "lesson": lesson.info().id,
                "exercise": e.number,
                "shader": e.shader,
                "source": shader.source,
            });
            println!("{}", serde_json::to_string_pretty(&solution)?);
            return Ok(());
        }
        eprintln!(
            "the shipped solution of lesson {} exercise {}: {}",
            lesson.info().id,
            e.number,
            e.shader
        );
        print!("{}", shader.source);
        return Ok(());
    }
    if args.bench {
        return bench(lesson.info().id, args, json, context);
    }
    // The one rule of every folder writer (page::folder), checked before any work.
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
        print_run(&run, lesson.info(), args.png.as_ref());
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
    for line in feedback(&run, ctx.glsl_dir().is_some(), args.png.as_ref()) {
        message.push_str(&format!("\n{line}"));
    }
    anyhow::bail!(message)
}

/// `--size N` of a bench against memory before any work: N values, or for
/// readback-and-upload an N x N array (its copies on both sides, about 64 bytes a texel).
fn check_bench_memory(id: &str, n: u32) -> anyhow::Result<()> {
    let (units, what) = match id {
        "readback-and-upload" => (n as u64 * n as u64, "texels"),
        _ => (n as u64, "values"),
    };
    super::limits::check_memory(
        &format!("--size {n}"),
        units,
        64,
        what,
        "use a smaller --size",
    )
}

/// `learn <id> --bench [--size N] [--out FILE.json]`: the lesson's bench, its tables on
/// stdout (its JSON with --json), and the JSON into --out, refused before any work when the
/// lesson has no bench or the file exists without --force.
fn bench(
    id: &str,
    args: &LearnArgs,
    json: bool,
    context: impl FnOnce() -> anyhow::Result<Context>,
) -> anyhow::Result<()> {
    learn::bench::has_bench(id)?;
    if let Some(n) = args.size {
        check_bench_memory(id, n)?;
    }
    if let Some(out) = &args.out {
        classic_gpgpu::files::check_output("--out", out, &[], args.force, &["json"])?;
    }
    let ctx = context()?;
    let runs = classic_gpgpu::timing::Runs::PAPER;
    if let Some(load) = classic_gpgpu::timing::Load::now().filter(|l| l.is_loaded()) {
        eprintln!(
            "note: the machine is loaded ({}): the times below say as much about the other \
             work as about the lesson; run on a quiet machine to compare them",
            load.in_words()
        );
    }
    let result = learn::bench::run(&ctx, id, args.size, runs)?;
    let text = serde_json::to_string_pretty(&result)?;
    if json {
        println!("{text}");
    } else {
        print!("{}", result.table());
    }
    if let Some(out) = &args.out {
        classic_gpgpu::files::write_bytes(out, format!("{text}\n").as_bytes())?;
        if !json {
            println!("wrote {}", out.display());
        }
    }
    Ok(())
}

/// Exercise `number` of a lesson (its first without one), or an error naming those it has.
fn exercise_of(
    info: &'static learn::LessonInfo,
    number: Option<u32>,
) -> anyhow::Result<&'static learn::Exercise> {
    let opts = LessonOptions {
        exercise: number,
        ..LessonOptions::default()
    };
    match learn::chosen_exercise(info, &opts)? {
        Some(e) => Ok(e),
        None => info
            .exercises
            .first()
            .with_context(|| format!("lesson {} has no exercise", info.id)),
    }
}

/// What a failed run says after its verdict: where the first failed check made texel by
/// texel went wrong (the texel, both values), its difference picture, the viewer command that
/// probes it, and the first hint with the command for the next.
fn feedback(run: &LessonRun, glsl_dir: bool, png: Option<&PathBuf>) -> Vec<String> {
    let mut lines = Vec::new();
    let texelwise = run
        .checks
        .iter()
        .enumerate()
        .find(|(_, c)| !c.passed && c.wrong.is_some_and(|n| n > 0));
    if let Some((k, check)) = texelwise {
        lines.push(format!("{}:", check.what));
        lines.extend(check.where_wrong().into_iter().map(|l| format!("  {l}")));
        match (png, &check.difference_picture) {
            (Some(dir), Some(picture)) => lines.push(format!(
                "  the difference GPU - CPU, with its colour key: {}",
                dir.join(picture).display()
            )),
            _ => lines.push(format!(
                "  add --png DIR to get the difference GPU - CPU as a picture ({})",
                LessonRun::difference_file(k)
            )),
        }
        let buffer = check
            .buffer
            .map_or(String::new(), |b| format!(" --buffer {b}"));
        let first = check.first_wrong.first();
        lines.push(format!(
            "  look at it texel by texel: classic-gpgpu{} view learn {}{buffer} (point the mouse \
             at texel ({}, {}), or --probe X,Y in window pixels)",
            if glsl_dir { " --glsl-dir DIR" } else { "" },
            run.id,
            first.map_or(0, |w| w.x),
            first.map_or(0, |w| w.y),
        ));
    }
    if let (Some(hint), Some(n)) = (&run.hint, run.hint_exercise) {
        lines.push(format!("hint 1 of 3 (exercise {n}): {hint}"));
        lines.push(format!(
            "more: classic-gpgpu learn {} --exercise {n} --hint 2 (then --hint 3; --solution \
             prints the shipped shader)",
            run.id
        ));
    }
    lines
}

/// A lesson as `learn --list --json` gives it: its card, and its host exercise (null for none).
#[derive(serde::Serialize)]
struct Listed {
    #[serde(flatten)]
    info: &'static learn::LessonInfo,
    host_exercise: Option<learn::host::HostCard>,
}

/// `learn --list`.
fn list(json: bool) -> anyhow::Result<()> {
    let infos: Vec<_> = learn::all().iter().map(|l| l.info()).collect();
    if json {
        let listed: Vec<Listed> = infos
            .into_iter()
            .map(|info| Listed {
                info,
                host_exercise: learn::host::for_lesson(info.id).map(|h| h.card()),
            })
            .collect();
        println!("{}", serde_json::to_string_pretty(&listed)?);
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
        if let Some(host) = learn::host::for_lesson(info.id) {
            println!(
                "      host exercise  {}: {} (edit {}; the solution: {})",
                host.title,
                host.run_command(),
                host.template(),
                host.solution()
            );
        }
    }
    Ok(())
}

/// The run as text: the idea, each pass, each check (where a failed one went wrong), the
/// notes, the compute counterpart, and what comes next.
fn print_run(run: &LessonRun, info: &learn::LessonInfo, png: Option<&PathBuf>) {
    println!("lesson {}: {} ({})", run.id, run.title, run.renderer);
    if let Some(ran) = &run.exercise_ran {
        println!("  {ran}");
    }
    println!("  the idea:");
    for line in classic_gpgpu::gl::picture::wrap(info.idea, 88) {
        println!("    {line}");
    }
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
        if !check.passed {
            for line in check.where_wrong() {
                println!("       {line}");
            }
            if let (Some(dir), Some(picture)) = (png, &check.difference_picture) {
                println!(
                    "       wrote the difference GPU - CPU {}",
                    dir.join(picture).display()
                );
            }
        }
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
    if let Some(host) = learn::host::for_lesson(info.id) {
        println!(
            "your turn, on the host side ({}): {}, after editing {}",
            host.title,
            host.run_command(),
            host.template()
        );
    }
    for line in next_step(info) {
        println!("{line}");
    }
}

/// The lesson after `info` with the command that runs it; after the last, the paper to read.
fn next_step(info: &learn::LessonInfo) -> Vec<String> {
    let lessons = learn::all();
    let at = lessons.iter().position(|l| l.info().id == info.id);
    match at.and_then(|k| lessons.get(k + 1)) {
        Some(next) => vec![format!(
            "next: lesson {}, {}: classic-gpgpu learn {}",
            next.info().number,
            next.info().title,
            next.info().id
        )],
        None => classic_gpgpu::learn::guide::after_the_lessons(),
    }
}

/// `learn --guide DIR`: run every lesson and write the guide; fails when a lesson failed.
fn guide(dir: &std::path::Path, force: bool, json: bool, ctx: Context) -> anyhow::Result<()> {
    let written = classic_gpgpu::learn::guide::write_guide(&ctx, dir, force)?;
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
