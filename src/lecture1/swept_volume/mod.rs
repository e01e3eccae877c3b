//! Swept volumes: Kim, Varadhan, Lin & Manocha, "Fast swept volume approximation of complex
//! polyhedral models", ACM Solid Modeling 2003 / CAD 36(11) 2004 (`lecture1-sources.md`,
//! section 2). The swept volume is the outer boundary of the arrangement of the surfaces the
//! moving model's faces and edges sweep.
//!
//! What the sources confirm: the five stages (primitives of the boundary's superset within an
//! error bound, an unsigned distance field on a uniform grid, classification of grid points
//! by front propagation, isosurface extraction, topological refinement) and that rasterization
//! hardware speeds it up. Everything below is a reconstruction:
//! 1. [`path`]: K poses sampled from keyframes (translation linear, rotation by slerp);
//! 2. [`primitives`]: the model's triangles at each pose and each edge's bilinear ruled quad
//!    between consecutive poses, split into triangles within ε;
//! 3. their unsigned distance field on the GPU slice by slice
//!    ([`super::distance_field::slices`]), clamped near the surface;
//! 4. [`classify`]: a flood fill from the grid's border (not fast marching) into outside
//!    voxels, the rest inside, as a signed field;
//! 5. [`extract`]: the zero level by marching tetrahedra, its vertices where the grid's edges
//!    meet the primitives, sharp edges kept ([`features`], after Kobbelt et al. 2001), a
//!    closed 2-manifold, its volume, and ([`topology`]) its Euler characteristic and genus;
//!    no topological refinement.
//!
//! The grid is the cube around every posed primitive grown by a margin of at least four voxels
//! ([`margin_for`]), so that the border is outside.

pub mod classify;
pub mod extract;
pub mod features;
pub mod path;
pub mod primitives;
pub mod topology;

use super::distance_field::slices::SliceRasterizer;
use super::distance_field::{FieldTimings, Grid};
use super::weld::weld;
use crate::gl::Context;
use crate::mesh::Mesh;
use path::Path3;
use serde::Serialize;
use std::time::Instant;

/// The smallest resolution: the margin alone takes eight voxels.
pub const MIN_RESOLUTION: usize = 16;
/// Default number of sampled poses.
pub const DEFAULT_POSES: usize = 17;

/// The user's choices.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Voxels per axis.
    pub resolution: usize,
    /// K, the sampled poses (at least 2 unless the path has one keyframe).
    pub poses: usize,
    /// ε of the ruled quads' triangles, mesh units; `None`: a quarter of a voxel.
    pub epsilon: Option<f64>,
}

/// What one run gives.
#[derive(Clone, Debug)]
pub struct SweptVolume {
    pub surface: extract::Surface,
    pub grid: Grid,
    pub primitives: primitives::Primitives,
    pub epsilon: f64,
    /// The distance field's clamp (mesh units): two voxel diagonals.
    pub clamp: f64,
    pub classification: classify::Classification,
    pub timings: SweepTimings,
}

/// Where the time went, ms.
#[derive(Clone, Debug, Default, Serialize)]
pub struct SweepTimings {
    /// Sampling poses and building the primitives (CPU, wall clock).
    pub primitives_ms: f64,
    /// The distance field (GPU passes by timer queries, readback and upload by wall clock).
    pub field: FieldTimings,
    /// The distance field's whole wall-clock time.
    pub field_wall_ms: f64,
    /// Flood fill (CPU).
    pub classify_ms: f64,
    /// Marching tetrahedra, volume, topology (CPU).
    pub extract_ms: f64,
}

/// The margin around the primitives' box of side `extent` for `n` voxels: four voxels of the
/// resulting grid (`m = 4 (extent + 2m) / n`), and never below 5% of the extent.
pub fn margin_for(extent: f64, n: usize) -> f64 {
    let voxels = 4.0;
    (voxels * extent / (n as f64 - 2.0 * voxels)).max(0.05 * extent)
}

