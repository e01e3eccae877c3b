//! The `classic-gpgpu` command line: `info`, each paper's commands, and `reproduce`.

#![deny(unsafe_code)]

use anyhow::Context as _;
use clap::{CommandFactory as _, FromArgMatches as _, Parser, Subcommand};
use classic_gpgpu::gl::{self, Renderer};
use classic_gpgpu::report::{self, BenchArgs, NoOptions};
use std::process::ExitCode;

mod cli;

/// The classic GPGPU papers of a 2007 tutorial, reproduced on a headless OpenGL context.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    /// Which platform provides OpenGL (default: the CLASSIC_GPGPU_RENDERER variable, else auto:
    /// EGL device, then EGL surfaceless, then OSMesa).
    #[arg(long, global = true, value_parser = renderer_parser())]
    renderer: Option<Renderer>,
    /// Print one JSON object instead of text.
    #[arg(long, global = true)]
    json: bool,
    /// Load each shader from DIR/<its path> where DIR has it (e.g. after `glsl export DIR`),
    /// the compiled-in copy otherwise; `view` reloads them when they are saved.
    #[arg(long, global = true, value_name = "DIR")]
    glsl_dir: Option<std::path::PathBuf>,
    /// Record every GL call the command makes, in order with its arguments, grouped by pass,
    /// and print the calls when it ends; `--trace=FILE` writes them to FILE (a new file)
    /// instead. The file is given after `=`, so that `--trace info` and `learn --trace 1` trace
    /// `info` and lesson 1. A debugging aid: a long run makes a long trace. Refused by the
    /// commands that make no GL call.
    #[arg(
        long,
        global = true,
        value_name = "FILE",
        num_args = 0..=1,
        require_equals = true,
        default_missing_value = "-"
    )]
    trace: Option<std::path::PathBuf>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The renderer in use, why it was chosen, and the limits the papers depend on.
    Info,
    /// Paper 1: every intersecting triangle pair of two meshes, with streaming AABBs.
    Collide(cli::collide::CollideArgs),
    /// Paper 1: a deforming scene of Table III, frame by frame.
    CollideScene(cli::collide::SceneArgs),
    /// Paper 1: Tables III-IV and Fig. 7, 10-12 against SOLID and CULLIDE.
    CollideBench(BenchArgs<report::paper1::Paper1Args>),
    /// Paper 4: mass properties by depth peeling and reduction, beside Mirtich's method.
    Mass(cli::mass::MassArgs),
    /// Paper 4: rigid bodies floating on still water (section 5).
    Buoyancy(cli::mass::BuoyancyArgs),
    /// Paper 4: Table 1, Fig. 4 and Fig. 5 regenerated, and the buoyancy steps per second.
    MassBench(BenchArgs<NoOptions>),
    /// Check an OBJ file, or write one of the papers' test objects.
    #[command(subcommand)]
    Mesh(cli::mesh::MeshCommand),
    /// Regenerate every table and figure of the papers into a report beside the published
    /// numbers (report/index.html, report/results.json, PNG figures).
    Reproduce(report::reproduce::ReproduceArgs),
    /// Paper 2: render a skinned crowd off-screen (two-pass or vertex-shader skinning).
    Crowd(cli::crowd::CrowdArgs),
    /// Paper 2: Table 1 and the LOD runs beside the paper's numbers.
    CrowdBench(BenchArgs<NoOptions>),
    /// Paper 3 (Oh & Jung 2004): a multilayer perceptron as render passes, text detection.
    Mlp(cli::mlp::MlpArgs),
    /// Paper 3's Table 1 (texture creation, matrix product, sigmoid; GPU vs CPU) with GFLOP/s.
    MlpBench(BenchArgs<NoOptions>),
    /// The tutorial's lecture 1: self-collision, pairwise triangle tests, Voronoi diagrams,
    /// distance fields, swept volumes, penetration depth and avatar CCD on the GPU.
    #[command(subcommand)]
    Lecture1(cli::lecture1::Lecture1Command),
    /// The tutorial's lecture 3: image pyramids, pyramidal displacement mapping, octrees,
    /// quadtree search of a light hierarchy, and the lecture's texture and debugging techniques.
    #[command(subcommand)]
    Lecture3(cli::lecture3::Lecture3Command),
    /// Lecture 3's section: every technique against its CPU reference, tables and figures.
    Lecture3Bench(BenchArgs<report::lecture3::Lecture3Options>),
    /// Does this renderer do classic GPGPU right? A small workload of every paper and every GL
    /// feature they use, each against its CPU reference: one pass/fail line per check, a
    /// non-zero exit if any fails.
    Selftest(cli::selftest::SelftestArgs),
    /// Watch a technique live in a window, its intermediate buffers one key away (or draw the
    /// same frame headless with --headless).
    View(cli::view::ViewArgs),
    /// The shader files: list them, or export them to edit and run with --glsl-dir.
    #[command(subcommand)]
    Glsl(cli::glsl::GlslCommand),
    /// The inputs the project ships (the bunny, text.png, the XOR network, example files):
    /// list them, or export them to use from any folder.
    #[command(subcommand)]
    Assets(cli::assets::AssetsCommand),
    /// The lessons of the basic GPGPU approach, in order, each checked against the CPU.
    Learn(cli::learn::LearnArgs),
    /// Several runs' results.json side by side: every claim a row (a row per version of it),
    /// each run a column (a page in --out), the README's table (--markdown), or one run
    /// against a baseline: the regression gate (--baseline, exit 1 on a regression).
    Compare(classic_gpgpu::compare::CompareArgs),
    /// Every claim this build can make: its id, its versions (at the papers' sizes and at
    /// --quick sizes) and what each is a hash of; or --stamp a run from before them.
    Claims(cli::claims::ClaimsArgs),
    /// Every command's options as JSON: name, kind of value, role of a path, help (for the
    /// tests that hold every option to the rules of values and paths).
    #[command(hide = true)]
    Options,
}

