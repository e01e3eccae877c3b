//! Matrix-product throughput (not in the paper): GFLOP/s of every case and method side by
//! side, as a table and as a plot against the batch size.

use super::bench::{Method, Paper3Results};
use super::table1::{ms, passes};
use crate::page::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};

pub fn table(results: &Paper3Results) -> Table {
    Table {
        caption: format!(
            "Matrix product throughput, every method side by side (GFLOP/s = 2 M N L / \
             median product time; best = fastest run; runs = timed runs after a warm-up; max \
             |diff| against the CPU plain loop's outputs; {})",
            results.renderer
        ),
        header: [
            "case",
            "method",
            "tiles",
            "product passes",
            "texture ms",
            "product ms",
            "sigmoid ms",
            "total ms",
            "GFLOP/s",
            "best GFLOP/s",
            "runs",
            "max |diff|",
        ]
        .map(String::from)
        .to_vec(),
        rows: results
            .measurements
            .iter()
            .map(|m| {
                vec![
                    m.case.clone(),
                    m.method.label(),
                    m.tiles.to_string(),
                    passes(&m.product_passes),
                    ms(m.times_ms.texture_creation),
                    ms(m.times_ms.matmul),
                    ms(m.times_ms.activation),
                    ms(m.total_ms),
                    format!("{:.2}", m.matmul_gflops),
                    format!("{:.2}", m.best_matmul_gflops),
                    m.runs.to_string(),
                    format!("{:.1e}", m.max_abs_diff_vs_cpu_plain),
                ]
            })
            .collect(),
    }
}

/// GFLOP/s of the detector's product against the batch size, the four methods.
pub fn figure(opts: &BenchOptions, results: &Paper3Results) -> anyhow::Result<Figure> {
    let file = "paper3_gflops.png";
    let series = Method::ALL
        .iter()
        .map(|&method| {
            let points = results
                .measurements
                .iter()
                .filter(|m| m.method == method && m.layers.len() == 2)
                .map(|m| (m.vectors as f64, m.matmul_gflops))
                .collect();
            Series::new(method.label(), points)
        })
        .collect();
    Plot {
        title: format!(
            "121-30-1 text detector: matrix product throughput ({})",
            opts.gl.info().renderer
        ),
        x_label: "input vectors L".into(),
        y_label: "GFLOP/s (median run)".into(),
        log_x: true,
        log_y: true,
        series,
    }
    .write_png(&opts.out_dir.join(file))?;
    Ok(Figure {
        file: file.into(),
        caption: "Matrix product GFLOP/s of the detector network against the batch size L, GPU \
                  passes (faithful in one pass and split as the paper's board required, packed) \
                  and CPU baselines (plain loop, sgemm), one run"
            .into(),
    })
}
