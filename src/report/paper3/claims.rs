//! The paper's claims (the 20-fold speed-up of Table 1, Fig. 2's "almost the same result"),
//! judged on this run. This project's own targets are not claims of the paper: see
//! [`super::targets`].

use super::bench::{Method, Paper3Results};
use crate::report::published::Paper3Table1;
use crate::report::versions::TIMING_POLICY;
use crate::report::{Basis, Claim, ClaimDef, Evidence};
use crate::timing;

/// Every claim of the section, with what decides it.
pub const CLAIMS: &[ClaimDef] = &[TWENTY_FOLD, SAME_CLASSIFICATION];

pub fn claims(results: &Paper3Results, paper: &Paper3Table1) -> Vec<Claim> {
    vec![twenty_fold(results, paper), same_classification(results)]
}

// region: rule twenty-fold
/// Table 1: the GPU about 20 times faster than CPU-only processing.
const TWENTY_FOLD: ClaimDef = ClaimDef {
    id: "paper3.twenty-fold",
    rule: &[
        "src/report/paper3/claims.rs#rule twenty-fold",
        TIMING_POLICY,
    ],
    published: &["paper3.table1"],
    workload: &[
        "src/report/paper3/bench.rs#workload runs",
        "src/report/paper3/bench.rs#workload cases",
    ],
    // Twice the most it moved between three llvmpipe runs of one build, 2 cores (54%).
    band: Some(1.1),
};

/// A software renderer runs the "GPU" passes on the CPU (the report's timing policy,
/// [`crate::report::timing_policy`], says what a verdict means there).
pub fn software(results: &Paper3Results) -> bool {
    results.renderer.contains("llvmpipe") || results.renderer.contains("softpipe")
}

fn twenty_fold(results: &Paper3Results, paper: &Paper3Table1) -> Claim {
    let (cpu, gpu) = (
        results.paper_row(Method::CpuPlain),
        results.paper_row(Method::GpuFaithful),
    );
    let speedup = cpu.total_ms / gpu.total_ms;
    // The speed-up from the runs' ends: the CPU's slowest over the GPU's fastest favours it.
    let (cpu_runs, gpu_runs) = (&cpu.total_spread_ms, &gpu.total_spread_ms);
    let ends = timing::Ends::of(|favour| {
        timing::end(cpu_runs, favour) / timing::end(gpu_runs, !favour) >= paper.speedup_claimed
    });
    let runs = format!(
        "CPU {}; GPU {}",
        cpu_runs.in_words(" ms"),
        gpu_runs.in_words(" ms")
    );
    let verdict = timing::judge_ends(
        ends,
        &runs,
        &format!(
            "the runs give speed-ups on both sides of {}x",
            paper.speedup_claimed
        ),
        results.load,
    );
    Claim {
        id: TWENTY_FOLD.id.into(),
        claim: "The GPU is about 20 times faster than CPU-only processing".into(),
        paper: format!(
            "CPU {} vs GPU {} + {} + {} (ATI RADEON 9700 PRO)",
            paper.cpu_matrix_multiplication,
            paper.gpu_texture_creation,
            paper.gpu_matrix_multiplication,
            paper.gpu_sigmoid
        ),
        measured: format!(
            "CPU plain loop / GPU faithful (all steps) = {speedup:.2}x on {} ({})",
            results.renderer, verdict.note
        ),
        decided_by: Basis::Timing,
        holds: verdict.holds,
        evidence: vec![TWENTY_FOLD.timing(
            "CPU-only / GPU time, all steps",
            speedup,
            "x",
            true,
            results.load,
        )],
        ..Claim::default()
    }
}
// endregion

// region: rule same-classification
/// Fig. 2(b): the GPU classifies text.png as the CPU does.
const SAME_CLASSIFICATION: ClaimDef = ClaimDef {
    id: "paper3.same-classification",
    rule: &["src/report/paper3/claims.rs#rule same-classification"],
    published: &[],
    workload: &["src/report/paper3/bench.rs#workload cases"],
    band: None,
};

fn same_classification(results: &Paper3Results) -> Claim {
    let agreement = results.detection.faithful.agreement_with_cpu;
    Claim {
        id: SAME_CLASSIFICATION.id.into(),
        claim: "Classification on the GPU gives almost the same result as without it".into(),
        paper: "Fig. 2(b), qualitative".into(),
        measured: format!(
            "{:.4}% of text.png's pixels classified identically (faithful GPU vs CPU)",
            100.0 * agreement
        ),
        decided_by: Basis::Count,
        holds: Some(agreement >= 0.999),
        evidence: vec![Evidence::count(
            "share of text.png's pixels classified as the CPU does",
            agreement,
        )],
        ..Claim::default()
    }
}
// endregion
