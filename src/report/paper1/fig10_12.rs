//! Fig. 10-12: streaming against SOLID's CPU refit (Fig. 10-11, Sec. 7.4.1) and against
//! CULLIDE (Fig. 12, Sec. 7.4.2), as per-scene numbers and per-frame plots.

use super::bench::{Paper1Results, SceneRun};
use super::{f2, header};
use crate::report::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};

/// SOLID / streaming culling time, without and with the texture download (Fig. 10-11).
pub fn solid_ratios(run: &SceneRun) -> (f64, f64) {
    let cull = run.stream_cull_ms();
    let solid = run.solid_cull_ms();
    (solid / cull, solid / (cull + run.stream.timings.download))
}

/// CULLIDE / streaming time of a whole frame (Fig. 12).
pub fn cullide_ratio(run: &SceneRun) -> f64 {
    run.cullide_total_ms() / run.stream.timings.total
}

pub fn table(results: &Paper1Results) -> Table {
    let rows = results
        .scenes
        .iter()
        .map(|r| {
            let t = &r.stream.timings;
            let cull = r.stream_cull_ms();
            let (without, with) = solid_ratios(r);
            vec![
                r.label.clone(),
                f2(cull),
                f2(cull + t.download),
                f2(r.solid_cull_ms()),
                f2(without),
                f2(with),
                f2(t.total),
                f2(r.solid_cull_ms() + r.solid_tri),
                f2(r.cullide_total_ms()),
                f2(cullide_ratio(r)),
                format!("{}/{}", r.solid_agrees, r.frames),
            ]
        })
        .collect();
    Table {
        caption: format!(
            "Fig. 10-12: ms per frame ({}). Culling = streaming overlap + readback + update (+ \
             download) vs SOLID refit + traversal; totals include the triangle test",
            results.renderer
        ),
        header: header(&[
            "scene",
            "stream cull",
            "stream cull+download",
            "SOLID refit+traverse",
            "SOLID / stream (no download)",
            "SOLID / stream (with download)",
            "stream total",
            "SOLID total",
            "CULLIDE total",
            "CULLIDE / stream",
            "SOLID = exact",
        ]),
        rows,
    }
}

/// Time per frame over the animation: streaming, SOLID and CULLIDE.
pub fn figure(opts: &BenchOptions, run: &SceneRun) -> anyhow::Result<Figure> {
    let file = format!("paper1_fig10-12_{}.png", run.name);
    let frames = |v: &[f64]| {
        v.iter()
            .enumerate()
            .map(|(i, &t)| (i as f64 + 1.0, t))
            .collect()
    };
    Plot {
        title: format!("{} ({})", run.label, opts.gl.info().renderer),
        x_label: "frame".into(),
        y_label: "ms per frame".into(),
        log_x: false,
        log_y: true,
        series: vec![
            Series::new("streaming AABBs", frames(&run.series[0])),
            Series::new("SOLID", frames(&run.series[1])),
            Series::new("CULLIDE", frames(&run.series[2])),
        ],
    }
    .write_png(&opts.out_dir.join(&file))?;
    Ok(Figure {
        file,
        caption: format!(
            "Fig. 10-12: time per frame over the animation, {} (streaming vs SOLID vs CULLIDE)",
            run.label
        ),
    })
}