impl Command {
    /// Why `--json` does nothing for this command, when it does nothing.
    fn prints_no_json(&self) -> Option<&'static str> {
        match self {
            Command::View(_) => {
                Some("view draws frames (in a window, or into --screenshot) and prints no results")
            }
            Command::Compare(a) if a.markdown => Some(
                "--markdown prints a Markdown table; the comparison as JSON is what compare \
                 prints without --markdown (and writes as comparison.json)",
            ),
            _ => None,
        }
    }

    /// Why this command makes no GL call (so `--trace` would record nothing), when it makes none.
    fn makes_no_gl_call(&self) -> Option<&'static str> {
        match self {
            Command::Mesh(_) => Some("mesh reads and writes OBJ files on the CPU"),
            Command::Glsl(_) => Some("glsl lists and writes the shader files"),
            Command::Compare(_) => Some("compare reads results.json files"),
            Command::Claims(_) => Some("claims lists the claims and stamps results.json files"),
            Command::Assets(_) => Some("assets lists and writes the files the project ships"),
            Command::Options => Some("options lists the command line's options"),
            Command::Mlp(a) if !cli::mlp::uses_gl(a) => {
                Some("this mlp command runs on the CPU (mlp train, or --cpu)")
            }
            Command::Learn(a) if a.list || a.hint.is_some() || a.solution => {
                Some("learn --list, --hint and --solution print text")
            }
            _ => None,
        }
    }
}

/// `--renderer`: the names and help lines `gl::Renderer` gives, parsed by its `FromStr`.
fn renderer_parser() -> impl clap::builder::TypedValueParser<Value = Renderer> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
    let values = Renderer::ALL.map(|r| PossibleValue::new(r.name()).help(r.description()));
    PossibleValuesParser::new(values).map(|name| name.parse().expect("one of the possible values"))
}

/// What every command gets.
pub struct Global {
    pub renderer: Option<Renderer>,
    pub json: bool,
    /// `--glsl-dir`: set on every context made for a command.
    pub glsl_dir: Option<std::path::PathBuf>,
    /// `--trace` or `--trace=FILE`: "-" (a bare `--trace`) prints the trace.
    pub trace: Option<std::path::PathBuf>,
    /// The contexts made while tracing, whose calls are written when the command ends.
    traced: std::cell::RefCell<Vec<gl::Context>>,
}

