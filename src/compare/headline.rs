//! The headline figures: one row per headline claim of each paper (the README's "What a run
//! shows" table), each machine's verdict and the figure it rests on, and the then-and-now
//! ratios. Every figure is read from a run's `results.json`: the numbers of a claim's measured
//! text (so the figure is the one the claim was judged on, as the report printed it), or the
//! section's results (the then-and-now tables).

use super::run::Run;
use crate::report::published::Published;
use crate::report::{Claim, Section};
use serde::Serialize;

/// A figure on one machine: the words for the table, and the ratio for the plot.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Figure {
    pub text: String,
    /// The headline's ratio (see [`Headline::ratio`]), where it has one.
    pub ratio: Option<f64>,
}

/// One headline claim: which claim of which section, in the README's words, and how its
/// figure is read.
pub struct Headline {
    /// The paper's number ("1" .. "4").
    pub paper: &'static str,
    pub section: &'static str,
    /// The claim's id ([`crate::report::ClaimDef::id`]).
    pub id: &'static str,
    /// Words of the claim's text that find it in a run from before claims had ids.
    pub claim: &'static str,
    /// The claim in a few words.
    pub label: &'static str,
    /// What the plotted ratio is, where the figure has one ("" for none).
    pub ratio: &'static str,
    /// The paper's own value of that ratio, where it states one.
    pub paper_ratio: fn(&Published) -> Option<f64>,
    /// The figure, from the claim and its section.
    pub figure: fn(&Claim, &Section, &Published) -> Option<Figure>,
}

/// The headline claims, in the README's order.
pub fn headlines() -> Vec<Headline> {
    vec![
        Headline {
            paper: "1",
            section: "paper1",
            id: "paper1.tori-frame-interactive",
            claim: "A whole frame of the 15K-triangle tori scenes is interactive",
            label: "15K-triangle tori, whole frame",
            ratio: "paper 1: the paper's slowest tori frame / the slowest here",
            paper_ratio: |_| Some(1.0),
            figure: tori_frame,
        },
        Headline {
            paper: "1",
            section: "paper1",
            id: "paper1.beats-cullide",
            claim: "About 3x faster than CULLIDE, and nothing missed",
            label: "faster than CULLIDE, no pair missed",
            ratio: "paper 1: CULLIDE / streaming frame time (mean over the scenes)",
            paper_ratio: |p| Some(p.paper1.claims.speedup_over_cullide),
            figure: beats_cullide,
        },
        Headline {
            paper: "1",
            section: "paper1",
            id: "paper1.beats-solid",
            claim: "Streaming culling + update beats SOLID's refit + traversal",
            label: "faster than SOLID's CPU refit",
            ratio: "paper 1: SOLID / streaming culling with download (lowest over the scenes)",
            paper_ratio: |p| Some(p.paper1.claims.speedup_over_solid_with_download[0]),
            figure: beats_solid,
        },
        Headline {
            paper: "1",
            section: "paper1",
            id: "paper1.any-p0-read-back-quickly",
            claim: "With the scheme chosen per eta, any P0 is read back quickly",
            label: "any P0 read back quickly",
            ratio: "",
            paper_ratio: |_| None,
            figure: readback,
        },
        Headline {
            paper: "2",
            section: "paper2",
            id: "paper2.overtakes-vs-one-per-draw",
            claim: "Two-pass (pixel-shader) skinning overtakes vertex-shader skinning (VS 1/draw)",
            label: "two-pass skinning overtakes vertex-shader skinning (one character per draw)",
            ratio: "",
            paper_ratio: |_| None,
            figure: crossover,
        },
        Headline {
            paper: "3",
            section: "paper3",
            id: "paper3.twenty-fold",
            claim: "The GPU is about 20 times faster than CPU-only processing",
            label: "GPU vs CPU-only MLP",
            ratio: "paper 3: CPU-only / GPU time of the MLP",
            paper_ratio: |p| Some(p.paper3.table1.speedup_claimed),
            figure: mlp_speedup,
        },
        Headline {
            paper: "3",
            section: "paper3",
            id: "paper3.same-classification",
            claim: "Classification on the GPU gives almost the same result as without it",
            label: "GPU mask equals the CPU mask (text.png)",
            ratio: "",
            paper_ratio: |_| None,
            figure: mlp_mask,
        },
        Headline {
            paper: "4",
            section: "paper4",
            id: "paper4.error-bound",
            claim: "is enough for 5% error in mass and the moments of inertia",
            label: "error at 32x32 (mass and I_xx, I_yy, I_zz, as Fig. 4)",
            ratio: "",
            paper_ratio: |_| None,
            figure: error_bound,
        },
        Headline {
            paper: "4",
            section: "paper4",
            id: "paper4.outperforms-analytic-bunny",
            claim: "at 64x64 the GPU method outperforms the analytic one for the bunny",
            label: "at 64x64 the GPU outperforms the analytic method (bunny)",
            ratio: "paper 4: analytic / GPU time, bunny at 64x64",
            paper_ratio: |_| None,
            figure: outperforms_analytic,
        },
        Headline {
            paper: "4",
            section: "paper4",
            id: "paper4.interactive-buoyancy",
            claim: "interactive buoyancy of",
            label: "floating bodies, frames per second",
            ratio: "paper 4: buoyancy frames/s / the paper's",
            paper_ratio: |_| Some(1.0),
            figure: buoyancy,
        },
    ]
}

