//! `classic-gpgpu reproduce`: every paper's benchmark, one report. The report is written into
//! a staging folder beside the target and swapped in only when every section succeeded, so a
//! failed run never leaves a half-written report where a good one was. The report folder is
//! only ever the program's own ([`crate::page::folder`]).

use super::{html, run_section, BenchOptions, Paper, Report, Section};
use crate::gl;
use crate::page::folder::{self, Owned};
use anyhow::{bail, Context as _};
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Names a section that fails on purpose (tests of the report's atomic replacement).
pub const FAIL_SECTION_ENV: &str = "CLASSIC_GPGPU_FAIL_SECTION";

/// A section of the report and the function that measures it.
pub struct Stage {
    pub id: &'static str,
    pub title: &'static str,
    /// The claims the section can make ([`Paper::CLAIMS`]).
    pub claims: &'static [super::ClaimDef],
    pub run: fn(&BenchOptions) -> anyhow::Result<Section>,
}

impl Stage {
    /// The stage of section `P`, run with its default options.
    pub fn of<P: Paper>() -> Stage {
        Stage {
            id: P::ID,
            title: P::TITLE,
            claims: P::CLAIMS,
            run: |opts| run_section::<P>(opts, &P::Options::default()),
        }
    }
}

/// Every stage, in report order. Each section adds its line here.
pub fn stages() -> Vec<Stage> {
    vec![
        Stage::of::<super::blocks::Blocks>(),
        Stage::of::<super::paper1::Paper1>(),
        Stage::of::<super::paper2::Paper2>(),
        Stage::of::<super::paper3::Paper3>(),
        Stage::of::<super::paper4::Paper4>(),
        Stage::of::<super::lecture1::Lecture1>(),
        Stage::of::<super::lecture3::Lecture3>(),
    ]
}

/// `--only`'s values: every stage's id, so that the help lists each section there is.
fn section_ids() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(stages().into_iter().map(|s| s.id))
}

/// The `reproduce` options.
#[derive(Clone, Debug, clap::Args)]
pub struct ReproduceArgs {
    /// Small sizes, for CI and smoke tests; the report says so.
    #[arg(long)]
    pub quick: bool,
    /// Only these sections (comma separated ids, from the list of sections the report has).
    #[arg(long, value_delimiter = ',', value_parser = section_ids())]
    pub only: Vec<String>,
    /// Where the report goes. With --only, the sections run are merged into the report
    /// already there (made on the same renderer at the same sizes).
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// With --only, replace a report that cannot be merged with (another renderer or other
    /// sizes) by one holding just the sections run now. Also: write the report into a folder
    /// that holds other files (they are never removed).
    #[arg(long)]
    pub force: bool,
    /// Time every repeated measurement exactly this many times [default: 3, and up to 5
    /// while the runs take under a second in all].
    #[arg(long, value_parser = crate::values::ranges::RUNS.of::<usize>())]
    pub runs: Option<usize>,
    /// Leave out the "period" block that papers 1 to 4 carry by default: each step of the
    /// paper's path run under the limits of the paper's own GPU (fits, the period's way, or
    /// refused with the limit named), and the results at that GPU's precision beside today's.
    #[arg(long, overrides_with = "period")]
    pub no_period: bool,
    /// Keep the period blocks (the default; the last of --period and --no-period wins).
    #[arg(long, overrides_with = "no_period")]
    pub period: bool,
}

/// Run the stages and write the report to `args.out`; returns the report.
pub fn reproduce(
    ctx: &gl::Context,
    args: &ReproduceArgs,
    progress: MultiProgress,
) -> anyhow::Result<Report> {
    super::period::set_requested(!args.no_period);
    if let Some(warning) = crate::timing::loaded_warning(crate::timing::Load::now()) {
        eprintln!("{warning}");
    }
    // A link to a folder: the report goes into that folder, and the link stays.
    let args = &ReproduceArgs {
        out: folder::resolve("--out", &args.out)?,
        ..args.clone()
    };
    let all = stages();
    let chosen = chosen_stages(&all, &args.only)?;
    folder::check_out(&args.out, args.force)?;
    let _lock = folder::Lock::take(&args.out)?;
    folder::recover(&args.out)?;
    // Checked again under the lock: a recovered report is a folder too.
    folder::check_out(&args.out, args.force)?;
    let kept = kept_sections(ctx, args, &chosen)?;
    let staging = staging_dir(&args.out)?;
    let mut owned = Owned::default();
    let result =
        run_stages(ctx, args, &chosen, &staging, progress, &mut owned).and_then(|mut report| {
            merge_kept(&mut report, kept, &all, &args.out, &staging, &mut owned)?;
            write_report(&report, &staging)?;
            owned.add("-", "results.json");
            owned.add("-", "index.html");
            // Last: a staging folder with its marker holds a finished report.
            owned.write(&staging)?;
            Ok(report)
        });
    match result {
        Ok(report) => {
            folder::install(&staging, &args.out, &owned)?;
            Ok(report)
        }
        Err(e) => {
            std::fs::remove_dir_all(&staging).ok();
            Err(e.context(format!(
                "the report was not written; {} is left as it was",
                args.out.display()
            )))
        }
    }
}