impl Global {
    /// The GL context chosen by `--renderer`, else by the environment.
    pub fn context(&self) -> anyhow::Result<gl::Context> {
        let ctx = match self.renderer {
            Some(r) => gl::Context::new(r),
            None => gl::Context::from_env(),
        };
        let ctx = ctx.context("creating the OpenGL context")?;
        ctx.set_glsl_dir(self.glsl_dir.clone());
        if self.trace.is_some() {
            ctx.trace_start();
            self.traced.borrow_mut().push(ctx.clone());
        }
        Ok(ctx)
    }

    /// `--trace`: the calls of every context the command made, printed or written to FILE.
    fn write_trace(&self) -> anyhow::Result<()> {
        let Some(out) = &self.trace else {
            return Ok(());
        };
        if self.traced.borrow().is_empty() {
            anyhow::bail!(
                "--trace: this run made no GL call, so there is no trace to {}",
                if out.as_os_str() == "-" {
                    "print".to_string()
                } else {
                    format!("write ({} was not written)", out.display())
                }
            );
        }
        let mut lines = Vec::new();
        for ctx in self.traced.borrow().iter() {
            lines.extend(gl::trace::lines(&ctx.trace_stop()));
        }
        if out.as_os_str() == "-" {
            for line in &lines {
                // Beside --json's object on stdout, the trace goes to stderr.
                if self.json {
                    eprintln!("{line}");
                } else {
                    println!("{line}");
                }
            }
            return Ok(());
        }
        let text = lines.join("\n") + "\n";
        classic_gpgpu::files::write_bytes(out, text.as_bytes())
            .with_context(|| format!("--trace {}: writing the trace", out.display()))
    }

    /// A `*-bench` command: section `P`, figures in `--out` (default `default_out`).
    fn bench<P: report::Paper>(
        &self,
        args: &BenchArgs<P::Options>,
        default_out: &str,
    ) -> anyhow::Result<()> {
        report::bench_command::<P>(&self.context()?, args, default_out, self.json)
    }
}

/// `classic-gpgpu ... | head` closes stdout early: that is the reader's choice, not an error,
/// so end quietly instead of reporting a panic from `println!`.
fn quiet_on_broken_pipe() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.contains("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(0);
        }
        default(info);
    }));
}

/// The command line as clap knows it, every numeric option ready for a value that starts with
/// `-` ([`classic_gpgpu::values::prepare`]).
fn command_line() -> clap::Command {
    classic_gpgpu::values::prepare(Cli::command())
}

/// Parses the command line; a refusal by clap is printed with a note when a bare `--trace`
/// may have changed how the words after it were read.
fn parse() -> (Cli, clap::ArgMatches) {
    let matches = command_line().try_get_matches().unwrap_or_else(|e| {
        if e.use_stderr() {
            let _ = e.print();
            if let Some(note) = trace_note(&e.to_string()) {
                eprintln!("{note}");
            }
            std::process::exit(e.exit_code());
        }
        e.exit()
    });
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    (cli, matches)
}

/// A note for an error that names the word after a bare `--trace` (`--trace out.txt info`):
/// the trace's file is given as `--trace=FILE`, so that word was read as an argument.
fn trace_note(error: &str) -> Option<String> {
    let args: Vec<String> = std::env::args().collect();
    let at = args.iter().position(|a| a == "--trace")?;
    let word = args.get(at + 1).filter(|w| !w.starts_with('-'))?;
    error.contains(word.as_str()).then(|| {
        format!(
            "note: a bare --trace prints the calls and takes no file, so '{word}' after it was \
             read as an argument of the command; to write the trace to {word}, give \
             --trace={word}"
        )
    })
}

