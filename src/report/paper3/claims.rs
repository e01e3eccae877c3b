//! The paper's claims (the 20-fold speed-up of Table 1, Fig. 2's "almost the same result"),
//! and this project's throughput target, judged on this run.

use super::bench::{Method, Paper3Results};
use crate::report::published::Paper3Table1;
use crate::report::Claim;

pub fn claims(results: &Paper3Results, paper: &Paper3Table1) -> Vec<Claim> {
    vec![
        twenty_fold(results, paper),
        same_classification(results),
        packed_target(results),
    ]
}

/// A software renderer runs the "GPU" passes on the CPU: a GPU-versus-CPU ratio says nothing
/// about the paper's claim there.
fn software(results: &Paper3Results) -> bool {
    results.renderer.contains("llvmpipe") || results.renderer.contains("softpipe")
}

fn twenty_fold(results: &Paper3Results, paper: &Paper3Table1) -> Claim {
    let speedup = results.paper_row(Method::CpuPlain).total_ms
        / results.paper_row(Method::GpuFaithful).total_ms;
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
            "CPU plain loop / GPU faithful (all steps) = {speedup:.2}x on {}",
            results.renderer
        ),
        holds: if software(results) {
            None
        } else {
            Some(speedup >= paper.speedup_claimed)
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

fn packed_target(results: &Paper3Results) -> Claim {
    let best = |f: fn(&super::bench::Measurement) -> f64| {
        results
            .measurements
            .iter()
            .filter(|m| m.method == Method::GpuPacked)
            .map(f)
            .fold(0.0, f64::max)
    };
    let (median, fastest) = (best(|m| m.matmul_gflops), best(|m| m.best_matmul_gflops));
    Claim {
        claim: "The packed product reaches 10 GFLOP/s on the project's 2-core machine (issue 7 \
                target)"
            .into(),
        paper: "not in the paper".into(),
        measured: format!(
            "packed matrix product, best case: {median:.2} GFLOP/s (median run), {fastest:.2} \
             GFLOP/s (fastest run)"
        ),
        holds: if software(results) {
            Some(median >= 10.0)
        } else {
            None
        },
    }
}
