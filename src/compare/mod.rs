//! `classic-gpgpu compare`: the `results.json` of several machines side by side, one page.
//!
//! Each of the papers' claims is a row; the published hardware and each machine are columns
//! (the verdict, what was measured, the machine's load). Results are put side by side only
//! when they can be: runs at different sizes (`--quick` against the papers' sizes) or that
//! judged different versions of the claims are refused with the reason, never mixed; the
//! README's text (`--markdown`) puts each such group in a table of its own, under a heading
//! that says which it is ([`markdown::grouped`]).
//! The headline ratios are plotted across the machines, and the README's "What a run shows"
//! table is printed from the kept results (`compare --markdown`).

mod folder;
pub mod headline;
pub mod markdown;
mod page;
mod plot;
pub mod run;

pub use run::Run;

use crate::report::published::Published;
use anyhow::bail;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Everything the page shows, as `comparison.json` holds it.
#[derive(Clone, Debug, Serialize)]
pub struct Comparison {
    /// Whether the runs are `--quick` ones (all of them are, or none).
    pub quick: bool,
    /// The version of the claims every run judged.
    pub claims_version: String,
    /// The machines, in the order given: renderer, GL version, CPU, date, commit, command.
    pub machines: Vec<Run>,
    /// Every claim of every run, in report order.
    pub claims: Vec<ClaimRow>,
    /// The headline figures, one row each (the README's table).
    pub headlines: Vec<headline::Row>,
    /// Per machine, the then-and-now ratios (compute over classic frame time) per section.
    pub then_and_now: Vec<headline::ThenAndNowRow>,
}

/// One claim across the machines.
#[derive(Clone, Debug, Serialize)]
pub struct ClaimRow {
    pub section: String,
    pub claim: String,
    /// What the paper states, and on what hardware.
    pub paper: String,
    pub hardware: String,
    /// One per machine, in the order of [`Comparison::machines`].
    pub cells: Vec<Cell>,
}

/// One claim on one machine.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// `None`: not judged there, or not run there (`ran` says which).
    pub holds: Option<bool>,
    pub ran: bool,
    pub measured: String,
    /// The section's load at its start and end.
    pub load: String,
}

impl Cell {
    /// "holds", "does not hold", "not judged here" or "not run".
    pub fn verdict(&self) -> &'static str {
        match (self.ran, self.holds) {
            (false, _) => "not run",
            (true, Some(true)) => "holds",
            (true, Some(false)) => "does not hold",
            (true, None) => "not judged here",
        }
    }
}

/// Reads every file and checks that they can be compared; the error names the files and why
/// they cannot.
pub fn read(paths: &[PathBuf]) -> anyhow::Result<Vec<Run>> {
    if paths.is_empty() {
        bail!("compare: give at least one results.json (the file `reproduce` writes)");
    }
    let mut runs = paths
        .iter()
        .map(|p| Run::read(p))
        .collect::<anyhow::Result<Vec<Run>>>()?;
    comparable(&runs)?;
    run::number_shared_labels(&mut runs);
    Ok(runs)
}