/// The refusals that hold for any command, before any work: `--json` where the command prints
/// no JSON, `--trace` where it makes no GL call, and the rule of every path written.
fn check_options(cli: &Cli, matches: &clap::ArgMatches) -> anyhow::Result<()> {
    if let (true, Some(why)) = (cli.json, cli.command.prints_no_json()) {
        anyhow::bail!("--json: {why}, so there is nothing to print as JSON; leave out --json");
    }
    if let Some(why) = cli.command.makes_no_gl_call() {
        if let Some(file) = &cli.trace {
            anyhow::bail!(
                "--trace{}: {why}, so there would be no GL call to record; leave out --trace",
                if file.as_os_str() == "-" {
                    String::new()
                } else {
                    format!("={}", file.display())
                }
            );
        }
        if let Some(dir) = &cli.glsl_dir {
            anyhow::bail!(
                "--glsl-dir {}: {why}, so no shader would be read from it; leave out --glsl-dir",
                dir.display()
            );
        }
        if let Some(renderer) = cli.renderer {
            anyhow::bail!(
                "--renderer {}: {why}, so no renderer would be used; leave out --renderer",
                renderer.name()
            );
        }
    }
    check_glsl_dir(cli.glsl_dir.as_deref())?;
    check_trace_file(cli.trace.as_deref())?;
    cli::paths::check(&command_line(), matches)
}

fn main() -> ExitCode {
    // Before any thread: it may set a variable of the environment.
    gl::quiet_display_probes();
    quiet_on_broken_pipe();
    let (cli, matches) = parse();
    if let Err(e) = check_options(&cli, &matches) {
        eprintln!("error: {}", classic_gpgpu::files::error_text(&e));
        return ExitCode::FAILURE;
    }
    let global = Global {
        renderer: cli.renderer,
        json: cli.json,
        glsl_dir: cli.glsl_dir,
        trace: cli.trace,
        traced: Default::default(),
    };
    let json = global.json;
    let result = match cli.command {
        Command::Info => info(&global),
        Command::Collide(a) => global
            .context()
            .and_then(|ctx| cli::collide::run_collide(&a, &ctx, json)),
        Command::CollideScene(a) => global
            .context()
            .and_then(|ctx| cli::collide::run_scene(&a, &ctx, json)),
        Command::CollideBench(a) => global.bench::<report::paper1::Paper1>(&a, "collide-bench"),
        Command::Mass(a) => global
            .context()
            .and_then(|c| cli::mass::run_mass(&a, &c, json)),
        Command::Buoyancy(a) => global
            .context()
            .and_then(|c| cli::mass::run_buoyancy(&a, &c, json)),
        Command::MassBench(a) => global.bench::<report::paper4::Paper4>(&a, "mass-bench"),
        Command::Mesh(command) => cli::mesh::run(&command, json),
        Command::Reproduce(args) => reproduce(&global, &args),
        Command::Crowd(a) => global.context().and_then(|c| cli::crowd::run(&a, &c, json)),
        Command::CrowdBench(a) => global.bench::<report::paper2::Paper2>(&a, "crowd-bench"),
        Command::Mlp(args) => cli::mlp::run(args, json, || global.context()),
        Command::MlpBench(a) => global.bench::<report::paper3::Paper3>(&a, "mlp-bench"),
        Command::Lecture1(c) => global
            .context()
            .and_then(|ctx| cli::lecture1::run(&c, &ctx, json)),
        Command::Lecture3(c) => global
            .context()
            .and_then(|ctx| cli::lecture3::run(&c, &ctx, json)),
        Command::Lecture3Bench(a) => {
            global.bench::<report::lecture3::Lecture3>(&a, "lecture3-bench")
        }
        Command::Selftest(a) => global
            .context()
            .and_then(|ctx| cli::selftest::run(&a, &ctx, json)),
        Command::View(a) => cli::view::run(&a, global.glsl_dir.clone(), || global.context()),
        Command::Glsl(c) => cli::glsl::run(&c, json),
        Command::Assets(c) => cli::assets::run(&c, json),
        Command::Learn(a) => cli::learn::run(&a, json, || global.context()),
        Command::Compare(a) => cli::compare::run(&a, json),
        Command::Claims(a) => cli::claims::run(&a, json),
        Command::Options => cli::options::run(&command_line()),
    };
    // The trace is written whether the command succeeded or not: a failure is when it helps.
    let result = match (result, global.write_trace()) {
        (Err(e), _) | (Ok(()), Err(e)) => Err(e),
        (Ok(()), Ok(())) => Ok(()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let text = classic_gpgpu::files::error_text(&e);
            eprintln!("error: {text}");
            if let Some(note) = trace_note(&text) {
                eprintln!("{note}");
            }
            ExitCode::FAILURE
        }
    }
}

