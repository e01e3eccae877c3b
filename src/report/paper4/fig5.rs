//! Fig. 5: the GPU path's time against resolution, beside Mirtich's analytic method.

use super::bench::Paper4Results;
use crate::page::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};

pub fn table(results: &Paper4Results) -> Table {
    let mut table = Table {
        caption: format!(
            "Fig. 5: time (ms) against resolution, on {}",
            results.renderer
        ),
        header: [
            "object",
            "resolution",
            "GPU (timer query)",
            "GPU (wall)",
            "analytic (CPU)",
            "GPU / analytic",
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    for o in &results.objects {
        for r in &o.resolutions {
            let n = r.resolution;
            table.rows.push(vec![
                o.object.clone(),
                format!("{n}x{n}"),
                format!("{:.3}", r.gpu_ms),
                format!("{:.3}", r.gpu_wall_ms),
                format!("{:.3}", o.analytic_ms),
                format!("{:.1}", r.gpu_wall_ms / o.analytic_ms),
            ]);
        }
    }
    table
}

/// GPU wall time per object (log-log), with the analytic time as a flat line.
pub fn figure(opts: &BenchOptions, results: &Paper4Results) -> anyhow::Result<Figure> {
    let objects = &results.objects;
    let mut series: Vec<Series> = objects
        .iter()
        .enumerate()
        .map(|(k, o)| {
            Series::new(
                format!("{}: GPU", o.object),
                o.resolutions
                    .iter()
                    .map(|r| (r.resolution as f64, r.gpu_wall_ms))
                    .collect(),
            )
            .slot(k)
        })
        .collect();
    for (k, o) in objects.iter().enumerate() {
        let (lo, hi) = (
            o.resolutions.first().map_or(8, |r| r.resolution),
            o.resolutions.last().map_or(512, |r| r.resolution),
        );
        series.push(
            Series::new(
                format!("{}: analytic (dashed)", o.object),
                vec![(lo as f64, o.analytic_ms), (hi as f64, o.analytic_ms)],
            )
            .slot(k)
            .dashed(),
        );
    }
    let file = "fig5_time.png";
    Plot {
        title: format!(
            "Fig. 5: time against resolution ({})",
            opts.gl.info().renderer
        ),
        x_label: "resolution (pixels per side)".into(),
        y_label: "milliseconds (wall clock)".into(),
        log_x: true,
        log_y: true,
        series,
    }
    .write_png(&opts.out_dir.join(file))?;
    Ok(Figure {
        file: file.into(),
        caption: "Fig. 5: GPU path (wall clock per call, solid lines with markers) against \
                  resolution; flat dashed lines of the same colour: Mirtich's analytic method \
                  on the same object"
            .into(),
    })
}
