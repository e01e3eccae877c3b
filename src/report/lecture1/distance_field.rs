//! Distance fields by rasterization in the report: where the time of each formulation goes
//! (slice passes or the compute dispatch, upload, readback), how the field's error against
//! brute force on the CPU (the same point-triangle distance in f64) behaves as the resolution
//! grows, on a torus, and its difference from parry3d's closest points (an independent
//! reference); Hoff's distance meshes beside the exact slices, with their error against the
//! exact field; then the 2D Voronoi rows.

use super::{Block, Setting};
use crate::lecture1::distance_field::compute::ComputeField;
use crate::lecture1::distance_field::independent::parry_field;
use crate::lecture1::distance_field::mesh_slices::MeshSlices;
use crate::lecture1::distance_field::reference::brute_force;
use crate::lecture1::distance_field::slices::SliceRasterizer;
use crate::lecture1::distance_field::{DistanceField, FieldTimings, Grid};
use crate::mesh::generate::torus_closed;
use crate::page::plot::{Plot, Series};
use crate::report::{Figure, Table};
use crate::timing::Load;
use serde::Serialize;

/// One resolution, one formulation.
#[derive(Clone, Debug, Serialize)]
pub struct FieldRow {
    pub formulation: String,
    pub resolution: usize,
    /// Largest |GPU - CPU| over the grid, in voxels (spacing units).
    pub max_error_voxels: f64,
    /// The tessellation bound of Hoff's distance meshes (pixels or voxels); `None` for exact
    /// methods.
    pub tessellation_bound: Option<f64>,
    /// Mean |GPU - CPU| over the grid, in voxels (the 3D distance meshes' rows).
    pub mean_error_voxels: Option<f64>,
    /// Whether every voxel of the distance meshes' field lies within their stated bound
    /// (3D meshes' rows).
    pub within_bound: Option<bool>,
    /// Largest |GPU - parry3d's closest points| over the grid, in voxels (3D rows).
    pub parry3d_error_voxels: Option<f64>,
    pub timings: FieldTimings,
}

fn largest_difference(a: &DistanceField, b: &DistanceField) -> f64 {
    a.values
        .iter()
        .zip(&b.values)
        .map(|(&x, &y)| (x as f64 - y as f64).abs())
        .fold(0.0, f64::max)
        / a.grid.spacing
}

