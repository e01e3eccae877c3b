//! This project's own targets for paper 3, apart from the paper's claims: what the code aims
//! at on the machine it is developed on, which the paper never states.

use super::bench::{Measurement, Method, Paper3Results};
use super::claims::software;
use crate::report::Table;

/// The project's target for the packed product on a software renderer (2 cores): a naive
/// fragment-shader product reaches about 2 GFLOP/s there, and packing 4 x 4 outputs per
/// fragment should make it at least five times that.
const PACKED_GFLOPS_TARGET: f64 = 10.0;

pub fn table(results: &Paper3Results) -> Table {
    Table {
        caption: format!(
            "Project targets (this project's goals, not claims of the paper; {})",
            results.renderer
        ),
        header: ["target", "source", "measured", "met"]
            .map(String::from)
            .to_vec(),
        rows: vec![packed_gflops(results)],
    }
}

fn packed_gflops(results: &Paper3Results) -> Vec<String> {
    let best = |f: fn(&Measurement) -> f64| {
        results
            .measurements
            .iter()
            .filter(|m| m.method == Method::GpuPacked)
            .map(f)
            .fold(0.0, f64::max)
    };
    let (median, fastest) = (best(|m| m.matmul_gflops), best(|m| m.best_matmul_gflops));
    let met = if !software(results) {
        "not judged (set for a software renderer on 2 cores)"
    } else if median >= PACKED_GFLOPS_TARGET {
        "yes"
    } else {
        "no"
    };
    vec![
        format!(
            "The packed product reaches {PACKED_GFLOPS_TARGET} GFLOP/s on the project's 2-core \
             machine"
        ),
        "this project's goal: 5x a naive fragment product's 2 GFLOP/s, by packing 4 x 4 \
         outputs per fragment"
            .into(),
        format!(
            "packed matrix product, best case: {median:.2} GFLOP/s (median run), {fastest:.2} \
             GFLOP/s (fastest run)"
        ),
        met.into(),
    ]
}
