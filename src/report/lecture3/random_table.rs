//! Technique 5: the per-texel generator against the CPU's, its tests, its speed.

use super::images::RANDOM_PNG;
use super::results::Lecture3Results;
use crate::page::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};

pub fn table(results: &Lecture3Results) -> Table {
    let r = &results.random;
    let n = (r.side * r.side) as f64;
    Table {
        caption: format!(
            "5. Random numbers into a texture: {0}x{0} hybrid Tausworthe generators, {1} steps, \
             on {2}; tests at the 0.1% level",
            r.side, r.steps, results.renderer
        ),
        header: ["measure", "value", "limit / reference"]
            .map(String::from)
            .to_vec(),
        rows: vec![
            vec![
                "equal to the CPU generator, bit for bit".into(),
                if r.bit_exact { "yes" } else { "NO" }.into(),
                "every state and number of every step".into(),
            ],
            vec![
                "chi-square, 64 bins".into(),
                format!("{:.1}", r.chi_square),
                format!("< {:.1}", r.chi_square_critical),
            ],
            vec![
                "serial correlation (each texel's successive numbers)".into(),
                format!("{:.2e}", r.serial_correlation),
                format!("|r| < {:.2e}", r.correlation_bound),
            ],
            vec![
                "neighbour correlation (adjacent texels, same step)".into(),
                format!("{:.2e}", r.neighbour_correlation),
                format!("|r| < {:.2e}", r.correlation_bound),
            ],
            vec![
                "GPU ms per step (one pass)".into(),
                format!("{:.3}", r.gpu_ms_per_step),
                format!("{:.0} M numbers/s", n / r.gpu_ms_per_step / 1e3),
            ],
            vec![
                "CPU ms per step (same generators)".into(),
                format!("{:.3}", r.cpu_ms_per_step),
                format!("CPU / GPU {:.2}", r.cpu_ms_per_step / r.gpu_ms_per_step),
            ],
        ],
    }
}

pub fn figures(opts: &BenchOptions, results: &Lecture3Results) -> anyhow::Result<Vec<Figure>> {
    let r = &results.random;
    let expected = (r.side * r.side) as f64 / r.histogram.len() as f64;
    let file = "lecture3_random_histogram.png";
    let bins = r.histogram.len() as f64;
    Plot {
        title: format!(
            "5. The last step's numbers in 64 bins ({})",
            results.renderer_name
        ),
        x_label: "value".into(),
        y_label: "count".into(),
        log_x: false,
        log_y: false,
        series: vec![
            Series::new(
                "counted by additive blending (technique 7)",
                r.histogram
                    .iter()
                    .enumerate()
                    .map(|(i, &c)| ((i as f64 + 0.5) / bins, c as f64))
                    .collect(),
            ),
            Series::new("expected", vec![(0.0, expected), (1.0, expected)]),
        ],
    }
    .write_png(&opts.out_dir.join(file))?;
    Ok(vec![
        Figure {
            file: RANDOM_PNG.into(),
            caption: "5. The numbers of the last step, one per texel".into(),
        },
        Figure {
            file: file.into(),
            caption: "5. Their histogram, drawn by technique 7".into(),
        },
    ])
}