/// The distance-field block: a table of the time by stage and of the error, and a plot of the
/// error against the resolution.
pub fn block(setting: &Setting) -> anyhow::Result<Block> {
    let ctx = setting.opts.gl;
    let bar = setting.stage("distance fields");
    let mesh = torus_closed(0.6, 0.25, 16, 8);
    let resolutions: &[usize] = if setting.opts.quick {
        &[8, 16]
    } else {
        &[16, 32, 48]
    };
    let slices = SliceRasterizer::new(ctx)?;
    let meshes = MeshSlices::new(ctx)?;
    let compute = ComputeField::new(ctx).ok();
    // One untimed run of each formulation on a small grid first: it compiles their shaders,
    // which is all a warm-up buys (each run makes its own textures), so the runs below are
    // each measured once.
    let small = Grid::around(&mesh, WARM_UP_VOXELS, Grid::default_margin(&mesh))?;
    slices.field(&mesh, &small, None)?;
    meshes.field(&mesh, &small, None, MESH_ERROR_VOXELS)?;
    if let Some(c) = &compute {
        c.field(&mesh, &small, None)?;
    }
    let mut rows = Vec::new();
    for &n in resolutions {
        let grid = Grid::around(&mesh, n, Grid::default_margin(&mesh))?;
        let cpu = brute_force(&mesh, &grid, None);
        let parry = parry_field(&mesh, &grid, None)?;
        let (field, timings) = slices.field(&mesh, &grid, None)?;
        rows.push(FieldRow {
            formulation: "classic (slices, GL_MIN)".into(),
            resolution: n,
            max_error_voxels: largest_difference(&field, &cpu),
            tessellation_bound: None,
            mean_error_voxels: None,
            within_bound: None,
            parry3d_error_voxels: Some(largest_difference(&field, &parry)),
            timings,
        });
        // Hoff's distance meshes, within MESH_ERROR_VOXELS.
        let (field, timings, bound) = meshes.field(&mesh, &grid, None, MESH_ERROR_VOXELS)?;
        let error = bound.compare(&field, &cpu);
        rows.push(FieldRow {
            formulation: "classic, Hoff's distance meshes (depth test)".into(),
            resolution: n,
            max_error_voxels: error.max(),
            tessellation_bound: Some(bound.tessellation_voxels),
            mean_error_voxels: Some(error.mean),
            within_bound: Some(error.within()),
            parry3d_error_voxels: Some(largest_difference(&field, &parry)),
            timings,
        });
        if let Some(c) = &compute {
            let (field, timings) = c.field(&mesh, &grid, None)?;
            rows.push(FieldRow {
                formulation: "compute (one invocation per voxel)".into(),
                resolution: n,
                max_error_voxels: largest_difference(&field, &cpu),
                tessellation_bound: None,
                mean_error_voxels: None,
                within_bound: None,
                parry3d_error_voxels: Some(largest_difference(&field, &parry)),
                timings,
            });
        }
    }
    rows.extend(voronoi_rows(
        ctx,
        if setting.opts.quick { 64 } else { 256 },
    )?);
    let load = Load::now();
    bar.finish_and_clear();
    let table = Table {
        caption: format!(
            "Distance field of a torus ({} triangles), unclamped, on {}: where the time goes \
             (ms; slice passes by GL timer queries, compute by glFinish wall clock, readback \
             and upload by wall clock; one run each, {}), the largest difference from \
             brute force in f64 (the same point-triangle distance) and from parry3d's closest \
             points (an independent library, fp32), in voxels; Hoff's distance meshes in 3D \
             within {MESH_ERROR_VOXELS} voxel (their rows: the largest and mean difference \
             from brute force; upload holds building the meshes on the CPU); the Voronoi rows (2D, {VORONOI_SITES} random \
             points, segments and triangles, N x N pixels, measured in the same run) in \
             pixels, with Hoff's distance meshes within {MESH_ERROR_PIXELS} pixel",
            mesh.triangles.len(),
            setting.renderer,
            load.map_or("load average unknown".to_string(), |l| l.in_words())
        ),
        header: [
            "formulation",
            "N",
            "passes ms",
            "readback ms",
            "upload ms",
            "triangles drawn",
            "max error (voxels or pixels)",
            "mean error (voxels)",
            "max |GPU - parry3d| (voxels)",
        ]
        .map(String::from)
        .to_vec(),
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    r.formulation.clone(),
                    r.resolution.to_string(),
                    format!("{:.2}", r.timings.passes_ms),
                    format!("{:.2}", r.timings.readback_ms),
                    format!("{:.2}", r.timings.upload_ms),
                    r.timings.triangles_drawn.to_string(),
                    format!("{:.2e}", r.max_error_voxels),
                    r.mean_error_voxels
                        .map_or("-".into(), |e| format!("{e:.2e}")),
                    r.parry3d_error_voxels
                        .map_or("-".into(), |e| format!("{e:.2e}")),
                ]
            })
            .collect(),
    };
    let file = "lecture1_distance_field_error.png";
    let series = |name: &str, prefix: &str| {
        Series::new(
            name,
            rows.iter()
                .filter(|r| r.formulation.starts_with(prefix))
                .map(|r| (r.resolution as f64, r.max_error_voxels))
                .collect(),
        )
    };
    Plot {
        title: "Distance field: largest error against brute force".into(),
        x_label: "N (voxels per axis)".into(),
        y_label: "max |GPU - CPU| (voxels)".into(),
        log_x: false,
        log_y: true,
        series: vec![
            series("classic, exact", "classic (slices"),
            series("classic, Hoff's meshes", "classic, Hoff"),
            series("compute", "compute"),
        ]
        .into_iter()
        .filter(|s| !s.points.is_empty())
        .collect(),
    }
    .write_png(&setting.opts.out_dir.join(file))?;
    let worst = |prefix: &str, f: fn(&FieldRow) -> Option<f64>| {
        rows.iter()
            .filter(|r| r.formulation.starts_with(prefix))
            .filter_map(f)
            .fold(0.0, f64::max)
    };
    let mesh_error = worst("voronoi 2D, Hoff", |r| Some(r.max_error_voxels));
    let meshes_3d = |f: fn(&FieldRow) -> Option<f64>| worst("classic, Hoff", f);
    let meshes_within = rows.iter().filter_map(|r| r.within_bound).all(|w| w);
    let time = |prefix: &str| {
        rows.iter()
            .rev()
            .find(|r| r.formulation.starts_with(prefix))
            .map_or(0.0, |r| {
                r.timings.passes_ms + r.timings.readback_ms + r.timings.upload_ms
            })
    };
    let largest = resolutions.last().copied().unwrap_or(0);
    let summary = format!(
        "The unsigned distance field of a mesh, slice by slice, by two methods. Exact \
         per-fragment distances kept by GL_MIN blending (the default, a reconstruction in \
         DiFi's style): at most {:.1e} voxels from brute force in f64 and {:.1e} voxels from \
         parry3d's closest points. Hoff's distance meshes (every vertex, edge and face's \
         distance drawn as triangles, the depth test keeping the nearest): at most {:.3} and \
         on average {:.3} voxels from brute force, {} their bound (a tessellation error of \
         {MESH_ERROR_VOXELS} voxel plus the rasterizer's coverage); at N = {largest} the exact \
         slices took {:.0} ms and the meshes {:.0} ms (passes, readback and upload; the \
         meshes' upload includes building them). In 2D, the exact per-fragment Voronoi \
         distances are at most {:.1e} pixels from brute force, and Hoff's distance meshes \
         (cones and tents, the depth interpolated) {mesh_error:.2} pixels, {} their \
         tessellation bound of {MESH_ERROR_PIXELS} pixel.",
        worst("classic (slices", |r| Some(r.max_error_voxels)),
        worst("classic (slices", |r| r.parry3d_error_voxels),
        meshes_3d(|r| Some(r.max_error_voxels)),
        meshes_3d(|r| r.mean_error_voxels),
        if meshes_within { "within" } else { "BEYOND" },
        time("classic (slices"),
        time("classic, Hoff"),
        worst("voronoi 2D, exact", |r| Some(r.max_error_voxels)),
        if mesh_error <= MESH_ERROR_PIXELS {
            "within"
        } else {
            "BEYOND"
        },
    );
    let mut paths = vec![
        super::paths::FIELD_SLICES,
        super::paths::FIELD_MESHES,
        super::paths::FIELD_PARRY3D,
        super::paths::VORONOI_EXACT,
        super::paths::VORONOI_MESH,
    ];
    if compute.is_some() {
        paths.push(super::paths::FIELD_COMPUTE);
    }
    Ok(Block {
        id: "distance-field".into(),
        results: serde_json::to_value(&rows)?,
        load,
        summary,
        checks_made: vec![
            "distance field vs f64",
            "distance field vs parry3d",
            "distance meshes vs exact field",
            "voronoi vs brute force",
        ],
        paths,
        tables: vec![table],
        figures: vec![Figure {
            file: file.into(),
            caption: "Distance field: the exact methods' error stays at fp32 rounding as N \
                      grows (exact per voxel, not an approximation that converges); Hoff's \
                      meshes stay under their tessellation bound, in voxels, at every N"
                .into(),
        }],
        ..Block::default()
    })
}