/// Refuse a model that does not bound a solid: after welding equal positions, every edge
/// must have exactly two triangles, oppositely oriented. An open surface or a triangle soup
/// has no inside, so the fill would run through it and the boundary found would be that of
/// the primitives' own thickness, not of a solid's sweep.
pub fn check_closed(model: &Mesh) -> anyhow::Result<()> {
    let closed = model.closedness();
    anyhow::ensure!(
        closed.faces > 0,
        "every triangle of the model repeats a vertex (after welding equal positions): it has \
         no surface to sweep"
    );
    anyhow::ensure!(
        closed.is_closed(),
        "the model is not a closed surface: after welding equal positions, {} edges have one \
         triangle, {} have three or more and {} have two facing the same way; a swept volume \
         needs a closed, consistently oriented mesh (`classic-gpgpu mesh check MODEL` lists \
         the problems)",
        closed.boundary_edges,
        closed.non_manifold_edges,
        closed.misoriented_edges
    );
    Ok(())
}

/// The swept volume of `model` along `path`.
pub fn sweep(
    ctx: &Context,
    model: &Mesh,
    path: &Path3,
    options: Options,
) -> anyhow::Result<SweptVolume> {
    anyhow::ensure!(
        options.resolution >= MIN_RESOLUTION,
        "the resolution must be at least {MIN_RESOLUTION}, not {}",
        options.resolution
    );
    anyhow::ensure!(
        options.poses >= 2 || path.keyframes.len() == 1,
        "sample at least 2 poses of a moving model, not {}",
        options.poses
    );
    super::distance_field::check_input(model, None)?;
    check_closed(model)?;
    let start = Instant::now();
    let model = weld(model);
    let poses = path.sample(options.poses.max(1));
    // The grid comes first (ε depends on its spacing): the box of the model at every pose;
    // between poses the ruled quads stay inside the box of their corners.
    let mut lo = glam::DVec3::INFINITY;
    let mut hi = glam::DVec3::NEG_INFINITY;
    for pose in &poses {
        for p in &model.positions {
            let q = pose.apply(p.as_dvec3());
            lo = lo.min(q);
            hi = hi.max(q);
        }
    }
    let extent = (hi - lo).max_element();
    let n = options.resolution;
    let grid = Grid::around_box(lo, hi, n, margin_for(extent, n))?;
    let epsilon = options.epsilon.unwrap_or(0.25 * grid.spacing);
    let primitives = primitives::primitives(&model, &poses, epsilon)?;
    let mut timings = SweepTimings {
        primitives_ms: start.elapsed().as_secs_f64() * 1e3,
        ..SweepTimings::default()
    };
    // The unsigned field, clamped at two voxel diagonals: the fill needs it exact only within
    // half a voxel of the surface.
    let clamp = 4.0 * grid.half_diagonal();
    let start = Instant::now();
    let (field, field_timings) =
        SliceRasterizer::new(ctx)?.field(&primitives.mesh, &grid, Some(clamp))?;
    timings.field = field_timings;
    timings.field_wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let start = Instant::now();
    let classification = classify::classify(&field, &primitives.mesh)?;
    let signed = classify::signed_field(&field, &classification, &primitives.mesh);
    timings.classify_ms = start.elapsed().as_secs_f64() * 1e3;
    anyhow::ensure!(
        classification.outside_voxels < grid.len(),
        "no voxel centre is inside the swept surface at resolution {n}: the model is too thin \
         for this grid (or not closed); raise the resolution"
    );
    let start = Instant::now();
    let buckets = classify::Buckets::new(&grid, &primitives.mesh);
    let surface = extract::extract(&grid, &signed, Some(&buckets))?;
    timings.extract_ms = start.elapsed().as_secs_f64() * 1e3;
    let t = &surface.topology;
    anyhow::ensure!(
        surface.watertight(),
        "the extracted boundary at resolution {n} is not closed ({} boundary and {} \
         misoriented edges), so its volume means nothing; try another resolution",
        t.boundary_edges,
        t.misoriented_edges
    );
    Ok(SweptVolume {
        surface,
        grid,
        primitives,
        epsilon,
        clamp,
        classification,
        timings,
    })
}
