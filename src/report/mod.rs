//! The reproduction report: each paper's benchmark at the paper's sizes (where a model or a
//! size differs, the section's fidelity table says by how much and why), beside the published
//! numbers (`assets/paper_tables.toml`), written as HTML, JSON and PNG.
//!
//! Every section has one shape, the [`Paper`] trait: `measure` runs the paper module at the
//! paper's sizes and fills a typed, serialisable results struct; `section` turns those results
//! into tables, claims, figures and the fidelity table. Each section lives in its own folder,
//! `report/<id>/`, with one file per table or figure. The `*-bench` commands
//! ([`bench_command`]) and `reproduce` both go through [`run_section`].
//!
//! Each claim has a stable id and a version of its own ([`versions`]): a hash of the code that
//! judges it, the published values and the sizes that measure it, so that results of other
//! builds compare claim by claim for as long as what decides a claim stays the same. A claim
//! also keeps the numbers its verdict rests on ([`evidence`]), for `compare --baseline`.
//!
//! This room holds the papers' reproduction and nothing else: the course's pages are in
//! [`crate::learn`], `compare` and `selftest` are rooms of their own, and the HTML, plots and
//! folder writer they all use are the page layer's ([`crate::page`]).

pub mod blocks;
pub mod checks;
pub mod claim_defs;
pub mod evidence;
mod html;
pub mod lecture1;
pub mod lecture3;
pub mod not_built;
pub mod paper1;
pub mod paper2;
pub mod paper3;
pub mod paper4;
pub mod period;
pub mod profile;
pub mod provenance;
pub mod published;
pub mod reproduce;
pub mod then_and_now;
pub mod timing_policy;
pub mod versions;

use crate::timing;
use anyhow::Context as _;
pub use evidence::Evidence;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
pub use versions::ClaimDef;

/// One section of the report: a paper (or a lecture, or the shared building blocks).
///
/// Adding a section is one type implementing this trait, one results struct, and one folder
/// under `report/` with a file per table or figure; [`reproduce::stages`] lists it.
pub trait Paper {
    /// The section's id, as `reproduce --only` takes it (`paper1`).
    const ID: &'static str;
    /// The section's heading in the report.
    const TITLE: &'static str;
    /// The paper whose GPU the section's period block runs under, if it has one
    /// (`gl::period::for_paper`).
    const PERIOD_PAPER: Option<u8> = None;
    /// Every claim the section can make, each with what decides it ([`versions`]).
    const CLAIMS: &'static [ClaimDef];
    /// What the section's `*-bench` command can change beyond [`BenchArgs`]; `reproduce` runs
    /// with the defaults.
    type Options: clap::Args + Default;
    /// Everything one run measures, machine readable: written as the section's `results`.
    type Results: Serialize;

    /// Run the paper's experiments.
    fn measure(opts: &BenchOptions, options: &Self::Options) -> anyhow::Result<Self::Results>;

    /// Tables, claims, figures (written under [`BenchOptions::out_dir`]) and fidelity rows from
    /// the results. `id`, `title` and `results` are filled in by [`run_section`].
    fn section(opts: &BenchOptions, results: &Self::Results) -> anyhow::Result<Section>;
}

/// A section without options of its own.
#[derive(Clone, Copy, Debug, Default, clap::Args)]
pub struct NoOptions {}

/// The arguments every `*-bench` command takes, and the section's own options.
#[derive(Clone, Debug, clap::Args)]
pub struct BenchArgs<O: clap::Args> {
    /// Small sizes, for CI and smoke tests; the output says so.
    #[arg(long)]
    pub quick: bool,
    /// Where the figures (PNG) go [default: the command's name, e.g. `collide-bench`]. A
    /// folder holding files the command did not write is refused without --force; a rerun
    /// replaces the files of the earlier one.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write the figures into an --out folder that holds other files (they are never
    /// removed or replaced).
    #[arg(long)]
    pub force: bool,
    /// Time every repeated measurement exactly this many times [default: 3, and up to 5
    /// while the runs take under a second in all].
    #[arg(long, value_parser = crate::values::ranges::RUNS.of::<usize>())]
    pub runs: Option<usize>,
    /// Leave out the section's period block (papers 1 to 4 carry one by default, as in
    /// `reproduce`): each step of the paper's path run under the limits of the paper's own
    /// GPU (the profile `--period` puts the paper's command under), and its results at that
    /// GPU's precision.
    #[arg(long, overrides_with = "period")]
    pub no_period: bool,
    /// Keep the section's period block (the default for papers 1 to 4; the last of --period
    /// and --no-period wins).
    #[arg(long, overrides_with = "no_period")]
    pub period: bool,
    #[command(flatten)]
    pub options: O,
}

