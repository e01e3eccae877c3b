//! `classic-gpgpu compare`: the `results.json` of several machines and builds side by side, one
//! page, and the regression gate CI runs ([`gate`]).
//!
//! Each claim is a row (by its id), each run a column with the verdict, what was measured, and
//! the run's commit, date and load. Nothing is refused: runs at other sizes (`--quick` against
//! the papers' sizes) form a group of their own on the same page, with the reason; within a
//! group, runs compare on every claim whose version they share, and a claim whose version
//! differs between them is shown once per version, never two versions in one cell, and listed
//! as changed since the last commit that judged the older one. A run from before claims had
//! versions is its own version ("version not recorded"). The README's "What a run shows" table
//! is printed from the kept results (`compare --markdown`, [`markdown`]), the headline ratios
//! are plotted across the machines.

mod folder;
pub mod gate;
pub mod headline;
pub mod markdown;
mod page;
mod plot;
pub mod run;
pub mod stamp;

pub use run::Run;

use crate::report::published::Published;
use crate::report::{versions, Claim, Section};
use anyhow::bail;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Everything the page shows, as `comparison.json` holds it.
#[derive(Clone, Debug, Serialize)]
pub struct Comparison {
    /// The runs in groups of the same sizes, the papers' sizes first.
    pub groups: Vec<Group>,
}

/// Runs at the same sizes, compared claim by claim.
#[derive(Clone, Debug, Serialize)]
pub struct Group {
    /// Whether the runs are `--quick` ones.
    pub quick: bool,
    /// Why the group stands apart, where the page has several ("" for one group).
    pub reason: String,
    /// The machines, in the order given: renderer, GL version, CPU, date, commit, command.
    pub machines: Vec<Run>,
    /// Every claim of every run, in report order, a row per version of it.
    pub claims: Vec<ClaimRow>,
    /// The claims whose definition differs between the group's runs.
    pub changed: Vec<Changed>,
    /// The headline figures, one row each (the README's table).
    pub headlines: Vec<headline::Row>,
    /// Per machine, the then-and-now ratios (compute over classic frame time) per section.
    pub then_and_now: Vec<headline::ThenAndNowRow>,
}

/// One version of one claim across the machines.
#[derive(Clone, Debug, Serialize)]
pub struct ClaimRow {
    /// The claim's id (for a run from before ids, the id of the same claim in a later run of
    /// the group, else "").
    pub id: String,
    pub section: String,
    pub claim: String,
    /// What the paper states, and on what hardware.
    pub paper: String,
    pub hardware: String,
    /// The version the row's cells judged (for runs from before per-claim versions, `run-wide`
    /// and the version of their whole set of claims).
    pub version: String,
    /// Whether that is this build's definition of the claim, in words.
    pub status: String,
    /// One per machine, in the order of [`Group::machines`].
    pub cells: Vec<Cell>,
}

/// A claim whose definition differs between the runs of a group.
#[derive(Clone, Debug, Serialize)]
pub struct Changed {
    pub id: String,
    /// "changed since 1a2b3c4 (llvmpipe, 2026-11-28)": the newest run that judged the earlier
    /// definition.
    pub since: String,
    /// Each version, with the commits of the runs that judged it.
    pub versions: Vec<String>,
}

/// One claim on one machine.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// `None`: not judged there, or not in this row there (`ran` says which).
    pub holds: Option<bool>,
    /// The run judged this version of the claim.
    pub ran: bool,
    pub measured: String,
    /// The section's load at its start and end.
    pub load: String,
    /// The commit that ran the section, and the run's date.
    pub commit: String,
    pub date: String,
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

/// Reads every file; the error names a file that cannot be read or is not a results.json.
pub fn read(paths: &[PathBuf]) -> anyhow::Result<Vec<Run>> {
    if paths.is_empty() {
        bail!("compare: give at least one results.json (the file `reproduce` writes)");
    }
    paths.iter().map(|p| Run::read(p)).collect()
}

/// The runs in groups of the same sizes (the papers' sizes first, each in the order given),
/// labels numbered where runs of a group share one.
pub fn groups(runs: Vec<Run>) -> Vec<Vec<Run>> {
    let (quick, full): (Vec<Run>, Vec<Run>) = runs.into_iter().partition(|r| r.quick);
    let mut groups: Vec<Vec<Run>> = [full, quick]
        .into_iter()
        .filter(|g| !g.is_empty())
        .collect();
    for group in &mut groups {
        run::number_shared_labels(group);
    }
    groups
}

/// The comparison of `runs`: every group, every claim.
pub fn compare(runs: Vec<Run>) -> anyhow::Result<Comparison> {
    let groups = groups(runs);
    let several = groups.len() > 1;
    let groups = groups
        .into_iter()
        .map(|runs| {
            let reason = match (several, runs[0].quick) {
                (false, _) => String::new(),
                (true, false) => "runs at the papers' sizes".into(),
                (true, true) => "`--quick` runs (small sizes, for CI): their figures show the \
                                 mechanism, not the papers' sizes, so they are compared with \
                                 each other only"
                    .into(),
            };
            compare_group(runs, reason)
        })
        .collect::<anyhow::Result<_>>()?;
    Ok(Comparison { groups })
}

