//! The figure: wall clock of both ways, by size.

use super::bench::BlocksResults;
use crate::page::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure};

pub fn figure(opts: &BenchOptions, results: &BlocksResults) -> anyhow::Result<Figure> {
    let file = "blocks_reduction.png";
    let runs = &results.reduction;
    Plot {
        title: format!(
            "Sum reduction vs full readback ({})",
            opts.gl.info().renderer
        ),
        x_label: "n (n x n RGBA32F texels)".into(),
        y_label: "wall clock ms".into(),
        log_x: true,
        log_y: true,
        series: vec![
            Series::new(
                "ping-pong reduction",
                runs.iter()
                    .map(|r| (r.size as f64, r.reduce_wall_ms))
                    .collect(),
            ),
            Series::new(
                "readback + CPU sum",
                runs.iter()
                    .map(|r| (r.size as f64, r.readback_wall_ms))
                    .collect(),
            ),
        ],
    }
    .write_png(&opts.out_dir.join(file))?;
    Ok(Figure {
        file: file.into(),
        caption: "Wall clock of the two ways to sum a buffer, by size".into(),
    })
}
