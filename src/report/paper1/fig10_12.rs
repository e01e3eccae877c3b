//! Fig. 10-12: streaming against SOLID's CPU refit (Fig. 10 for the tori, Fig. 11 for the
//! other scenes; Sec. 7.4.1) and against CULLIDE (Fig. 12, Sec. 7.4.2), as per-scene numbers
//! and per-frame plots.

use super::bench::{FrameTimes, Paper1Results, SceneRun};
use super::{f2, header};
use crate::collide::scenes::SCENES;
use crate::page::plot::{Plot, Series};
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

/// Which of the paper's figures shows `run` and its panel: benchmark set I (the tori) is
/// Fig. 10 (a)-(c), set II Fig. 11 (a)-(c).
pub fn solid_figure_of(run: &SceneRun) -> (u32, char) {
    let i = SCENES.iter().position(|&s| s == run.name).unwrap_or(0);
    let panel = |k: usize| (b'a' + k as u8) as char;
    if i < 3 {
        (10, panel(i))
    } else {
        (11, panel(i - 3))
    }
}

/// One curve per frame of `f`.
fn per_frame(run: &SceneRun, f: impl Fn(&FrameTimes) -> f64) -> Vec<(f64, f64)> {
    run.frame_times
        .iter()
        .enumerate()
        .map(|(i, t)| (i as f64 + 1.0, f(t)))
        .collect()
}

/// Fig. 10-11 the paper's way: culling and update without the triangle test (both methods
/// run the same one), the streaming texture download apart.
pub fn solid_series(run: &SceneRun) -> Vec<Series> {
    vec![
        Series::new(
            "streaming: overlap + readback + update",
            per_frame(run, |t| t.stream_cull),
        ),
        Series::new(
            "streaming: texture download",
            per_frame(run, |t| t.stream_download),
        ),
        Series::new("SOLID: refit + traversal", per_frame(run, |t| t.solid_cull)),
    ]
}

/// Fig. 12: all intersecting triangles, whole frames.
pub fn cullide_series(run: &SceneRun) -> Vec<Series> {
    vec![
        Series::new(
            "streaming AABBs (whole frame)",
            per_frame(run, |t| t.stream_total),
        ),
        Series::new(
            "CULLIDE (pruning + triangle test)",
            per_frame(run, |t| t.cullide_total),
        ),
    ]
}

/// Fig. 10 or 11, and Fig. 12, for one scene: time per frame over the animation.
pub fn figures(opts: &BenchOptions, run: &SceneRun) -> anyhow::Result<Vec<Figure>> {
    let renderer = &opts.gl.info().renderer;
    let (number, panel) = solid_figure_of(run);
    // Titles name the scene without its stand-in note (the caption has it), so they fit.
    let scene = run.label.split(" (").next().unwrap_or(&run.label);
    let plot = |title: String, series: Vec<Series>, file: &str| {
        Plot {
            title,
            x_label: "frame".into(),
            y_label: "ms per frame".into(),
            log_x: false,
            log_y: true,
            series,
        }
        .write_png(&opts.out_dir.join(file))
    };
    let solid_file = format!("paper1_fig{number}_{}.png", run.name);
    plot(
        format!("Fig. {number}({panel}): {scene} vs SOLID ({renderer})"),
        solid_series(run),
        &solid_file,
    )?;
    let cullide_file = format!("paper1_fig12_{}.png", run.name);
    plot(
        format!("Fig. 12: {scene} vs CULLIDE ({renderer})"),
        cullide_series(run),
        &cullide_file,
    )?;
    Ok(vec![
        Figure {
            file: solid_file,
            caption: format!(
                "Fig. {number}({panel}): {}, streaming culling + update against SOLID's refit +                  traversal per frame, the triangle test left out (both run the same one) and the                  streaming texture download shown apart, as in the paper",
                run.label
            ),
        },
        Figure {
            file: cullide_file,
            caption: format!(
                "Fig. 12: {}, whole frames (every intersecting triangle pair) of streaming                  against CULLIDE",
                run.label
            ),
        },
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(name: &str) -> SceneRun {
        let frame = FrameTimes {
            stream_cull: 1.0,
            stream_download: 2.0,
            stream_tri_test: 30.0,
            stream_total: 33.5,
            solid_cull: 4.0,
            solid_tri_test: 30.0,
            cullide_total: 90.0,
        };
        SceneRun {
            name: name.into(),
            frame_times: vec![frame, frame],
            ..SceneRun::default()
        }
    }

    #[test]
    fn fig10_11_leave_out_the_triangle_test_and_show_the_download_apart() {
        let series = solid_series(&run("touching-tori"));
        let last = |k: usize| series[k].points.last().map(|p| p.1);
        assert_eq!(series.len(), 3);
        assert_eq!(
            last(0),
            Some(1.0),
            "streaming culling, no download, no triangle test"
        );
        assert_eq!(last(1), Some(2.0), "the download, apart");
        assert_eq!(last(2), Some(4.0), "SOLID without its triangle test");
        assert_eq!(series[0].points.len(), 2);
    }

    #[test]
    fn fig12_compares_whole_frames() {
        let series = cullide_series(&run("bump-bunnies"));
        assert_eq!(series[0].points[0].1, 33.5);
        assert_eq!(series[1].points[0].1, 90.0);
    }

    #[test]
    fn the_tori_are_fig10_and_the_other_scenes_fig11() {
        assert_eq!(solid_figure_of(&run("interlocking-tori")), (10, 'a'));
        assert_eq!(solid_figure_of(&run("merging-tori")), (10, 'c'));
        assert_eq!(solid_figure_of(&run("bump-bunnies")), (11, 'a'));
        assert_eq!(solid_figure_of(&run("intimate-animals")), (11, 'c'));
    }
}