/// One headline across the machines.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The claim's id.
    pub id: String,
    pub paper: String,
    pub section: String,
    pub label: String,
    /// What the paper states (the claim's own words for it).
    pub published: String,
    pub ratio: String,
    pub paper_ratio: Option<f64>,
    /// One per machine.
    pub cells: Vec<Cell>,
}

/// A headline on one machine.
#[derive(Clone, Debug, Serialize)]
pub struct Cell {
    /// "yes", "no", "not judged", or "not run".
    pub verdict: String,
    /// `None` where the claim was not run, or its figure could not be read (a bug the
    /// tests catch: the claim's words changed).
    pub figure: Option<Figure>,
    /// The version of the claim the run judged ("" where it did not record one).
    pub version: String,
}

impl Cell {
    /// "yes: 46.18x on average ...", "not run".
    pub fn text(&self) -> String {
        match &self.figure {
            Some(f) => format!("{}: {}", self.verdict, f.text),
            None if self.verdict == "not run" => self.verdict.clone(),
            None => format!("{}: (figure not found)", self.verdict),
        }
    }
}

/// The headline rows of `runs`; a headline no run has is left out.
pub fn rows(runs: &[Run]) -> Vec<Row> {
    let Ok(published) = Published::get() else {
        return Vec::new();
    };
    let mut rows = Vec::new();
    for h in headlines() {
        let found: Vec<Option<(&Claim, &Section)>> = runs.iter().map(|r| find(r, &h)).collect();
        let Some((first, _)) = found.iter().flatten().next() else {
            continue;
        };
        rows.push(Row {
            id: h.id.into(),
            paper: h.paper.into(),
            section: h.section.into(),
            label: h.label.into(),
            published: first.paper.clone(),
            ratio: h.ratio.into(),
            paper_ratio: (h.paper_ratio)(published),
            cells: found.iter().map(|f| cell(&h, *f, published)).collect(),
        });
    }
    rows
}

/// Headline `h` on a run that made its claim (`found`), or did not.
pub fn cell(h: &Headline, found: Option<(&Claim, &Section)>, published: &Published) -> Cell {
    match found {
        Some((claim, section)) => Cell {
            verdict: verdict(claim.holds).into(),
            figure: (h.figure)(claim, section, published),
            version: claim.version.clone(),
        },
        None => Cell {
            verdict: "not run".into(),
            figure: None,
            version: String::new(),
        },
    }
}

/// The claim of headline `h` on `run`, and its section: by its id, or in a run from before
/// ids, by its words.
pub fn find<'a>(run: &'a Run, h: &Headline) -> Option<(&'a Claim, &'a Section)> {
    let section = run.section(h.section)?;
    let claim = section.claims.iter().find(|c| c.id == h.id).or_else(|| {
        section
            .claims
            .iter()
            .find(|c| c.id.is_empty() && c.claim.contains(h.claim))
    })?;
    Some((claim, section))
}

/// The README's verdict words.
fn verdict(holds: Option<bool>) -> &'static str {
    match holds {
        Some(true) => "yes",
        Some(false) => "no",
        None => "not judged",
    }
}