/// A claim's key across runs: its id, or for a run from before ids, its section and words.
pub fn key(section: &Section, claim: &Claim) -> String {
    if claim.id.is_empty() {
        format!("{}: {}", section.id, claim.claim)
    } else {
        claim.id.clone()
    }
}

/// The key of every claim of `run`, where a claim without an id takes the id a later run of
/// `runs` gives the claim of the same section and words.
fn keys_of<'a>(run: &'a Run, runs: &'a [Run]) -> Vec<(String, &'a Section, &'a Claim)> {
    let id_of = |section: &Section, claim: &Claim| {
        runs.iter()
            .filter_map(|r| r.section(&section.id))
            .flat_map(|s| &s.claims)
            .find(|c| !c.id.is_empty() && c.claim == claim.claim)
            .map(|c| c.id.clone())
    };
    run.sections
        .iter()
        .flat_map(|s| s.claims.iter().map(move |c| (s, c)))
        .map(|(s, c)| {
            let key = if c.id.is_empty() {
                id_of(s, c).unwrap_or_else(|| key(s, c))
            } else {
                c.id.clone()
            };
            (key, s, c)
        })
        .collect()
}

/// This build's version of claim `id` at the group's sizes (`None`: not a claim of this build).
pub fn current_version(id: &str, quick: bool) -> Option<String> {
    crate::report::claim_defs::find(id).and_then(|def| versions::current(def, quick).ok())
}

/// The words for the commit and machine of a run: "1a2b3c4 (llvmpipe, 2026-11-28)".
fn run_in_words(run: &Run) -> String {
    format!("{} ({}, {})", run.short_commit(), run.label, run.day())
}

/// What a claim of a run from before per-claim versions is compared as: the version of the
/// whole set of claims its run recorded, after this mark (runs of two such versions are never
/// mixed either).
const UNRECORDED: &str = "run-wide ";

fn compare_group(mut runs: Vec<Run>, reason: String) -> anyhow::Result<Group> {
    for run in &mut runs {
        let run_wide = format!("{UNRECORDED}{}", run.claims_version);
        for claim in run.sections.iter_mut().flat_map(|s| &mut s.claims) {
            if claim.version.is_empty() {
                claim.version = run_wide.clone();
            }
        }
    }
    let published = Published::get()?;
    let quick = runs[0].quick;
    let keyed: Vec<Vec<(String, &Section, &Claim)>> =
        runs.iter().map(|r| keys_of(r, &runs)).collect();
    // Every key in report order (the first run that has it decides where it goes).
    let mut order: Vec<String> = Vec::new();
    for claims in &keyed {
        for (key, _, _) in claims {
            if !order.contains(key) {
                order.push(key.clone());
            }
        }
    }
    let mut rows = Vec::new();
    let mut changed = Vec::new();
    for key in &order {
        // The versions of this claim, newest run first within each.
        let found: Vec<Option<(&Section, &Claim)>> = keyed
            .iter()
            .map(|claims| {
                claims
                    .iter()
                    .find(|(k, _, _)| k == key)
                    .map(|(_, s, c)| (*s, *c))
            })
            .collect();
        let mut versions: Vec<String> = Vec::new();
        for (_, claim) in found.iter().flatten() {
            if !versions.contains(&claim.version) {
                versions.push(claim.version.clone());
            }
        }
        let id = found
            .iter()
            .flatten()
            .map(|(_, c)| c.id.as_str())
            .find(|id| !id.is_empty())
            .unwrap_or_else(|| if key.contains(": ") { "" } else { key })
            .to_string();
        let current = current_version(&id, quick);
        // This build's definition first, then the newest run's.
        let newest = |v: &String| {
            runs.iter()
                .zip(&found)
                .filter(|(_, f)| f.is_some_and(|(_, c)| &c.version == v))
                .map(|(r, _)| r.date.clone())
                .max()
                .unwrap_or_default()
        };
        versions.sort_by(|a, b| {
            let is_current = |v: &String| Some(v) == current.as_ref();
            is_current(b)
                .cmp(&is_current(a))
                .then_with(|| newest(b).cmp(&newest(a)))
        });
        for version in &versions {
            let (section, claim) = found
                .iter()
                .flatten()
                .find(|(_, c)| &c.version == version)
                .copied()
                .expect("a run judged this version");
            let last_run = runs
                .iter()
                .zip(&found)
                .filter(|(_, f)| judged(f, version))
                .max_by(|a, b| a.0.date.cmp(&b.0.date))
                .map(|(r, _)| r)
                .expect("a run judged this version");
            rows.push(ClaimRow {
                id: id.clone(),
                section: section.id.clone(),
                claim: claim.claim.clone(),
                paper: claim.paper.clone(),
                hardware: hardware(published, &section.id),
                version: version.clone(),
                status: status(version, current.as_deref(), &id, last_run),
                cells: runs
                    .iter()
                    .zip(&found)
                    .map(|(run, f)| match f {
                        Some((s, c)) if judged(f, version) => cell(run, s, c),
                        Some((_, c)) => Cell {
                            holds: None,
                            ran: false,
                            measured: format!(
                                "judged as another version of the claim ({}): see its row",
                                version_words(&c.version)
                            ),
                            load: String::new(),
                            commit: run.short_commit(),
                            date: run.date.clone(),
                        },
                        None => not_run(run, &section.id),
                    })
                    .collect(),
            });
        }
        if versions.len() > 1 {
            let older = &versions[1..];
            let since = runs
                .iter()
                .zip(&found)
                .filter(|(_, f)| f.is_some_and(|(_, c)| older.contains(&c.version)))
                .max_by(|a, b| a.0.date.cmp(&b.0.date))
                .map(|(r, _)| run_in_words(r))
                .unwrap_or_default();
            changed.push(Changed {
                id: if id.is_empty() {
                    key.clone()
                } else {
                    id.clone()
                },
                since: format!("changed since {since}"),
                versions: versions
                    .iter()
                    .map(|v| {
                        let commits: Vec<String> = runs
                            .iter()
                            .zip(&found)
                            .filter(|(_, f)| f.is_some_and(|(_, c)| &c.version == v))
                            .map(|(r, _)| r.short_commit())
                            .collect();
                        format!("{} ({})", version_words(v), commits.join(", "))
                    })
                    .collect(),
            });
        }
    }
    Ok(Group {
        quick,
        reason,
        claims: rows,
        changed,
        headlines: headline::rows(&runs),
        then_and_now: headline::then_and_now(&runs),
        machines: runs,
    })
}

