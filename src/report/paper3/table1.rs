//! Table 1: processing time per elementary operation, the four methods beside the paper's
//! GPU and CPU columns.

use super::bench::{Measurement, Method, Paper3Results};
use crate::report::published::Paper3Table1;
use crate::report::Table;

pub fn ms(v: f64) -> String {
    format!("{v:.3}")
}

pub fn table(results: &Paper3Results, paper: &Paper3Table1) -> Table {
    let rows: Vec<&Measurement> = Method::ALL.iter().map(|&m| results.paper_row(m)).collect();
    let line = |op: &str, paper_gpu: String, paper_cpu: String, value: fn(&Measurement) -> f64| {
        [op.to_string(), paper_gpu, paper_cpu]
            .into_iter()
            .chain(rows.iter().map(|m| ms(value(m))))
            .collect()
    };
    let na = || "-".to_string();
    let paper_gpu_total =
        paper.gpu_texture_creation + paper.gpu_matrix_multiplication + paper.gpu_sigmoid;
    Table {
        caption: format!(
            "Table 1 beside the paper: processing times per elementary operation, {} \
             (paper: ATI RADEON 9700 PRO, unit not stated; here: ms on {})",
            rows[0].case, results.renderer
        ),
        header: ["operation", "paper GPU", "paper CPU"]
            .into_iter()
            .map(String::from)
            .chain(Method::ALL.iter().map(|m| column(*m).to_string()))
            .collect(),
        rows: vec![
            line(
                "texture creation",
                paper.gpu_texture_creation.to_string(),
                na(),
                |m| m.times_ms.texture_creation,
            ),
            line(
                "matrix multiplication",
                paper.gpu_matrix_multiplication.to_string(),
                paper.cpu_matrix_multiplication.to_string(),
                |m| m.times_ms.matmul,
            ),
            line("sigmoid", paper.gpu_sigmoid.to_string(), na(), |m| {
                m.times_ms.activation
            }),
            line("readback", na(), na(), |m| m.times_ms.readback),
            [
                "product passes per layer".to_string(),
                "not stated".to_string(),
                na(),
            ]
            .into_iter()
            .chain(rows.iter().map(|m| passes(&m.product_passes)))
            .collect(),
            line(
                "total",
                format!("{paper_gpu_total:.3}"),
                paper.cpu_matrix_multiplication.to_string(),
                |m| m.total_ms,
            ),
        ],
    }
}

/// "9 + 2": the product passes of each layer, "-" on the CPU.
pub fn passes(per_layer: &[usize]) -> String {
    if per_layer.is_empty() {
        return "-".into();
    }
    let counts: Vec<String> = per_layer.iter().map(usize::to_string).collect();
    counts.join(" + ")
}

/// The short column heading of a method.
fn column(method: Method) -> &'static str {
    match method {
        Method::GpuFaithful => "GPU faithful",
        Method::GpuMultiPass => "GPU multi-pass",
        Method::GpuPacked => "GPU packed",
        Method::CpuPlain => "CPU plain",
        Method::CpuOptimised => "CPU sgemm",
    }
}
