//! Penetration depth by rasterized Minkowski sums (a reconstruction of Kim, Otaduy, Lin &
//! Manocha 2002): the error of the rasterized upper bound, and of the refined depth, against
//! the exact depth, by cube resolution, for a convex pair and a union of convex pieces.

use crate::lecture1::penetration::scenes::{convex_pair, corner_pair, Scene};
use crate::lecture1::penetration::{Formulation, Options, PenetrationQuery};
use crate::page::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};
use serde::{Deserialize, Serialize};

/// One scene at one resolution.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ErrorRow {
    pub scene: String,
    pub resolution: usize,
    pub exact: f64,
    /// The smallest T over all pixels.
    pub upper_bound: f64,
    /// (upper bound - exact) / exact.
    pub bound_error: f64,
    /// |refined - exact| / exact.
    pub refined_error: f64,
    pub passes: usize,
    /// GPU time of the passes (timer queries), ms.
    pub gpu_ms: f64,
}

/// Every row, and the renderer they ran on.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PenetrationErrors {
    pub renderer: String,
    pub rows: Vec<ErrorRow>,
}

/// Resolutions per cube face measured: 8 to 32 under `--quick`, 16 to 128 otherwise.
pub fn resolutions(quick: bool) -> Vec<usize> {
    if quick {
        vec![8, 16, 32]
    } else {
        vec![16, 32, 64, 128]
    }
}

/// Run the classic query on both scenes at every resolution.
pub fn measure(opts: &BenchOptions) -> anyhow::Result<PenetrationErrors> {
    let query = PenetrationQuery::new(opts.gl)?;
    let mut rows = Vec::new();
    for scene in [convex_pair(), corner_pair()] {
        let exact = scene.exact_depth()?;
        for n in resolutions(opts.quick) {
            rows.push(row(&query, &scene, exact, n)?);
        }
    }
    Ok(PenetrationErrors {
        renderer: opts.gl.info().renderer_line(),
        rows,
    })
}

fn row(query: &PenetrationQuery, scene: &Scene, exact: f64, n: usize) -> anyhow::Result<ErrorRow> {
    let r = query.run(
        &scene.a,
        &scene.b,
        &Options {
            resolution: n,
            formulation: Formulation::Classic,
            keep_exits: false,
        },
    )?;
    Ok(ErrorRow {
        scene: scene.name.into(),
        resolution: n,
        exact,
        upper_bound: r.upper_bound,
        bound_error: (r.upper_bound - exact) / exact,
        refined_error: (r.depth - exact).abs() / exact,
        passes: r.passes,
        gpu_ms: r.gpu_ms,
    })
}

/// The table: one row per scene and resolution.
pub fn table(r: &PenetrationErrors) -> Table {
    Table {
        caption: format!(
            "Penetration depth by rasterized Minkowski sums (a reconstruction): the rasterized \
             upper bound and the refined depth against the exact depth, by texels per cube \
             face, on {}",
            r.renderer
        ),
        header: [
            "models",
            "texels per face",
            "exact depth",
            "upper bound",
            "bound error (relative)",
            "refined error (relative)",
            "passes",
            "GPU ms",
        ]
        .map(String::from)
        .to_vec(),
        rows: r
            .rows
            .iter()
            .map(|row| {
                vec![
                    row.scene.clone(),
                    row.resolution.to_string(),
                    format!("{:.6}", row.exact),
                    format!("{:.6}", row.upper_bound),
                    format!("{:.2e}", row.bound_error),
                    format!("{:.1e}", row.refined_error),
                    row.passes.to_string(),
                    format!("{:.2}", row.gpu_ms),
                ]
            })
            .collect(),
    }
}

/// The plot of the bound's relative error against the resolution (log-log), one series per
/// scene, written to `lecture1_penetration_error.png`.
pub fn figure(opts: &BenchOptions, r: &PenetrationErrors) -> anyhow::Result<Figure> {
    let mut scenes: Vec<&str> = r.rows.iter().map(|row| row.scene.as_str()).collect();
    scenes.dedup();
    let series = scenes
        .iter()
        .map(|scene| {
            Series::new(
                format!("upper bound, {scene}"),
                r.rows
                    .iter()
                    .filter(|row| row.scene == *scene)
                    // A zero error has no place on a log axis: floor it at fp32's epsilon.
                    .map(|row| (row.resolution as f64, row.bound_error.max(1e-7)))
                    .collect(),
            )
        })
        .collect();
    let file = "lecture1_penetration_error.png";
    Plot {
        title: "Penetration depth: rasterized bound error by resolution".into(),
        x_label: "texels per cube face side".into(),
        y_label: "(upper bound - exact) / exact".into(),
        log_x: true,
        log_y: true,
        series,
    }
    .write_png(&opts.out_dir.join(file))?;
    Ok(Figure {
        file: file.into(),
        caption: "Penetration depth: the rasterized upper bound's relative error against the \
                  resolution (a face's nearest point: about 1/N²; a crease between sums: \
                  about 1/N)"
            .into(),
    })
}

/// Everything the section needs from this technique: measured rows (for the section's
/// results), the table and the figure.
pub fn report(opts: &BenchOptions) -> anyhow::Result<(PenetrationErrors, Table, Figure)> {
    let errors = measure(opts)?;
    let table = table(&errors);
    let figure = figure(opts, &errors)?;
    Ok((errors, table, figure))
}

/// The section's penetration-depth block: the error table and figure, what the rows say in
/// one sentence (its fidelity row is in `fidelity.rs`).
pub fn block(setting: &super::Setting) -> anyhow::Result<super::Block> {
    let bar = setting.stage("penetration depth");
    let (errors, table, figure) = report(setting.opts)?;
    bar.finish_and_clear();
    let worst = |f: fn(&ErrorRow) -> f64| errors.rows.iter().map(f).fold(0.0, f64::max);
    let finest = errors.rows.iter().map(|r| r.resolution).max().unwrap_or(0);
    let at_finest = |f: fn(&ErrorRow) -> f64| {
        let rows = errors.rows.iter().filter(|r| r.resolution == finest);
        rows.map(f).fold(0.0, f64::max)
    };
    let summary = format!(
        "Penetration depth (a reconstruction of Kim, Otaduy, Lin & Manocha 2002): the \
         rasterized upper bound is within {:.1}% of the exact depth at {finest} texels a cube \
         face ({:.1}% at the coarsest), and the refined depth within {:.1e} relative.",
        100.0 * at_finest(|r| r.bound_error),
        100.0 * worst(|r| r.bound_error),
        worst(|r| r.refined_error),
    );
    Ok(super::Block {
        id: String::new(),
        results: serde_json::to_value(&errors)?,
        load: crate::timing::Load::now(),
        summary,
        tables: vec![table],
        figures: vec![figure],
        claims: Vec::new(),
        fidelity: Vec::new(),
        checks_made: vec!["penetration vs exact depth"],
        paths: vec![super::paths::PENETRATION],
    })
}