/// Whether the claim a run has (if any) is of `version`.
fn judged(found: &Option<(&Section, &Claim)>, version: &str) -> bool {
    found.is_some_and(|(_, c)| c.version == version)
}

/// A version for a reader: its hash, or that the run did not record one.
pub fn version_words(version: &str) -> String {
    match version.strip_prefix(UNRECORDED) {
        _ if version.is_empty() => "version not recorded: run before per-claim versions".into(),
        Some("") => version_words(""),
        Some(run_wide) => format!(
            "version not recorded: run before per-claim versions (its run's claims version {run_wide})"
        ),
        None => format!("version {version}"),
    }
}

/// Whether `version` is this build's definition of claim `id`, in words.
fn status(version: &str, current: Option<&str>, id: &str, last_run: &Run) -> String {
    match current {
        _ if version.is_empty() || version.starts_with(UNRECORDED) => version_words(version),
        Some(c) if c == version => "this build's definition".into(),
        Some(_) => format!(
            "definition changed since {}: re-run to compare with this build",
            run_in_words(last_run)
        ),
        None if id.is_empty() => "not a claim of this build".into(),
        None => format!("{id} is not a claim of this build (removed or renamed)"),
    }
}

/// Claim `claim` of section `section` on `run`.
fn cell(run: &Run, section: &Section, claim: &Claim) -> Cell {
    Cell {
        holds: claim.holds,
        ran: true,
        measured: claim.measured.clone(),
        load: run::section_load(section),
        commit: if section.commit.is_empty() {
            run.short_commit()
        } else {
            crate::report::provenance::short_commit(&section.commit)
        },
        date: run.date.clone(),
    }
}

/// The cell of a run without the claim.
fn not_run(run: &Run, section: &str) -> Cell {
    Cell {
        holds: None,
        ran: false,
        measured: if run.section(section).is_some() {
            "the section ran without this claim".into()
        } else {
            format!("section {section} was not run")
        },
        load: String::new(),
        commit: run.short_commit(),
        date: run.date.clone(),
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
    /// The results.json of each run (as `reproduce` writes them), one column each; with
    /// --baseline, the one new run.
    #[arg(required = true, value_name = "RESULTS_JSON")]
    pub results: Vec<PathBuf>,
    /// Where the page goes (index.html, comparison.json, the figures); not with --markdown,
    /// which writes no page.
    #[arg(long, default_value = "compare", conflicts_with = "markdown")]
    pub out: PathBuf,
    /// Write into a folder that holds other files (they are never replaced or removed), or
    /// replace an existing --junit file.
    #[arg(long, conflicts_with = "markdown")]
    pub force: bool,
    /// Print the README's "What a run shows" table (and the then-and-now lines) instead of
    /// writing the page: a table per size, each claim from the newest run of each machine
    /// whose version of it is this build's.
    #[arg(long, conflicts_with = "baseline")]
    pub markdown: bool,
    /// The regression gate: compare the one RESULTS_JSON with this earlier run, print each
    /// changed claim and a last line `compared N claims: R regressed, C changed definition,
    /// J not judged`; exit 1 when a claim regressed, else 0.
    #[arg(long, value_name = "OLD_JSON")]
    pub baseline: Option<PathBuf>,
    /// With --baseline: also write the gate's result as JUnit XML to FILE.xml (an existing
    /// file only with --force).
    #[arg(long, value_name = "FILE", requires = "baseline")]
    pub junit: Option<PathBuf>,
}

/// The page's own files besides the figures.
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
    let figure_names = plot::files(comparison);
    let mut names = vec![PAGE.to_string(), JSON.to_string()];
    names.extend(figure_names.iter().cloned());
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
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
