//! Fig. 4: relative error of mass and the three diagonal moments against resolution.

use super::bench::Paper4Results;
use crate::page::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};

/// Fig. 4's quantities, in the order of [`super::bench::RelativeErrors::all`].
const QUANTITIES: [&str; 4] = ["mass", "Ixx", "Iyy", "Izz"];

pub fn table(results: &Paper4Results) -> Table {
    let mut table = Table {
        caption: "Fig. 4: relative error against Mirtich's analytic result (%)".into(),
        header: ["object", "resolution"]
            .into_iter()
            .chain(QUANTITIES)
            .map(String::from)
            .collect(),
        rows: Vec::new(),
    };
    for o in &results.objects {
        for r in &o.resolutions {
            let n = r.resolution;
            table.rows.push(
                [o.object.clone(), format!("{n}x{n}")]
                    .into_iter()
                    .chain(
                        r.relative_error
                            .all()
                            .iter()
                            .map(|v| format!("{:.3}", 100.0 * v)),
                    )
                    .collect(),
            );
        }
    }
    table
}

/// fp32's relative resolution (its machine epsilon): a smaller relative error means the GPU's
/// fp32 sum is the exact value rounded.
const FP32_RESOLUTION: f64 = f32::EPSILON as f64;

/// An error as Fig. 4 draws it: 0 where it is below [`FP32_RESOLUTION`] (an f64 difference of
/// 1e-17 would stretch the log axis over sixteen decades that hold no data).
fn shown_error(e: f64) -> f64 {
    if e.abs() < FP32_RESOLUTION {
        0.0
    } else {
        e
    }
}

/// One log-log plot per quantity.
pub fn figures(opts: &BenchOptions, results: &Paper4Results) -> anyhow::Result<Vec<Figure>> {
    let mut figures = Vec::new();
    for (k, quantity) in QUANTITIES.iter().enumerate() {
        let plot = Plot {
            title: format!("Fig. 4: relative error of {quantity}"),
            x_label: "resolution (pixels per side)".into(),
            y_label: "relative error".into(),
            log_x: true,
            log_y: true,
            series: results
                .objects
                .iter()
                .map(|o| {
                    Series::new(
                        &o.object,
                        o.resolutions
                            .iter()
                            .map(|r| (r.resolution as f64, shown_error(r.relative_error.all()[k])))
                            .collect(),
                    )
                })
                .chain([Series::reference("5% (the paper's bound)", 0.05)])
                .collect(),
        };
        let file = format!("fig4_{}.png", quantity.to_lowercase());
        plot.write_png(&opts.out_dir.join(&file))?;
        figures.push(Figure {
            file,
            caption: format!(
                "Fig. 4: relative error of {quantity} against resolution, each object; the \
                 dashed line is 5%, the error the paper's claim is about; an error below fp32's \
                 resolution ({FP32_RESOLUTION:.1e}: the GPU's fp32 sum is the exact value \
                 rounded, as for the cube) is drawn as 0, a hollow mark on the floor, so that \
                 the axis spans the errors that resolution makes (the table gives every value)"
            ),
        });
    }
    Ok(figures)
}
