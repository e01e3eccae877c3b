//! The table: both ways of summing, by size.

use super::bench::{repeats, BlocksResults};
use crate::report::{BenchOptions, Table};

pub fn table(opts: &BenchOptions, results: &BlocksResults) -> Table {
    let renderer = opts.gl.info().renderer_line();
    Table {
        caption: format!(
            "Sum of an n x n RGBA32F buffer ({renderer}), best of {}",
            repeats(opts)
        ),
        header: [
            "n",
            "passes",
            "reduce GPU ms",
            "reduce wall ms",
            "readback wall ms",
            "readback / reduce",
            "bytes read (reduce)",
            "bytes read (readback)",
            "rel. diff",
        ]
        .map(String::from)
        .to_vec(),
        rows: results
            .reduction
            .iter()
            .map(|r| {
                vec![
                    r.size.to_string(),
                    r.passes.to_string(),
                    format!("{:.3}", r.reduce_gpu_ms),
                    format!("{:.3}", r.reduce_wall_ms),
                    format!("{:.3}", r.readback_wall_ms),
                    format!("{:.2}", r.readback_wall_ms / r.reduce_wall_ms),
                    r.reduce_bytes.to_string(),
                    r.readback_bytes.to_string(),
                    format!("{:.1e}", r.relative_difference),
                ]
            })
            .collect(),
    }
}