/// Refuses runs that cannot share a row: different sizes, or different versions of the
/// claims (which includes a run that does not record its version).
pub fn comparable(runs: &[Run]) -> anyhow::Result<()> {
    let files = |pick: &dyn Fn(&Run) -> bool| {
        runs.iter()
            .filter(|r| pick(r))
            .map(|r| r.file.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    if runs.iter().any(|r| r.quick) && runs.iter().any(|r| !r.quick) {
        bail!(
            "compare: the results were made at different sizes, so their figures are not \
             comparable: --quick (small sizes) in {}; the papers' sizes in {}. Compare quick \
             runs with quick runs and full runs with full ones",
            files(&|r| r.quick),
            files(&|r| !r.quick)
        );
    }
    if let Some(old) = runs.iter().find(|r| r.claims_version.is_empty()) {
        bail!(
            "compare: {} does not record which version of the claims it judged (a results.json \
             from before `compare`, commit {}); run `classic-gpgpu reproduce` again with this \
             version",
            old.file,
            old.short_commit()
        );
    }
    let first = &runs[0];
    if let Some(other) = runs
        .iter()
        .find(|r| r.claims_version != first.claims_version)
    {
        let mut versions: Vec<String> = Vec::new();
        for r in runs {
            let line = format!(
                "version {} (commit {}) in {}",
                r.claims_version,
                r.short_commit(),
                files(&|x| x.claims_version == r.claims_version)
            );
            if !versions.contains(&line) {
                versions.push(line);
            }
        }
        bail!(
            "compare: {} and {} judged different versions of the claims (the report's code or \
             the published tables differ between their builds), so a row would mix two \
             claims: {}. Compare results made by builds with the same claims version",
            first.file,
            other.file,
            versions.join("; ")
        );
    }
    Ok(())
}

/// The comparison of runs that [`read`] accepted.
pub fn compare(runs: Vec<Run>) -> anyhow::Result<Comparison> {
    let published = Published::get()?;
    let mut claims: Vec<ClaimRow> = Vec::new();
    for run in &runs {
        for section in &run.sections {
            for claim in &section.claims {
                let known = claims
                    .iter()
                    .any(|c| c.section == section.id && c.claim == claim.claim);
                if !known {
                    claims.push(ClaimRow {
                        section: section.id.clone(),
                        claim: claim.claim.clone(),
                        paper: claim.paper.clone(),
                        hardware: hardware(published, &section.id),
                        cells: runs
                            .iter()
                            .map(|r| cell(r, &section.id, &claim.claim))
                            .collect(),
                    });
                }
            }
        }
    }
    Ok(Comparison {
        quick: runs.first().is_some_and(|r| r.quick),
        claims_version: runs
            .first()
            .map(|r| r.claims_version.clone())
            .unwrap_or_default(),
        claims,
        headlines: headline::rows(&runs),
        then_and_now: headline::then_and_now(&runs),
        machines: runs,
    })
}

/// Claim `claim` of section `id` on `run`.
fn cell(run: &Run, id: &str, claim: &str) -> Cell {
    let section = run.section(id);
    match section.and_then(|s| s.claims.iter().find(|c| c.claim == claim)) {
        Some(c) => Cell {
            holds: c.holds,
            ran: true,
            measured: c.measured.clone(),
            load: section.map(run::section_load).unwrap_or_default(),
        },
        None => Cell {
            holds: None,
            ran: false,
            measured: if section.is_some() {
                "the section ran without this claim".into()
            } else {
                format!("section {id} was not run")
            },
            load: String::new(),
        },
    }
}

/// The hardware of the paper a section reproduces ("the tutorial" for the others).
pub fn hardware(published: &Published, section: &str) -> String {
    match section {
        "paper1" => published.paper1.hardware.clone(),
        "paper2" => published.paper2.hardware.clone(),
        "paper3" => published.paper3.table1.hardware.clone(),
        "paper4" => published.paper4.hardware.clone(),
        _ => "the tutorial's (no hardware stated)".into(),
    }
}

/// The options of `compare`.
#[derive(Clone, Debug, clap::Args)]
pub struct CompareArgs {
    /// The results.json of each machine (as `reproduce` writes them), one column each.
    #[arg(required = true, value_name = "RESULTS_JSON")]
    pub results: Vec<PathBuf>,
    /// Where the page goes (index.html, comparison.json, the figures); not with --markdown,
    /// which writes no page.
    #[arg(long, default_value = "compare", conflicts_with = "markdown")]
    pub out: PathBuf,
    /// Write into a folder that holds other files (they are never replaced or removed).
    #[arg(long, conflicts_with = "markdown")]
    pub force: bool,
    /// Print the README's "What a run shows" table (and the then-and-now lines) instead of
    /// writing the page; runs of other sizes or claims versions get a table each.
    #[arg(long)]
    pub markdown: bool,
}

/// The page's own files besides the figures ([`plot::FILES`]).
const PAGE: &str = "index.html";
const JSON: &str = "comparison.json";

/// Writes the page into `out` (index.html, comparison.json, the figures), after checking the
/// folder: it must be the page's own, or empty, or `force` must allow the user's files there
/// (which are never replaced). `inputs` are never written over.
pub fn write_page(
    comparison: &Comparison,
    out: &Path,
    inputs: &[PathBuf],
    force: bool,
) -> anyhow::Result<()> {
    let mut names = vec![PAGE, JSON];
    names.extend(plot::FILES);
    folder::check(out, inputs, &names, force)?;
    let figures = plot::figures(comparison)?;
    let mut files = vec![
        (
            PAGE.to_string(),
            page::page(comparison, &figures).into_bytes(),
        ),
        (
            JSON.to_string(),
            serde_json::to_string_pretty(comparison)?.into_bytes(),
        ),
    ];
    for figure in figures {
        files.push((figure.file, figure.png));
    }
    folder::write(out, &files)
}