/// Measure one section and build it, with its id, title and results filled in.
pub fn run_section<P: Paper>(opts: &BenchOptions, options: &P::Options) -> anyhow::Result<Section> {
    let (start, cpu_start) = (std::time::Instant::now(), process_cpu_s());
    let load_start = timing::Load::now();
    let results = P::measure(opts, options)?;
    let mut section = P::section(opts, &results)?;
    section.id = P::ID.into();
    section.title = P::TITLE.into();
    section.results = serde_json::to_value(&results).context("serialising the results")?;
    section.elapsed_s = start.elapsed().as_secs_f64();
    section.cpu_s = process_cpu_s() - cpu_start;
    for figure in &section.figures {
        let path = opts.out_dir.join(&figure.file);
        if let Some(drawn) = crate::gl::drawn::recorded(&path) {
            section.drawn.insert(figure.file.clone(), drawn);
        }
        if let Ok(size) = image::image_dimensions(&path) {
            section.figure_sizes.insert(figure.file.clone(), size);
        }
    }
    timing_policy::apply(&mut section, opts.gl.info().is_software());
    let escaped = timing_policy::problems(&section);
    anyhow::ensure!(
        escaped.is_empty(),
        "section {}: timing claims outside the report's policy: {}",
        P::ID,
        escaped.join("; ")
    );
    stamp_claims(P::ID, P::CLAIMS, opts.quick, &mut section.claims)?;
    section.commit = provenance::COMMIT.into();
    section.load_start = load_start;
    section.load_end = timing::Load::now();
    for row in &section.fidelity {
        anyhow::ensure!(
            !row.deviation.trim().is_empty(),
            "section {}: fidelity row '{}' has no deviation",
            P::ID,
            row.feature
        );
    }
    checks::verify(
        P::ID,
        &section.checks_listed,
        &section.checks_made,
        &section.paths,
        &section.fidelity,
    )?;
    Ok(section)
}

/// Gives each claim of section `id` its version, and keeps only its evidence that JSON can hold
/// (finite numbers); an error for a claim without an id, with an id the section does not list in
/// `defs`, or made twice.
fn stamp_claims(
    id: &str,
    defs: &[ClaimDef],
    quick: bool,
    claims: &mut [Claim],
) -> anyhow::Result<()> {
    for (i, claim) in claims.iter().enumerate() {
        anyhow::ensure!(
            claims[..i].iter().all(|c| c.id != claim.id),
            "section {id}: claim {} is made twice",
            claim.id
        );
    }
    for claim in claims {
        let def = defs.iter().find(|d| d.id == claim.id).ok_or_else(|| {
            anyhow::anyhow!(
                "section {id}: claim '{}' has id '{}', which is not among the section's CLAIMS",
                claim.claim,
                claim.id
            )
        })?;
        claim.version = versions::current(def, quick).map_err(anyhow::Error::msg)?;
        claim.evidence.retain(Evidence::is_finite);
    }
    Ok(())
}

/// What every paper's benchmark gets: the GL context, the size, where figures go.
pub struct BenchOptions<'a> {
    pub gl: &'a crate::gl::Context,
    /// Small sizes for CI and smoke tests; the report says so.
    pub quick: bool,
    /// Figures (PNG) are written here; [`Figure::file`] is relative to it.
    pub out_dir: PathBuf,
    /// Progress bars for long stages (hidden under `--json` or when not a terminal).
    pub progress: indicatif::MultiProgress,
    /// `--runs N`: time every repeated measurement exactly N times instead of
    /// [`timing::Runs::PAPER`].
    pub runs: Option<usize>,
}

impl BenchOptions<'_> {
    /// How often to repeat one timed measurement: `--runs` when given, else `quick_runs`
    /// exactly under `--quick`, else [`timing::Runs::PAPER`].
    pub fn runs(&self, quick_runs: usize) -> timing::Runs {
        match self.runs {
            Some(n) => timing::Runs::exactly(n),
            None => timing::Runs::paper_or(self.quick, quick_runs),
        }
    }
}

/// The whole report, as written to `results.json`.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub renderer: crate::gl::ContextInfo,
    pub cpu: String,
    pub date: String,
    /// The commit the binary was built from ([`provenance::COMMIT`]; sections kept from an
    /// earlier run with `--only` name their own).
    pub commit: String,
    /// The command that made the report, program name first.
    pub command_line: Vec<String>,
    pub quick: bool,
    /// How often each repeated timing ran ([`timing::runs_policy`]).
    pub runs: String,
    pub elapsed_s: f64,
    pub sections: Vec<Section>,
    /// `--glsl-dir`: the folder whose shader files replaced the compiled-in ones (null when
    /// none was given); with one, every result comes from modified shaders.
    pub glsl_dir: Option<String>,
}

