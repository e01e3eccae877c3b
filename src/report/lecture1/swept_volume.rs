//! Swept volumes in the report: where the time goes (primitives, the GPU distance field's
//! passes and readback, the flood fill, marching tetrahedra) and how the volume's error against the
//! exact swept volume falls with the resolution, for a cube translated by 1.5 (exact volume
//! 2.5: a convex polytope under translation sweeps its hull with its moved copy).

use super::{Block, Setting};
use crate::lecture1::swept_volume::path::{Keyframe, Path3};
use crate::lecture1::swept_volume::{sweep, Options, SweepTimings};
use crate::mesh::generate::cube;
use crate::report::plot::{Plot, Series};
use crate::report::timing::Load;
use crate::report::{Figure, Table};
use serde::Serialize;

/// The exact volume of the unit cube's sweep along (1.5, 0, 0).
const EXACT: f64 = 2.5;

/// One resolution.
#[derive(Clone, Debug, Serialize)]
pub struct SweepRow {
    pub resolution: usize,
    pub volume: f64,
    pub relative_error: f64,
    /// `None` when the surface is not a closed 2-manifold.
    pub euler_characteristic: Option<i64>,
    pub watertight: bool,
    pub timings: SweepTimings,
}

/// The swept-volume block: a table of the time by stage and the error, and a plot of the
/// error against the resolution.
pub fn block(setting: &Setting) -> anyhow::Result<Block> {
    let ctx = setting.opts.gl;
    let bar = setting.stage("swept volumes");
    let frame = |x: f64| Keyframe {
        translation: [x, 0.0, 0.0],
        rotation: [1.0, 0.0, 0.0, 0.0],
    };
    let path = Path3::new(&[frame(0.0), frame(1.5)])?;
    let model = cube(1.0);
    let resolutions: &[usize] = if setting.opts.quick {
        &[16, 24, 32]
    } else {
        &[16, 24, 32, 48, 64]
    };
    let mut rows = Vec::new();
    for &n in resolutions {
        let options = Options {
            resolution: n,
            poses: 2,
            epsilon: None,
        };
        let swept = sweep(ctx, &model, &path, options)?;
        rows.push(SweepRow {
            resolution: n,
            volume: swept.surface.volume,
            relative_error: (swept.surface.volume - EXACT).abs() / EXACT,
            euler_characteristic: swept.surface.topology.euler_characteristic,
            watertight: swept.surface.watertight(),
            timings: swept.timings,
        });
    }
    let load = Load::now();
    bar.finish_and_clear();
    let table = Table {
        caption: format!(
            "Swept volume of a unit cube translated by 1.5 (exact volume {EXACT}) on {}: \
             where the time goes (ms; field passes by GL timer queries, the rest wall clock; \
             one run each, {}) and the volume's error",
            setting.renderer,
            load.map_or("load average unknown".to_string(), |l| l.in_words())
        ),
        header: [
            "N",
            "primitives",
            "field passes",
            "field readback",
            "flood fill",
            "marching tetrahedra",
            "volume",
            "relative error",
            "V - E + F",
        ]
        .map(String::from)
        .to_vec(),
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    r.resolution.to_string(),
                    format!("{:.2}", r.timings.primitives_ms),
                    format!("{:.2}", r.timings.field.passes_ms),
                    format!("{:.2}", r.timings.field.readback_ms),
                    format!("{:.2}", r.timings.classify_ms),
                    format!("{:.2}", r.timings.extract_ms),
                    format!("{:.4}", r.volume),
                    format!("{:.2e}", r.relative_error),
                    r.euler_characteristic
                        .map_or("not a manifold".into(), |chi| chi.to_string()),
                ]
            })
            .collect(),
    };
    let file = "lecture1_swept_volume_error.png";
    Plot {
        title: "Swept volume: error against the exact volume".into(),
        x_label: "N (voxels per axis)".into(),
        y_label: "|V - V_exact| / V_exact".into(),
        log_x: true,
        log_y: true,
        series: vec![Series::new(
            "cube translated by 1.5",
            rows.iter()
                .map(|r| (r.resolution as f64, r.relative_error.max(1e-9)))
                .collect(),
        )],
    }
    .write_png(&setting.opts.out_dir.join(file))?;
    Ok(Block {
        id: "swept-volume".into(),
        results: serde_json::to_value(&rows)?,
        load,
        summary: "Swept volumes (a reconstruction of Kim et al. 2003): ruled quads and posed \
                  faces, their distance field on the GPU, a flood fill from the border and \
                  marching tetrahedra (a closed 2-manifold); the volume approaches the exact one as the grid is refined."
            .into(),
        tables: vec![table],
        figures: vec![Figure {
            file: file.into(),
            caption: "Swept volume: relative volume error against N (marching tetrahedra round \
                      the sharp edges off, about a voxel's square per unit of edge length)"
                .into(),
        }],
        ..Block::default()
    })
}