/// The stages `--only` names (all of them when it names none), in report order.
fn chosen_stages<'a>(all: &'a [Stage], only: &[String]) -> anyhow::Result<Vec<&'a Stage>> {
    for id in only {
        if !all.iter().any(|s| s.id == id) {
            let known: Vec<&str> = all.iter().map(|s| s.id).collect();
            bail!(
                "--only: unknown section '{id}' (known: {})",
                known.join(", ")
            );
        }
    }
    Ok(all
        .iter()
        .filter(|s| only.is_empty() || only.iter().any(|o| o == s.id))
        .collect())
}

/// With `--only`, the sections of the report already in `--out` that this run keeps: all
/// but those it runs again. The old report must come from the same renderer and sizes, or
/// `--force` must say to drop it.
fn kept_sections(
    ctx: &gl::Context,
    args: &ReproduceArgs,
    chosen: &[&Stage],
) -> anyhow::Result<Vec<Section>> {
    let path = args.out.join("results.json");
    if args.only.is_empty() || !path.is_file() {
        return Ok(Vec::new());
    }
    let refuse = |why: String| -> anyhow::Result<Vec<Section>> {
        if args.force {
            return Ok(Vec::new());
        }
        bail!(
            "--only: {why}; merging would mix them. Pass --force to replace the report with \
             only the sections run now, or choose another --out"
        )
    };
    let old: serde_json::Value = match std::fs::read_to_string(&path)
        .map_err(anyhow::Error::from)
        .and_then(|text| Ok(serde_json::from_str(&text)?))
    {
        Ok(old) => old,
        Err(e) => return refuse(format!("{} cannot be read ({e})", path.display())),
    };
    let renderer = ctx.info().renderer.as_str();
    let old_renderer = old["renderer"]["renderer"].as_str().unwrap_or("unknown");
    if old_renderer != renderer {
        return refuse(format!(
            "the report in {} was made on {old_renderer}, this run is on {renderer}",
            args.out.display()
        ));
    }
    if old["quick"].as_bool() != Some(args.quick) {
        let sizes = |quick| {
            if quick {
                "--quick sizes"
            } else {
                "the papers' sizes"
            }
        };
        return refuse(format!(
            "the report in {} has {}, this run {}",
            args.out.display(),
            sizes(!args.quick),
            sizes(args.quick)
        ));
    }
    // Sections from modified shaders (--glsl-dir) and from the shipped ones are not merged.
    let glsl_dir = ctx.glsl_dir().map(|d| d.display().to_string());
    if old["glsl_dir"].as_str().map(str::to_string) != glsl_dir {
        let shaders = |dir: Option<String>| match dir {
            Some(dir) => format!("the shaders of --glsl-dir {dir}"),
            None => "the compiled-in shaders".to_string(),
        };
        return refuse(format!(
            "the report in {} was made with {}, this run with {}",
            args.out.display(),
            shaders(old["glsl_dir"].as_str().map(str::to_string)),
            shaders(glsl_dir)
        ));
    }
    let runs = crate::timing::runs_policy(args.runs, args.quick);
    // A report made before `--runs` existed does not say how it was timed: it is refused
    // too, as another policy may have timed it.
    let old_runs = old["runs"].as_str();
    if old_runs != Some(runs.as_str()) {
        return refuse(format!(
            "in the report in {} {}; in this run {runs}",
            args.out.display(),
            old_runs.unwrap_or("the timing policy is not stated (a report from before --runs)")
        ));
    }
    let sections: Vec<Section> = match serde_json::from_value(old["sections"].clone()) {
        Ok(sections) => sections,
        Err(e) => return refuse(format!("{} has no readable sections ({e})", path.display())),
    };
    Ok(sections
        .into_iter()
        .filter(|s| !chosen.iter().any(|c| c.id == s.id))
        .collect())
}

