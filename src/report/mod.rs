//! The reproduction report: each paper's benchmark at the paper's sizes, beside the
//! published numbers (`assets/paper_tables.toml`), written as HTML, JSON and PNG.
//!
//! Each paper plugs in through one file, `report/paperN.rs`, whose `run` measures with the
//! paper module and returns a [`Section`]. The `*-bench` commands and `reproduce` both call it.

pub mod blocks;
mod html;
pub mod paper1;
pub mod paper2;
pub mod paper3;
pub mod paper4;
pub mod paper_tables;
pub mod plot;
pub mod reproduce;

use serde::Serialize;
use std::path::PathBuf;

/// What every paper's benchmark gets: the GL context, the size, where figures go.
pub struct BenchOptions<'a> {
    pub gl: &'a crate::gl::Context,
    /// Small sizes for CI and smoke tests; the report says so.
    pub quick: bool,
    /// Figures (PNG) are written here; [`Figure::file`] is relative to it.
    pub out_dir: PathBuf,
    /// Progress bars for long stages (hidden under `--json` or when not a terminal).
    pub progress: indicatif::MultiProgress,
}

/// The whole report, as written to `results.json`.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub renderer: crate::gl::ContextInfo,
    pub cpu: String,
    pub date: String,
    pub quick: bool,
    pub elapsed_s: f64,
    pub sections: Vec<Section>,
}

/// One paper's part of the report.
#[derive(Clone, Debug, Default, Serialize)]
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
    /// Every measured number, machine readable.
    pub results: serde_json::Value,
}

/// A table of measured numbers, usually with the paper's numbers in adjacent columns.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Table {
    pub caption: String,
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

/// A qualitative or quantitative claim of the paper, and whether it holds here.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Claim {
    pub claim: String,
    pub paper: String,
    pub measured: String,
    /// `None` when the claim cannot be judged on this renderer.
    pub holds: Option<bool>,
}

/// A PNG written under [`BenchOptions::out_dir`].
#[derive(Clone, Debug, Default, Serialize)]
pub struct Figure {
    pub file: String,
    pub caption: String,
}

/// One row of a paper's fidelity table.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Fidelity {
    pub feature: String,
    pub paper: String,
    /// Where this code does it (file path).
    pub code: String,
}

impl Fidelity {
    pub fn new(feature: &str, paper: &str, code: &str) -> Fidelity {
        Fidelity {
            feature: feature.into(),
            paper: paper.into(),
            code: code.into(),
        }
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
                "- {} [{}]\n  paper: {}\n  here:  {}\n",
                claim.claim,
                claim.verdict(),
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

/// A `*-bench` command: run one paper's section with its figures in `out_dir`, then print
/// its tables and claims, or the whole section as JSON.
pub fn bench_command(
    gl: &crate::gl::Context,
    run: impl FnOnce(&BenchOptions) -> anyhow::Result<Section>,
    quick: bool,
    out_dir: &std::path::Path,
    json: bool,
) -> anyhow::Result<()> {
    use anyhow::Context as _;
    std::fs::create_dir_all(out_dir).with_context(|| format!("creating {}", out_dir.display()))?;
    let opts = BenchOptions {
        gl,
        quick,
        out_dir: out_dir.to_path_buf(),
        progress: progress_bars(json),
    };
    let section = run(&opts)?;
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