/// The number that starts `text` ("12.5", "-0.3", "1e-3"), and the text after it.
pub fn leading_number(text: &str) -> Option<(f64, &str)> {
    let end = text
        .char_indices()
        .find(|&(i, c)| {
            !(c.is_ascii_digit()
                || c == '.'
                || (c == '-' && i == 0)
                || ((c == 'e' || c == 'E') && i > 0))
        })
        .map_or(text.len(), |(i, _)| i);
    // A trailing '.' or 'e' belongs to the words, not the number.
    let number = text[..end].trim_end_matches(['.', 'e', 'E']);
    let value = number.parse::<f64>().ok()?;
    Some((value, &text[number.len()..]))
}

/// The number right after the first `phrase` in `text`.
pub fn number_after(text: &str, phrase: &str) -> Option<f64> {
    let at = text.find(phrase)? + phrase.len();
    leading_number(&text[at..]).map(|(v, _)| v)
}

/// The range "lo-hi" right after the first `phrase` (a single number gives lo = hi).
pub fn range_after(text: &str, phrase: &str) -> Option<(f64, f64)> {
    let at = text.find(phrase)? + phrase.len();
    let (lo, rest) = leading_number(&text[at..])?;
    match rest.strip_prefix('-').and_then(leading_number) {
        Some((hi, _)) => Some((lo, hi)),
        None => Some((lo, lo)),
    }
}

