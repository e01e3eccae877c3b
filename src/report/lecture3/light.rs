//! Technique 3: error against speed of the hierarchical search, over the criterion theta.

use super::images::LIGHT_PNG;
use super::results::Lecture3Results;
use crate::page::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};

pub fn table(results: &Lecture3Results) -> Table {
    let l = &results.light;
    let mut rows = vec![vec![
        "brute force".to_string(),
        "0".into(),
        l.vpls.to_string(),
        format!("{:.2}", l.brute_gpu_ms),
        format!("{:.1}", l.brute_cpu_ms / l.brute_gpu_ms),
    ]];
    rows.extend(l.rows.iter().map(|r| {
        vec![
            format!("tree, theta {}", r.theta),
            format!("{:.2e}", r.relative_rms_error),
            format!("{:.1}", r.mean_nodes),
            format!("{:.2}", r.gpu_ms),
            format!("{:.1}", l.brute_cpu_ms / r.gpu_ms),
        ]
    }));
    Table {
        caption: format!(
            "3. Indirect light from {} VPLs ({1}x{1} image) at {2}x{3} receivers: relative RMS \
             error against the brute-force sum, nodes visited per receiver, GPU time, on {4}; \
             CPU brute force (f64, on {9} cores) {5:.0} ms, GPU brute force within {6:.1e} \
             of it; hierarchy built in {7:.2} ms{8}",
            l.vpls,
            l.vpl_side,
            l.image.0,
            l.image.1,
            results.renderer,
            l.brute_cpu_ms,
            l.brute_gpu_vs_cpu,
            l.build_ms,
            once(l),
            l.brute_cpu_threads
        ),
        header: [
            "gather",
            "relative RMS error",
            "VPLs or nodes visited per receiver",
            "GPU (ms)",
            "CPU brute force / this",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

/// The criteria timed once ([`super::bench::theta_runs`]: theta 0, the check against the
/// brute force), said in the caption when others ran more.
fn once(l: &super::results::LightRun) -> String {
    let once: Vec<String> = l
        .rows
        .iter()
        .filter(|r| r.gpu_spread.runs == 1)
        .map(|r| r.theta.to_string())
        .collect();
    if once.is_empty() || l.rows.iter().all(|r| r.gpu_spread.runs == 1) {
        return String::new();
    }
    format!(
        "; theta {} timed once: it opens every cluster, a check of the tree against the brute \
         force, and no claim takes its time",
        once.join(", ")
    )
}

pub fn figures(opts: &BenchOptions, results: &Lecture3Results) -> anyhow::Result<Vec<Figure>> {
    let l = &results.light;
    let error_file = "lecture3_light_error.png";
    Plot {
        title: format!("3. Error against the criterion ({})", results.renderer_name),
        x_label: "theta (cluster radius / distance)".into(),
        y_label: "relative RMS error".into(),
        log_x: false,
        log_y: true,
        series: vec![Series::new(
            "tree search",
            l.rows
                .iter()
                .filter(|r| r.theta > 0.0)
                .map(|r| (r.theta as f64, r.relative_rms_error))
                .collect(),
        )],
    }
    .write_png(&opts.out_dir.join(error_file))?;
    let time_file = "lecture3_light_time.png";
    let (lo, hi) = (
        l.rows.first().map_or(0.0, |r| r.theta as f64),
        l.rows.last().map_or(1.0, |r| r.theta as f64),
    );
    Plot {
        title: format!(
            "3. GPU time against the criterion ({})",
            results.renderer_name
        ),
        x_label: "theta (cluster radius / distance)".into(),
        y_label: format!("milliseconds ({})", results.gpu_timing),
        log_x: false,
        log_y: true,
        series: vec![
            Series::new(
                "tree search",
                l.rows.iter().map(|r| (r.theta as f64, r.gpu_ms)).collect(),
            ),
            Series::new(
                "brute force",
                vec![(lo, l.brute_gpu_ms), (hi, l.brute_gpu_ms)],
            ),
        ],
    }
    .write_png(&opts.out_dir.join(time_file))?;
    Ok(vec![
        Figure {
            file: error_file.into(),
            caption: "3. Relative RMS error of the tree search against the brute-force sum".into(),
        },
        Figure {
            file: time_file.into(),
            caption: "3. GPU time of the gather against theta, beside the brute force".into(),
        },
        Figure {
            file: LIGHT_PNG.into(),
            caption: format!(
                "3. The room: direct + indirect light (brute force), indirect alone (brute \
                 force), indirect alone with theta {}",
                super::scene::THETAS.last().expect("criteria")
            ),
        },
    ])
}