/// `--trace=FILE` writes a new file: an existing file or a folder is refused before any work.
fn check_trace_file(file: Option<&std::path::Path>) -> anyhow::Result<()> {
    match file {
        Some(f) if f.as_os_str() != "-" && f.exists() => anyhow::bail!(
            "--trace={}: {}; a trace is written to a new file, so name one that does not exist",
            f.display(),
            if f.is_dir() { "is a folder" } else { "exists" }
        ),
        _ => Ok(()),
    }
}

/// `--glsl-dir DIR` must name an existing folder (a typo would otherwise run every compiled-in
/// shader without a word).
fn check_glsl_dir(dir: Option<&std::path::Path>) -> anyhow::Result<()> {
    match dir {
        Some(dir) if !dir.is_dir() => anyhow::bail!(
            "--glsl-dir {}: {}; give the folder that `classic-gpgpu glsl export` wrote",
            dir.display(),
            if dir.exists() {
                "is a file, not a folder"
            } else {
                "no such folder"
            }
        ),
        Some(dir) => {
            // An entry that is there but is not a shader file is refused before any work.
            for s in classic_gpgpu::gl::shaders::ALL {
                let path = dir.join(s.name);
                if let Err(e) = classic_gpgpu::gl::shaders::in_glsl_dir(&path) {
                    anyhow::bail!("--glsl-dir: {}: {e}", path.display());
                }
            }
            let has_any = classic_gpgpu::gl::shaders::ALL
                .iter()
                .any(|s| dir.join(s.name).is_file());
            if !has_any {
                eprintln!(
                    "note: --glsl-dir {} has none of the shader files (they are read from \
                     {}/glsl/... and {}/cg_ports/...), so every shader is the compiled-in one",
                    dir.display(),
                    dir.display(),
                    dir.display()
                );
            }
            Ok(())
        }
        None => Ok(()),
    }
}

fn info(global: &Global) -> anyhow::Result<()> {
    let ctx = global.context()?;
    let info = ctx.info();
    if global.json {
        println!("{}", serde_json::to_string_pretty(info)?);
        return Ok(());
    }
    let l = &info.limits;
    println!("platform        {} ({})", info.platform, info.why);
    println!("vendor          {}", info.vendor);
    println!("renderer        {}", info.renderer);
    println!("version         {}", info.version);
    println!("GLSL            {}", info.glsl_version);
    println!(
        "max texture     {} x {}",
        l.max_texture_size, l.max_texture_size
    );
    println!(
        "max viewport    {} x {}",
        l.max_viewport_dims[0], l.max_viewport_dims[1]
    );
    println!(
        "draw buffers    {} (colour attachments {})",
        l.max_draw_buffers, l.max_color_attachments
    );
    println!("stencil bits    {}", l.stencil_bits);
    println!(
        "query bits      samples passed {}, time elapsed {}",
        l.samples_passed_counter_bits, l.time_elapsed_counter_bits
    );
    println!(
        "texture units   fragment {}, vertex {}",
        l.max_texture_image_units, l.max_vertex_texture_image_units
    );
    println!(
        "uniforms        vertex {}, fragment {} components",
        l.max_vertex_uniform_components, l.max_fragment_uniform_components
    );
    let facing = match ctx.fragment_facing()? {
        gl::FragmentFacing::FollowsWinding => "follows the winding",
        gl::FragmentFacing::Reversed => "the opposite of the winding",
        gl::FragmentFacing::Unusable => "unusable (the same for both windings)",
    };
    println!("gl_FrontFacing  {facing}");
    Ok(())
}

fn reproduce(global: &Global, args: &report::reproduce::ReproduceArgs) -> anyhow::Result<()> {
    let ctx = global.context()?;
    let report = report::reproduce::reproduce(&ctx, args, report::progress_bars(global.json))?;
    if global.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    for section in &report.sections {
        println!("{}", section.to_text());
    }
    for section in &report.sections {
        println!(
            "section {:<9} {:6.1} s wall, {:6.1} s CPU (all threads)",
            section.id, section.elapsed_s, section.cpu_s
        );
    }
    println!(
        "report written to {} ({:.0} s, renderer: {})",
        args.out.join("index.html").display(),
        report.elapsed_s,
        ctx.info().renderer_line()
    );
    Ok(())
}
