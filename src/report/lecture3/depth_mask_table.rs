//! Technique 6: the branching shader against the depth-masked one, over the share of active
//! pixels, for coherent and scattered masks.

use super::images::DEPTH_MASK_PNG;
use super::results::Lecture3Results;
use crate::lecture3::depth_mask::MaskShape;
use crate::page::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};

fn shape_name(shape: MaskShape) -> &'static str {
    match shape {
        MaskShape::Blobs => "blobs",
        MaskShape::Scattered => "scattered",
    }
}

pub fn table(results: &Lecture3Results) -> Table {
    let d = &results.depth_mask;
    Table {
        caption: format!(
            "6. An if removed with the depth buffer: {0}x{0} pixels, {1} sines per active pixel, \
             on {2}; shader runs counted by {3}; fragments passing the depth test counted by an \
             occlusion query",
            d.side,
            d.iterations,
            results.renderer,
            d.rows
                .first()
                .map_or_else(|| "nothing".into(), |r| r.counted_by.describe())
        ),
        header: [
            "mask",
            "active",
            "pixels active (CPU)",
            "2x2 quads active (CPU)",
            "shader runs, depth-masked",
            "shader runs, unmasked",
            "invocations by pipeline statistics, depth-masked",
            "fragments passing, depth-masked",
            "fragments, branching",
            "branching (ms)",
            "depth-masked (ms)",
            "branching / masked",
            "max |GPU - CPU|",
        ]
        .map(String::from)
        .to_vec(),
        rows: d
            .rows
            .iter()
            .map(|r| {
                vec![
                    shape_name(r.mask).into(),
                    format!("{:.0}%", 100.0 * r.fraction),
                    r.active.to_string(),
                    r.active_quads.to_string(),
                    r.masked_runs
                        .map_or_else(|| "not counted".into(), |n| n.to_string()),
                    r.unmasked_runs
                        .map_or_else(|| "not counted".into(), |n| n.to_string()),
                    r.masked_invocations
                        .map_or_else(|| "no query".into(), |n| n.to_string()),
                    r.masked_fragments.to_string(),
                    r.branching_fragments.to_string(),
                    format!("{:.2}", r.branching_ms),
                    format!("{:.2}", r.masked_ms),
                    format!("{:.2}", r.branching_ms / r.masked_ms),
                    format!("{:.1e}", r.max_error),
                ]
            })
            .collect(),
    }
}

pub fn figures(opts: &BenchOptions, results: &Lecture3Results) -> anyhow::Result<Vec<Figure>> {
    let d = &results.depth_mask;
    let mut series = Vec::new();
    for shape in [MaskShape::Blobs, MaskShape::Scattered] {
        let rows: Vec<_> = d.rows.iter().filter(|r| r.mask == shape).collect();
        series.push(Series::new(
            format!("branching, {}", shape_name(shape)),
            rows.iter()
                .map(|r| (r.fraction as f64, r.branching_ms))
                .collect(),
        ));
        series.push(Series::new(
            format!("depth-masked, {}", shape_name(shape)),
            rows.iter()
                .map(|r| (r.fraction as f64, r.masked_ms))
                .collect(),
        ));
    }
    let file = "lecture3_depth_mask_time.png";
    Plot {
        title: format!(
            "6. GPU time against active pixels ({})",
            results.renderer_name
        ),
        x_label: "share of active pixels".into(),
        y_label: format!("milliseconds ({})", results.gpu_timing),
        log_x: false,
        log_y: false,
        series,
    }
    .write_png(&opts.out_dir.join(file))?;
    Ok(vec![
        Figure {
            file: file.into(),
            caption: "6. The branching shader against the depth-masked passes".into(),
        },
        Figure {
            file: DEPTH_MASK_PNG.into(),
            caption: "6. The depth-masked passes on the coherent mask, 25% active: the active \
                      pixels (left), the picture the expensive shader drew where the depth test \
                      let it run (middle; grey, 0, wherever the mask is off) and its \
                      difference to the CPU's picture (right: fp32 rounding only). Look for the \
                      middle picture's pattern exactly inside the left one's blobs."
                .into(),
        },
    ])
}
