//! Paper 3's section (Oh & Jung 2004): Table 1 (texture creation, matrix product, sigmoid; GPU
//! vs CPU) beside the published numbers (`[paper3]` of `assets/paper_tables.toml`), the
//! GFLOP/s of both GPU formulations against both CPU baselines measured side by side in one
//! run, Fig. 2 (the classified text image), the period tables (the detector at the paper's
//! board's 24-bit precision and under its limits, beside fp32), and apart from the paper's
//! claims this project's own targets.

mod bench;
mod claims;
mod fidelity;
mod fig2;
mod fig2_files;
mod gflops;
pub mod period;
mod profile;
mod table1;
mod targets;
mod then_and_now;

pub use bench::{Detection, DetectionRun, Measurement, Method, Paper3Results};

use super::published::Published;
use super::{checks, BenchOptions, NoOptions, Paper, Section};
use crate::mlp::matmul::RADEON_9700_INPUTS_PER_PASS;

/// The paper-3 section.
pub struct Paper3;

impl Paper for Paper3 {
    const PERIOD_PAPER: Option<u8> = Some(3);
    const ID: &'static str = "paper3";
    const CLAIMS: &'static [super::ClaimDef] = claims::CLAIMS;
    const TITLE: &'static str = "Paper 3: Oh & Jung 2004, GPU implementation of neural networks";
    type Options = NoOptions;
    type Results = Paper3Results;

    fn measure(opts: &BenchOptions, _: &NoOptions) -> anyhow::Result<Paper3Results> {
        let (mut results, table) = super::profile::profiled(opts.gl, || bench::measure(opts))?;
        results.profile = Some(table);
        Ok(results)
    }

    fn section(opts: &BenchOptions, results: &Paper3Results) -> anyhow::Result<Section> {
        let paper = &Published::get()?.paper3.table1;
        let mut figures = fig2::figures();
        figures.push(gflops::figure(opts, results)?);
        figures.extend(results.period.as_ref().map(period::figure));
        Ok(Section {
            summary: summary(results),
            tables: vec![
                table1::table(results, paper),
                gflops::table(results),
                fig2::table(results),
                targets::table(results),
                results.then_and_now.table(&results.renderer),
            ]
            .into_iter()
            .chain(results.period.iter().flat_map(period::tables))
            .chain(profile::table(results))
            .chain([super::not_built::table(
                "paper 3 names",
                super::not_built::PAPER3,
            )])
            .collect(),
            claims: claims::claims(results, paper),
            figures,
            fidelity: fidelity::rows(),
            checks_listed: checks::ids(&listed_checks(results)),
            checks_made: checks_made(results),
            ..Section::default()
        })
    }
}

/// The checks of [`checks::PAPER3`] this run can make: the then-and-now comparison only where
/// the compute formulation runs (OpenGL 4.3).
pub fn listed_checks(results: &Paper3Results) -> Vec<checks::Check> {
    let skip: &[&str] = match results.then_and_now.unavailable {
        Some(_) => &["then and now same outputs"],
        None => &[],
    };
    checks::without(checks::PAPER3, skip)
}

/// The checks of [`checks::PAPER3`] whose comparisons are in `results`.
pub fn checks_made(results: &Paper3Results) -> Vec<String> {
    checks::made(&[
        (!results.measurements.is_empty(), "outputs vs CPU"),
        (results.detection.width > 0, "detection vs CPU"),
        (
            results.then_and_now.same_answer.is_some(),
            "then and now same outputs",
        ),
    ])
}

fn summary(results: &Paper3Results) -> String {
    format!(
        "The text detector's MLP (11 x 11 window = 121 inputs, 30 hidden sigmoid nodes, 1 \
         output; weights trained here on synthetic text, assets/mlp/text_detector.json) and a \
         wider synthetic network, each evaluated five ways in one run on {}: the paper's render \
         passes (one float per texel, one inner product per fragment), once with each product \
         in one pass and once split into passes of at most {} inputs, our estimate of what the \
         paper's ATI RADEON 9700 PRO allowed, a packed variant (RGBA \
         texels, 4 x 4 outputs per fragment), the plain CPU loop the paper compared with, and \
         matrixmultiply's sgemm. GPU passes are timed with GL timer queries, texture creation \
         and CPU work with the wall clock; each figure is the median of its runs after a \
         warm-up run ({} runs per measurement, as the throughput table lists); {} at the \
         end (a software renderer shares the CPU with whatever else runs).{} The batches are \
         windows of scikit-image's text.png. {}",
        results.renderer,
        RADEON_9700_INPUTS_PER_PASS,
        runs_range(results),
        results
            .load
            .map_or("load average unknown".to_string(), |l| l.in_words()),
        if results.quick {
            " QUICK MODE: reduced sizes."
        } else {
            ""
        },
        checks::sentence(&listed_checks(results)),
    )
}

/// "3" or "3-5": the fewest and most timed runs of any measurement.
fn runs_range(results: &Paper3Results) -> String {
    let runs = results.measurements.iter().map(|m| m.runs);
    match (runs.clone().min(), runs.max()) {
        (Some(a), Some(b)) if a != b => format!("{a}-{b}"),
        (Some(a), _) => a.to_string(),
        _ => "no".into(),
    }
}

/// Every fidelity row of the section.
pub fn fidelity_rows() -> Vec<super::Fidelity> {
    fidelity::rows()
}