/// Sites of the 2D rows.
const VORONOI_SITES: usize = 30;
/// Hoff's distance meshes' tessellation error in the 3D rows, voxels.
const MESH_ERROR_VOXELS: f64 = 0.5;

/// The grid (voxels a side) and image (pixels a side) of the untimed warm-up runs.
const WARM_UP_VOXELS: usize = 8;
const WARM_UP_PIXELS: usize = 16;
/// The distance meshes' tessellation error in the 2D rows, pixels.
const MESH_ERROR_PIXELS: f64 = 0.5;

/// The 2D generalized Voronoi diagram of random sites at `n x n`, exact per fragment and by
/// Hoff's distance meshes, each against brute force (distances in pixels).
fn voronoi_rows(ctx: &crate::gl::Context, n: usize) -> anyhow::Result<Vec<FieldRow>> {
    use crate::lecture1::voronoi::raster::{Method, VoronoiRasterizer};
    use crate::lecture1::voronoi::{reference, Domain, Site};
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let mut p = || [rng.gen_range(0.0..10.0), rng.gen_range(0.0..10.0)];
    let sites: Vec<Site> = (0..VORONOI_SITES)
        .map(|i| match i % 3 {
            0 => Site::Point(p()),
            1 => Site::Segment([p(), p()]),
            _ => Site::Triangle([p(), p(), p()]),
        })
        .collect();
    let domain = Domain {
        min: [0.0, 0.0],
        size: 10.0,
    };
    let raster = VoronoiRasterizer::new(ctx)?;
    let cpu = reference::brute_force(&sites, domain, n, 1.0);
    let methods = [
        ("voronoi 2D, exact per fragment", Method::Exact),
        (
            "voronoi 2D, Hoff's distance meshes",
            Method::Mesh {
                error_pixels: MESH_ERROR_PIXELS,
            },
        ),
    ];
    let mut rows = Vec::new();
    for (name, method) in methods {
        // An untimed first run on a small image (shader compilation), then the measured one.
        raster.diagram_by(&sites, domain, WARM_UP_PIXELS, method)?;
        let (diagram, t) = raster.diagram_by(&sites, domain, n, method)?;
        let pixel = domain.pixel(n);
        let error = diagram
            .distance
            .iter()
            .zip(&cpu.distance)
            .map(|(&g, &c)| (g as f64 - c as f64).abs())
            .fold(0.0, f64::max)
            / pixel;
        rows.push(FieldRow {
            formulation: name.into(),
            resolution: n,
            max_error_voxels: error,
            tessellation_bound: (diagram.mesh_error > 0.0).then_some(diagram.mesh_error / pixel),
            mean_error_voxels: None,
            within_bound: None,
            parry3d_error_voxels: None,
            timings: FieldTimings {
                passes_ms: t.pass_ms,
                readback_ms: t.readback_ms,
                upload_ms: t.upload_ms,
                triangles_drawn: t.triangles as u64,
            },
        });
    }
    Ok(rows)
}
