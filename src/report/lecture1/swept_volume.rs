//! Swept volumes in the report: where the time goes (primitives, the GPU distance field's
//! passes and readback, the flood fill, marching tetrahedra) and how the volume's error against the
//! exact swept volume falls with the resolution, for three motions whose swept volume is known
//! in closed form: a cube and a polyhedral sphere translated (a convex polytope under
//! translation sweeps its hull with its moved copy: its volume plus the path's length times
//! its shadow's area), and a cube turning a quarter turn about its centre (the cylinder its
//! corners' circle makes, pi / 2; the poses grow with the resolution, `K = N / 2 + 1`, since
//! K poses alone sweep the regular 4 (K - 1)-gon on that circle, short by `x^2 / 6` of it
//! with `x = pi / (2 (K - 1))`).

use super::{Block, Setting};
use crate::lecture1::swept_volume::path::{Keyframe, Path3};
use crate::lecture1::swept_volume::{sweep, Options, SweepTimings};
use crate::mesh::generate::{cube, uv_sphere};
use crate::mesh::Mesh;
use crate::page::plot::{Plot, Series};
use crate::report::{Figure, Table};
use crate::timing::Load;
use glam::DVec3;
use serde::Serialize;

/// One motion with its exact swept volume.
struct Case {
    name: &'static str,
    model: Mesh,
    path: Path3,
    /// K at resolution N.
    poses: fn(usize) -> usize,
    exact: f64,
}

/// The volume swept by the convex `mesh` translated by `v`: vol(P) + |v| area(shadow of P
/// along v), the shadow's area half the sum over the faces of |area vector . v/|v||.
fn convex_translation_volume(mesh: &Mesh, v: DVec3) -> f64 {
    let shadow: f64 = (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.triangle(t).map(|p| p.as_dvec3());
            0.25 * (b - a).cross(c - a).dot(v.normalize()).abs()
        })
        .sum();
    mesh.signed_volume() + v.length() * shadow
}

fn frame(translation: DVec3, rotation: glam::DQuat) -> Keyframe {
    Keyframe {
        translation: translation.to_array(),
        rotation: [rotation.w, rotation.x, rotation.y, rotation.z],
    }
}

fn cases() -> anyhow::Result<Vec<Case>> {
    let still = glam::DQuat::IDENTITY;
    let translated = |name, model: Mesh, v: DVec3| -> anyhow::Result<Case> {
        Ok(Case {
            name,
            exact: convex_translation_volume(&model, v),
            model,
            path: Path3::new(&[frame(DVec3::ZERO, still), frame(v, still)])?,
            poses: |_| 2,
        })
    };
    let quarter = glam::DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
    Ok(vec![
        translated(
            "cube translated by 1.5",
            cube(1.0),
            DVec3::new(1.5, 0.0, 0.0),
        )?,
        translated(
            "polyhedral sphere translated",
            uv_sphere(0.6, 16, 8),
            DVec3::new(0.9, -0.4, 0.3),
        )?,
        Case {
            name: "cube turning a quarter turn, N / 2 + 1 poses",
            model: cube(1.0),
            path: Path3::new(&[frame(DVec3::ZERO, still), frame(DVec3::ZERO, quarter)])?,
            poses: |n| n / 2 + 1,
            exact: std::f64::consts::FRAC_PI_2,
        },
    ])
}

/// One resolution of one case.
#[derive(Clone, Debug, Serialize)]
pub struct SweepRow {
    pub case: String,
    pub exact: f64,
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
    let resolutions: &[usize] = if setting.opts.quick {
        &[16, 24, 32]
    } else {
        &[16, 24, 32, 48, 64]
    };
    let cases = cases()?;
    let mut rows = Vec::new();
    for case in &cases {
        for &n in resolutions {
            let options = Options {
                resolution: n,
                poses: (case.poses)(n),
                epsilon: None,
            };
            let swept = sweep(ctx, &case.model, &case.path, options)?;
            rows.push(SweepRow {
                case: case.name.into(),
                exact: case.exact,
                resolution: n,
                volume: swept.surface.volume,
                relative_error: (swept.surface.volume - case.exact).abs() / case.exact,
                euler_characteristic: swept.surface.topology.euler_characteristic,
                watertight: swept.surface.watertight(),
                timings: swept.timings,
            });
        }
    }
    let load = Load::now();
    bar.finish_and_clear();
    let table = Table {
        caption: format!(
            "Swept volumes of three motions with known volumes (on {}): where the time goes \
             (ms; field passes by GL timer queries, the rest wall clock; one run each, {}) and \
             the volume's error",
            setting.renderer,
            load.map_or("load average unknown".to_string(), |l| l.in_words())
        ),
        header: [
            "motion",
            "exact volume",
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
                    r.case.clone(),
                    format!("{:.4}", r.exact),
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
        series: cases
            .iter()
            .map(|case| {
                Series::new(
                    case.name,
                    rows.iter()
                        .filter(|r| r.case == case.name)
                        .map(|r| (r.resolution as f64, r.relative_error))
                        .collect(),
                )
            })
            .collect(),
    }
    .write_png(&setting.opts.out_dir.join(file))?;
    let worst_at = |n: usize| {
        rows.iter()
            .filter(|r| r.resolution == n)
            .map(|r| r.relative_error)
            .fold(0.0, f64::max)
    };
    Ok(Block {
        id: "swept-volume".into(),
        results: serde_json::to_value(&rows)?,
        load,
        checks_made: vec!["swept volume vs closed form"],
        paths: vec![super::paths::SWEPT_VOLUME],
        summary: format!(
            "Swept volumes (a reconstruction of Kim et al. 2003): ruled quads and posed faces, \
             their distance field on the GPU, a flood fill from the border (not fast marching) \
             and marching tetrahedra with vertices where the grid meets the primitives and \
             sharp edges kept (after Kobbelt et al. 2001; a closed 2-manifold, no topological \
             refinement); the worst relative volume error of the three motions is {:.1e} at \
             N = {} and {:.1e} at N = {}.",
            worst_at(resolutions[0]),
            resolutions[0],
            worst_at(resolutions[resolutions.len() - 1]),
            resolutions[resolutions.len() - 1],
        ),
        tables: vec![table],
        figures: vec![Figure {
            file: file.into(),
            caption: "Swept volume: relative volume error against N (the translated \
                      polyhedra are rebuilt to rounding, their faces and sharp edges in place; \
                      the turning cube's error is that of its N / 2 + 1 sampled poses)"
                .into(),
        }],
        ..Block::default()
    })
}