/// A figure as the report prints it: up to 3 significant digits, at least 2 decimals under 10.
fn num(v: f64) -> String {
    if v.abs() >= 100.0 {
        format!("{v:.0}")
    } else if v.abs() >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

fn tori_frame(claim: &Claim, _: &Section, p: &Published) -> Option<Figure> {
    let slowest = number_after(&claim.measured, "slowest tori scene ")?;
    // The tori scenes of Table III (the claim's 7.86-29.35 ms).
    let paper = p
        .paper1
        .table3
        .iter()
        .filter(|r| r.models.contains("tori"))
        .map(|r| r.total)
        .fold(0.0, f64::max);
    Some(Figure {
        text: format!(
            "slowest scene {} ms per frame, {}x the paper's slowest ({} ms)",
            num(slowest),
            num(paper / slowest),
            num(paper)
        ),
        ratio: (slowest > 0.0).then(|| paper / slowest),
    })
}

fn beats_cullide(claim: &Claim, _: &Section, _: &Published) -> Option<Figure> {
    let m = &claim.measured;
    let mean = number_after(m, "CULLIDE / streaming ")?;
    let (lo, hi) = range_after(m, "scenes (")?;
    let (missed_lo, missed_hi) = range_after(m, "CULLIDE missed ")?;
    let exact = if m.contains("in every frame: true") {
        "streaming missed none (equal to SOLID's exact pairs in every frame)"
    } else {
        "STREAMING MISSED PAIRS"
    };
    Some(Figure {
        text: format!(
            "{}x on average ({}-{}x); CULLIDE missed {missed_lo:.0}-{missed_hi:.0}%, {exact}",
            num(mean),
            num(lo),
            num(hi)
        ),
        ratio: Some(mean),
    })
}

fn beats_solid(claim: &Claim, _: &Section, _: &Published) -> Option<Figure> {
    let (lo, hi) = range_after(&claim.measured, "without download, ")?;
    Some(Figure {
        text: format!(
            "SOLID / streaming {}-{}x with the download",
            num(lo),
            num(hi)
        ),
        ratio: Some(lo),
    })
}

fn readback(claim: &Claim, _: &Section, _: &Published) -> Option<Figure> {
    let m = &claim.measured;
    let ms = number_after(m, "at most ")?;
    let side = leading_number(m).map(|(v, _)| v)?;
    Some(Figure {
        text: format!(
            "at most {} ms for a {side:.0}x{side:.0} P0 (the faster scheme at each eta)",
            num(ms)
        ),
        ratio: None,
    })
}

fn crossover(claim: &Claim, _: &Section, _: &Published) -> Option<Figure> {
    let m = &claim.measured;
    let text = m[..m.find(" (")?].to_string();
    Some(Figure { text, ratio: None })
}

fn mlp_speedup(claim: &Claim, _: &Section, _: &Published) -> Option<Figure> {
    let speedup = number_after(&claim.measured, "(all steps) = ")?;
    Some(Figure {
        text: format!("CPU / GPU time {}x", num(speedup)),
        ratio: Some(speedup),
    })
}

fn mlp_mask(claim: &Claim, _: &Section, _: &Published) -> Option<Figure> {
    let (share, _) = leading_number(&claim.measured)?;
    Some(Figure {
        text: format!("{share:.2}% of pixels the same"),
        ratio: None,
    })
}

fn error_bound(claim: &Claim, _: &Section, _: &Published) -> Option<Figure> {
    let worst = number_after(&claim.measured, ": ")?;
    Some(Figure {
        text: format!("worst {worst:.2}% (closed objects)"),
        ratio: None,
    })
}

fn outperforms_analytic(claim: &Claim, _: &Section, _: &Published) -> Option<Figure> {
    let m = &claim.measured;
    let gpu = number_after(m, "GPU ")?;
    let analytic = number_after(m, "vs analytic ")?;
    Some(Figure {
        text: format!(
            "GPU {} ms (wall) against analytic {} ms",
            num(gpu),
            num(analytic)
        ),
        ratio: (gpu > 0.0).then(|| analytic / gpu),
    })
}

fn buoyancy(claim: &Claim, _: &Section, p: &Published) -> Option<Figure> {
    let (fps, _) = leading_number(&claim.measured)?;
    let paper = p.paper4.buoyancy.frames_per_second;
    Some(Figure {
        text: format!("{} frames/s, {}x the paper's", num(fps), num(fps / paper)),
        ratio: Some(fps / paper),
    })
}

/// The then-and-now block of a section: `results.then_and_now` of a paper, or lecture 1's
/// `then-and-now` block.
fn then_and_now_of(section: &Section) -> Option<&serde_json::Value> {
    let results = &section.results;
    if results["then_and_now"].is_object() {
        return Some(&results["then_and_now"]);
    }
    results["blocks"]
        .as_array()?
        .iter()
        .find(|b| b["id"] == "then-and-now")
        .map(|b| &b["results"])
}

/// The sections with a then-and-now block, and how the README names them.
pub const THEN_AND_NOW: [(&str, &str); 5] = [
    ("paper1", "paper 1"),
    ("paper2", "paper 2"),
    ("paper3", "paper 3"),
    ("paper4", "paper 4"),
    ("lecture1", "lecture 1's pairwise test"),
];

/// One section's then-and-now figure on one machine.
#[derive(Clone, Debug, Serialize)]
pub struct ThenAndNowCell {
    pub section: String,
    /// The frame time of the compute formulation over the classic one.
    pub ratio: Option<f64>,
    /// Whether both formulations gave the same answer, where the section says.
    pub same_answer: Option<bool>,
    /// Why there is no ratio (no compute shaders, section not run).
    pub note: String,
}

/// One machine's then-and-now figures.
#[derive(Clone, Debug, Serialize)]
pub struct ThenAndNowRow {
    pub machine: String,
    pub cells: Vec<ThenAndNowCell>,
}

/// The then-and-now figures of every machine: the last stage (the whole frame) of each
/// section's then-and-now table, compute over classic.
pub fn then_and_now(runs: &[Run]) -> Vec<ThenAndNowRow> {
    runs.iter()
        .map(|run| ThenAndNowRow {
            machine: run.label.clone(),
            cells: THEN_AND_NOW
                .iter()
                .map(|(id, _)| then_and_now_cell(run, id))
                .collect(),
        })
        .collect()
}

fn then_and_now_cell(run: &Run, id: &str) -> ThenAndNowCell {
    let mut cell = ThenAndNowCell {
        section: id.into(),
        ratio: None,
        same_answer: None,
        note: String::new(),
    };
    let Some(block) = run.section(id).and_then(then_and_now_of) else {
        cell.note = "not run".into();
        return cell;
    };
    cell.same_answer = block["same_answer"].as_bool();
    if let Some(reason) = block["unavailable"].as_str() {
        cell.note = format!("no compute shaders ({reason})");
        return cell;
    }
    let frame = block["stages"].as_array().and_then(|s| s.last());
    match frame.map(|f| (f["classic_ms"].as_f64(), f["compute_ms"].as_f64())) {
        Some((Some(classic), Some(compute))) if classic > 0.0 && compute > 0.0 => {
            cell.ratio = Some(compute / classic);
        }
        _ => cell.note = "no frame time of both formulations".into(),
    }
    cell
}

/// A then-and-now figure in words: "2.80x", "2.80x (THE ANSWERS DIFFERED)", or the note.
pub fn then_and_now_text(cell: &ThenAndNowCell) -> String {
    match cell.ratio {
        Some(r) if cell.same_answer == Some(false) => format!("{}x (THE ANSWERS DIFFERED)", num(r)),
        Some(r) => format!("{}x", num(r)),
        None => cell.note.clone(),
    }
}
