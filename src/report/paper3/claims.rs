//! The paper's claims (the 20-fold speed-up of Table 1, Fig. 2's "almost the same result"),
//! judged on this run. This project's own targets are not claims of the paper: see
//! [`super::targets`].

use super::bench::{Method, Paper3Results};
use crate::report::published::Paper3Table1;
use crate::report::timing;
use crate::report::Claim;

pub fn claims(results: &Paper3Results, paper: &Paper3Table1) -> Vec<Claim> {
    vec![twenty_fold(results, paper), same_classification(results)]
}

/// A software renderer runs the "GPU" passes on the CPU: a GPU-versus-CPU ratio says nothing
/// about the paper's claim there.
pub fn software(results: &Paper3Results) -> bool {
    results.renderer.contains("llvmpipe") || results.renderer.contains("softpipe")
}

fn twenty_fold(results: &Paper3Results, paper: &Paper3Table1) -> Claim {
    let speedup = results.paper_row(Method::CpuPlain).total_ms
        / results.paper_row(Method::GpuFaithful).total_ms;
    let verdict = timing::judge_under_load(speedup >= paper.speedup_claimed, results.load);
    Claim {
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
            results.renderer,
            if software(results) {
                "not judged: a software renderer is not the GPU the claim is about".to_string()
            } else {
                verdict.note
            }
        ),
        holds: if software(results) {
            None
        } else {
            verdict.holds
        },
    }
}

fn same_classification(results: &Paper3Results) -> Claim {
    let agreement = results.detection.faithful.agreement_with_cpu;
    Claim {
        claim: "Classification on the GPU gives almost the same result as without it".into(),
        paper: "Fig. 2(b), qualitative".into(),
        measured: format!(
            "{:.4}% of text.png's pixels classified identically (faithful GPU vs CPU)",
            100.0 * agreement
        ),
        holds: Some(agreement >= 0.999),
    }
}