/// One paper's part of the report.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Section {
    /// `paper1` .. `paper4`.
    pub id: String,
    pub title: String,
    /// A paragraph: what was run, on what sizes, and anything the reader must know
    /// (stand-in models, quick mode).
    pub summary: String,
    pub tables: Vec<Table>,
    pub claims: Vec<Claim>,
    pub figures: Vec<Figure>,
    /// Which GL feature the paper used and where this code uses it.
    pub fidelity: Vec<Fidelity>,
    /// The checks the summary names ([`checks::Check`] ids, from the section's list).
    #[serde(default)]
    pub checks_listed: Vec<String>,
    /// The checks the run made, recorded by the code that made them.
    #[serde(default)]
    pub checks_made: Vec<String>,
    /// The paths the run took (methods, formulations, scenes): each must be covered by a
    /// fidelity row ([`Fidelity::paths`]).
    #[serde(default)]
    pub paths: Vec<String>,
    /// Every measured number, machine readable.
    pub results: serde_json::Value,
    /// Wall time of the section's run, s (on a shared machine, see `cpu_s`).
    #[serde(default)]
    pub elapsed_s: f64,
    /// CPU time of the whole process (every thread: the software renderer's too) during the
    /// section's run, s: less sensitive than wall time to other work on the machine.
    #[serde(default)]
    pub cpu_s: f64,
    /// What each figure shows (axes, ticks, legend; panels and keys), by file, as the code
    /// that drew it recorded ([`crate::gl::drawn`]); filled by [`run_section`].
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub drawn: std::collections::BTreeMap<String, crate::gl::drawn::Drawn>,
    /// Each figure's size in pixels (width, height), by file, read from the PNG by
    /// [`run_section`]: the page shows a figure wider than itself shrunk, with a link.
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub figure_sizes: std::collections::BTreeMap<String, (u32, u32)>,
    /// The commit of the binary that ran the section ([`provenance::COMMIT`]; empty in a
    /// report from before it was recorded).
    #[serde(default)]
    pub commit: String,
    /// The machine's load (1-minute load average, `/proc/loadavg`) when the section started
    /// and when it ended; `None` where it cannot be read.
    #[serde(default)]
    pub load_start: Option<timing::Load>,
    #[serde(default)]
    pub load_end: Option<timing::Load>,
}

/// A table of measured numbers, usually with the paper's numbers in adjacent columns.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Table {
    pub caption: String,
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

/// A qualitative or quantitative claim of the paper, and whether it holds here.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Claim {
    /// `<section>.<name>`, stable across builds ([`ClaimDef::id`]; empty in a run from before
    /// claims had ids).
    #[serde(default)]
    pub id: String,
    /// A hash of what decides the claim ([`versions`]): two runs judged it the same way when
    /// the versions are equal. Empty in a run from before claims had versions.
    #[serde(default)]
    pub version: String,
    pub claim: String,
    pub paper: String,
    pub measured: String,
    /// `None` when the claim cannot be judged on this renderer.
    pub holds: Option<bool>,
    /// What decided the verdict (or, for "not judged", what would have).
    #[serde(default)]
    pub decided_by: Basis,
    /// The numbers the verdict rests on, for `compare --baseline`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub evidence: Vec<Evidence>,
}

/// What a verdict rests on, so that a reader knows whether the load of the machine, the
/// sizes of the run or neither could move it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Basis {
    /// A report from before the field existed.
    #[default]
    Unstated,
    /// Timings (judged only on a quiet machine, by the ends of their runs).
    Timing,
    /// Counts: pairs, pixels, draws, steps, bytes; the same on every run of the same sizes.
    Count,
    /// Errors against a reference, within a stated tolerance.
    Error,
    /// The size of the run: whether it reached the sizes the claim is about.
    RunSize,
}

impl Basis {
    /// "timing", "counts", ... ("" for a report that did not say).
    pub fn in_words(self) -> &'static str {
        match self {
            Basis::Unstated => "",
            Basis::Timing => "timing",
            Basis::Count => "counts",
            Basis::Error => "error",
            Basis::RunSize => "run size",
        }
    }
}

/// A PNG written under [`BenchOptions::out_dir`].
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Figure {
    pub file: String,
    pub caption: String,
}

/// One row of a paper's fidelity table.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Fidelity {
    pub feature: String,
    pub paper: String,
    /// Where this code does it (file path).
    pub code: String,
    /// What differs from the paper and why ("none" when the code does what the paper says).
    pub deviation: String,
    /// The run paths this row speaks for ([`Section::paths`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub paths: Vec<String>,
}

impl Fidelity {
    pub fn new(feature: &str, paper: &str, code: &str, deviation: &str) -> Fidelity {
        Fidelity {
            feature: feature.into(),
            paper: paper.into(),
            code: code.into(),
            deviation: deviation.into(),
            paths: Vec::new(),
        }
    }