/// Add the kept sections to the new report in report order, and copy every file they wrote
/// (as the old report's marker lists them; a report without one: their figures) from the old
/// report into the staging folder.
fn merge_kept(
    report: &mut Report,
    kept: Vec<Section>,
    all: &[Stage],
    out: &Path,
    staging: &Path,
    owned: &mut Owned,
) -> anyhow::Result<()> {
    let old = Owned::read(out)?.unwrap_or_else(|| Owned::from_results(out));
    for section in &kept {
        for file in old.files_of(&section.id) {
            let (from, to) = (out.join(file), staging.join(file));
            let bytes = std::fs::read(&from).with_context(|| {
                format!("keeping section {}: reading {}", section.id, from.display())
            })?;
            crate::files::write_bytes(&to, &bytes)?;
            owned.add(&section.id, file);
        }
    }
    report.sections.extend(kept);
    let rank = |id: &str| all.iter().position(|s| s.id == id).unwrap_or(all.len());
    report.sections.sort_by_key(|s| rank(&s.id));
    Ok(())
}

fn run_stages(
    ctx: &gl::Context,
    args: &ReproduceArgs,
    stages: &[&Stage],
    staging: &Path,
    progress: MultiProgress,
    owned: &mut Owned,
) -> anyhow::Result<Report> {
    let start = Instant::now();
    let overall = progress.add(ProgressBar::new(stages.len() as u64));
    overall.set_style(
        ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {msg}")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    overall.set_prefix("reproduce");
    let opts = BenchOptions {
        gl: ctx,
        quick: args.quick,
        out_dir: staging.to_path_buf(),
        progress: progress.clone(),
        runs: args.runs,
    };
    let mut sections = Vec::new();
    // Test hook: make one section fail, to check that a failed run keeps the old report.
    let fail = std::env::var(FAIL_SECTION_ENV).unwrap_or_default();
    for stage in stages {
        overall.set_message(stage.title);
        if fail == stage.id {
            bail!(
                "section {} failed on purpose ({FAIL_SECTION_ENV})",
                stage.id
            );
        }
        let before = folder::list_files(staging)?;
        let section = (stage.run)(&opts).with_context(|| format!("section {}", stage.id))?;
        for file in folder::list_files(staging)? {
            if before.binary_search(&file).is_err() {
                owned.add(stage.id, &file);
            }
        }
        for figure in &section.figures {
            if !staging.join(&figure.file).is_file() {
                bail!(
                    "section {} lists figure {} but did not write it",
                    stage.id,
                    figure.file
                );
            }
        }
        sections.push(section);
        overall.inc(1);
    }
    overall.finish_and_clear();
    Ok(Report {
        renderer: ctx.info().clone(),
        cpu: cpu_name(),
        date: utc_now(),
        commit: super::provenance::COMMIT.into(),
        command_line: super::provenance::command_line(),
        quick: args.quick,
        runs: crate::timing::runs_policy(args.runs, args.quick),
        elapsed_s: start.elapsed().as_secs_f64(),
        sections,
        glsl_dir: ctx.glsl_dir().map(|d| d.display().to_string()),
    })
}

fn write_report(report: &Report, staging: &Path) -> anyhow::Result<()> {
    crate::files::write_bytes(
        &staging.join("results.json"),
        serde_json::to_string_pretty(report)?.as_bytes(),
    )?;
    crate::files::write_bytes(&staging.join("index.html"), html::page(report).as_bytes())
}

/// A fresh staging folder beside `out` (same file system, so the swap is a rename).
fn staging_dir(out: &Path) -> anyhow::Result<PathBuf> {
    let staging = folder::staging_of(out, std::process::id())?;
    if staging.exists() {
        std::fs::remove_dir_all(&staging)?;
    }
    std::fs::create_dir_all(&staging).with_context(|| format!("creating {}", staging.display()))?;
    Ok(staging)
}

fn cpu_name() -> String {
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    format!("{model}, {cores} cores")
}

/// The current UTC time as `YYYY-MM-DD HH:MM:SS UTC`.
pub fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rest) = (secs / 86_400, secs % 86_400);
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02}:{:02} UTC",
        rest / 3600,
        rest % 3600 / 60,
        rest % 60
    )
}