    /// The same row, covering the run paths `paths`.
    pub fn covers(mut self, paths: &[&str]) -> Fidelity {
        self.paths.extend(paths.iter().map(|p| p.to_string()));
        self
    }
}

impl Claim {
    /// "holds", "does not hold" or "not judged here".
    pub fn verdict(&self) -> &'static str {
        match self.holds {
            Some(true) => "holds",
            Some(false) => "does not hold",
            None => "not judged here",
        }
    }
}

impl Section {
    /// Plain-text rendering: title, summary, tables, claims.
    pub fn to_text(&self) -> String {
        let mut out = format!("== {} ==\n{}\n\n", self.title, self.summary);
        for table in &self.tables {
            out.push_str(&table.to_text());
            out.push('\n');
        }
        for claim in &self.claims {
            out.push_str(&format!(
                "- {} [{}{}]\n  paper: {}\n  here:  {}\n",
                claim.claim,
                claim.verdict(),
                match claim.decided_by {
                    Basis::Unstated => String::new(),
                    basis => format!(", by {}", basis.in_words()),
                },
                claim.paper,
                claim.measured
            ));
        }
        out
    }
}

/// Progress bars on stderr, hidden for `--json` or when stderr is not a terminal.
pub fn progress_bars(json: bool) -> indicatif::MultiProgress {
    if json || !std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        indicatif::MultiProgress::with_draw_target(indicatif::ProgressDrawTarget::hidden())
    } else {
        indicatif::MultiProgress::new()
    }
}

/// A `*-bench` command: run one section with its figures in `--out`, then print its tables
/// and claims, or the whole section as JSON.
pub fn bench_command<P: Paper>(
    gl: &crate::gl::Context,
    args: &BenchArgs<P::Options>,
    default_out: &str,
    json: bool,
) -> anyhow::Result<()> {
    match (P::PERIOD_PAPER, args.no_period) {
        (None, true) => anyhow::bail!(
            "--no-period: section {} has no period block (only papers 1 to 4 do)",
            P::ID
        ),
        (None, false) if args.period => anyhow::bail!(
            "--period: section {} has no period block (only papers 1 to 4 do)",
            P::ID
        ),
        (Some(paper), false) => {
            let gpu = crate::gl::period::for_paper(paper);
            eprintln!(
                "period: the period block runs under the limits of the {} ({}), paper \
                 {paper}'s GPU (--no-period leaves it out)",
                gpu.name, gpu.chip
            );
        }
        _ => {}
    }
    period::set_requested(!args.no_period);
    if let Some(warning) = timing::loaded_warning(timing::Load::now()) {
        eprintln!("{warning}");
    }
    let out_dir = args.out.as_deref().unwrap_or(Path::new(default_out));
    // The one rule of every folder writer (page::folder): checked before any work.
    let folder = crate::page::folder::Staged::begin("--out", default_out, out_dir, args.force)?;
    let opts = BenchOptions {
        gl,
        quick: args.quick,
        out_dir: folder.path().to_path_buf(),
        progress: progress_bars(json),
        runs: args.runs,
    };
    let section = run_section::<P>(&opts, &args.options)?;
    folder.finish()?;
    if json {
        println!("{}", serde_json::to_string_pretty(&section)?);
    } else {
        println!("{}", section.to_text());
        for figure in &section.figures {
            println!(
                "figure: {} ({})",
                out_dir.join(&figure.file).display(),
                figure.caption
            );
        }
    }
    Ok(())
}

impl Table {
    /// Plain-text rendering for the `*-bench` commands.
    pub fn to_text(&self) -> String {
        let mut widths: Vec<usize> = self.header.iter().map(|h| h.chars().count()).collect();
        for row in &self.rows {
            for (i, cell) in row.iter().enumerate() {
                if i < widths.len() {
                    widths[i] = widths[i].max(cell.chars().count());
                } else {
                    widths.push(cell.chars().count());
                }
            }
        }
        let line = |cells: &[String]| {
            cells
                .iter()
                .enumerate()
                .map(|(i, c)| format!("{:>w$}", c, w = widths[i]))
                .collect::<Vec<_>>()
                .join("  ")
        };
        let mut out = format!("{}\n{}\n", self.caption, line(&self.header));
        for row in &self.rows {
            out.push_str(&line(row));
            out.push('\n');
        }
        out
    }
}

/// CPU time of this process so far (user + system, all threads), s, from `/proc/self/stat`
/// (in USER_HZ ticks, 100 per second on Linux); 0 where there is no such file.
pub fn process_cpu_s() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the command name (which may hold spaces) end with ')'.
    let Some(rest) = stat.rsplit_once(')').map(|(_, r)| r) else {
        return 0.0;
    };
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // utime and stime are fields 14 and 15 of the line: indices 11 and 12 after the name.
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (ticks(11) + ticks(12)) / 100.0
}
