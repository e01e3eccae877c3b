//! Penetration depth by rasterized Minkowski sums: Kim, Otaduy, Lin & Manocha, "Fast
//! penetration depth computation for physically-based animation", SCA 2002.
//!
//! Confirmed of the paper (`lecture1-sources.md`, section 1): the translational penetration
//! depth of two overlapping polyhedra is the distance from the origin to the boundary of
//! A ⊕ (-B); both models are decomposed into convex pieces, the Minkowski sum of every pair of
//! pieces is built, a closest-point query on the union of the sums runs on rasterization
//! hardware, and the estimate is refined. Its passes, models and refinement are not public,
//! so everything below the step list is a reconstruction:
//!
//! 1. [`pieces`]: each OBJ object or group is a convex piece; a piece that is not convex is
//!    refused (not replaced by its hull).
//! 2. [`minkowski`]: M_ij = hull(vertices(A_i) - vertices(B_j)) on the CPU (parry3d's
//!    quickhull), with their face planes; sums that cannot come nearer than a cheap bound are
//!    dropped.
//! 3. [`cube_map`], [`closest_point`], [`readback`] (OpenGL 3.3): six 90° views around the
//!    origin into R32F targets; pass after pass over the back faces of every sum, T (where
//!    each pixel's ray leaves the union) is raised with MAX blending until an occlusion query
//!    counts no raised pixel; a min-reduction read back gives the smallest T, an upper bound on
//!    the depth, with its direction.
//! 4. [`refine`]: object-space refinement on the CPU over the sums' planes within that bound
//!    (the technical report names "object-space walking"; ours enumerates the boundary
//!    features the bound leaves).
//!
//! [`reference`](mod@reference) is the CPU reference (exact for one convex sum; the same per-ray exits for a
//! union) and [`compute`] the OpenGL 4.3 counterpart of step 3; [`scenes`] are model pairs
//! with known depths. Shaders:
//! `glsl/lecture1/penetration_*`.

pub mod closest_point;
pub mod compute;
pub mod cube_map;
pub mod minkowski;
pub mod pieces;
pub mod readback;
pub mod reference;
pub mod refine;
pub mod scenes;

use crate::gl::picture::{Panel, Scale};
use crate::gl::{Context, GlError};
use closest_point::{ExitPasses, ExitTargets, SumBuffers};
use compute::ComputeRays;
use minkowski::{box_bound, cull, minkowski_sums, Plane, Polytope};
use pieces::Piece;
use refine::Refined;
use serde::Serialize;

/// Default texels per cube face side.
pub const DEFAULT_RESOLUTION: usize = 64;

/// Which formulation of the closest-point query runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Formulation {
    /// Rasterized back faces, MAX blending, occlusion queries (OpenGL 3.3).
    Classic,
    /// One compute invocation per ray (OpenGL 4.3).
    Compute,
}

/// How to run the query.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Texels per cube face side.
    pub resolution: usize,
    pub formulation: Formulation,
    /// Keep the T buffer (for pictures and comparisons).
    pub keep_exits: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            resolution: DEFAULT_RESOLUTION,
            formulation: Formulation::Classic,
            keep_exits: false,
        }
    }
}

/// The answer, and how it was reached.
#[derive(Clone, Debug, Serialize)]
pub struct Penetration {
    /// The penetration depth (0 when the models do not overlap).
    pub depth: f64,
    /// The unit vector along which B moves by `depth` to touch A without overlap; `None`
    /// when they do not overlap.
    pub direction: Option<[f64; 3]>,
    /// Whether the origin lies in a sum (the models overlap or touch).
    pub overlap: bool,
    pub resolution: usize,
    pub formulation: Formulation,
    /// Convex pieces of A and of B.
    pub pieces: [usize; 2],
    /// Minkowski sums built, and those kept after the cheap bound.
    pub sums: usize,
    pub sums_kept: usize,
    /// Classic passes drawn (0 for the compute formulation).
    pub passes: usize,
    /// The smallest T over all pixels (the rasterized bound).
    pub rasterized_bound: f64,
    /// Whether the rasterized bound's point lay inside a sum (a fragment the renderer lost),
    /// so that every ray whose T lay inside a sum took the CPU's exit along it instead, and
    /// the bound below is the smallest T after that.
    pub bound_corrected: bool,
    /// The upper bound the refinement starts from, and its pixel's direction.
    pub upper_bound: f64,
    pub upper_bound_direction: [f64; 3],
    /// What the object-space refinement did.
    pub refinement: Refined,
    /// The unit frame: sums divided by this power of two on the GPU.
    pub scale: f64,
    /// Points within this distance of a sum's boundary count as on it.
    pub tolerance: f64,
    /// GPU time of the query (classic: timer queries; compute: between glFinish calls), ms.
    pub gpu_ms: f64,
    /// T of every pixel in model units (`6N x N`, row-major from the bottom), when kept.
    #[serde(skip)]
    pub exits: Option<Vec<f32>>,
}

/// The programs of both formulations (the compute one only where the context has 4.3).
pub struct PenetrationQuery {
    ctx: Context,
    exit_passes: ExitPasses,
    compute: Option<ComputeRays>,
}

impl PenetrationQuery {
    pub fn new(ctx: &Context) -> Result<PenetrationQuery, GlError> {
        Ok(PenetrationQuery {
            ctx: ctx.clone(),
            exit_passes: ExitPasses::new(ctx)?,
            compute: if ctx.has_compute() {
                Some(ComputeRays::new(ctx)?)
            } else {
                None
            },
        })
    }

    /// The penetration depth of A (pieces `a`) and B (pieces `b`).
    pub fn run(&self, a: &[Piece], b: &[Piece], options: &Options) -> anyhow::Result<Penetration> {
        anyhow::ensure!(!a.is_empty(), "model A has no pieces");
        anyhow::ensure!(!b.is_empty(), "model B has no pieces");
        anyhow::ensure!(
            options.resolution >= 2,
            "the resolution must be at least 2 texels per cube face, not {}",
            options.resolution
        );
        let coordinates = a
            .iter()
            .chain(b)
            .flat_map(|p| p.mesh.positions.iter())
            .map(|p| p.abs().max_element() as f64)
            .fold(0.0, f64::max);
        let sums = minkowski_sums(a, b)?;
        let mut result = self.run_sums(sums, coordinates, options)?;
        result.pieces = [a.len(), b.len()];
        Ok(result)
    }

    /// The query on given sums; `coordinates` is the largest input coordinate (for the
    /// tolerance: fp32 inputs are known to about 1e-7 of it).
    pub fn run_sums(
        &self,
        sums: Vec<Polytope>,
        coordinates: f64,
        options: &Options,
    ) -> anyhow::Result<Penetration> {
        let all = sums.len();
        let reach = sums
            .iter()
            .flat_map(|s| s.vertices.iter())
            .map(|v| v.length())
            .fold(0.0, f64::max);
        anyhow::ensure!(
            reach.is_finite() && reach > 0.0,
            "the Minkowski sums have no finite extent ({reach})"
        );
        let tolerance = 1e-6 * reach.max(coordinates);
        let overlap = sums.iter().any(|s| s.contains_origin(tolerance));
        // Drop the sums that cannot come nearer than the bounding box's bound.
        let bound = if overlap {
            box_bound(&sums) + tolerance
        } else {
            tolerance
        };
        let kept = cull(sums, bound);
        // The unit frame: a power of two, so that scaling is exact.
        let scale = 2f64.powi(reach.log2().ceil() as i32);
        let unit: Vec<Polytope> = kept.iter().map(|s| scaled(s, 1.0 / scale)).collect();
        let (mut nearest, passes, gpu_ms, mut exits) = self.closest_point(&unit, options)?;
        // The bound's point must lie outside every sum's interior. A renderer that loses a
        // fragment leaves T too small on its ray (GL 3.3, section 3.6.1, asks exactly one of
        // two triangles sharing an edge to cover a pixel centre on it; softpipe can give
        // neither): then every ray whose T still lies inside a sum takes its exit in f64, and
        // the bound is the smallest T of all.
        let inside = |t: f32, pixel: usize| {
            let point = cube_map::direction_of(pixel, options.resolution) * (t as f64 * scale);
            kept.iter().any(|s| s.depth_of(point) < -tolerance)
        };
        let rasterized_bound = nearest.0 as f64 * scale;
        let bound_corrected = overlap && inside(nearest.0, nearest.1);
        if bound_corrected {
            let mut all = match exits.take() {
                Some(t) => t,
                None => {
                    let keep = Options {
                        keep_exits: true,
                        ..*options
                    };
                    self.closest_point(&unit, &keep)?
                        .3
                        .ok_or_else(|| anyhow::anyhow!("the T buffer was not kept"))?
                }
            };
            for (pixel, t) in all.iter_mut().enumerate() {
                if inside(*t, pixel) {
                    let ray = cube_map::direction_of(pixel, options.resolution);
                    *t = (reference::union_exit(&kept, ray, 0.0) / scale) as f32;
                }
            }
            nearest = smallest(&all).ok_or_else(|| anyhow::anyhow!("an empty T buffer"))?;
            exits = options.keep_exits.then_some(all);
        }
        let upper_bound = nearest.0 as f64 * scale;
        let bound_direction = cube_map::direction_of(nearest.1, options.resolution);
        anyhow::ensure!(
            upper_bound.is_finite(),
            "the closest-point query gave a non-finite upper bound ({upper_bound})"
        );
        let refinement = if overlap {
            refine::refine(&kept, upper_bound, bound_direction, tolerance)
        } else {
            Refined {
                depth: 0.0,
                direction: bound_direction.to_array(),
                planes: 0,
                candidates: 0,
                improved: false,
                complete: true,
            }
        };
        anyhow::ensure!(
            refinement.depth.is_finite() && refinement.direction.iter().all(|c| c.is_finite()),
            "the refined depth is not finite ({}, direction {:?})",
            refinement.depth,
            refinement.direction
        );
        Ok(Penetration {
            depth: if overlap { refinement.depth } else { 0.0 },
            direction: overlap.then_some(refinement.direction),
            overlap,
            resolution: options.resolution,
            formulation: options.formulation,
            pieces: [0, 0],
            sums: all,
            sums_kept: kept.len(),
            passes,
            rasterized_bound,
            bound_corrected,
            upper_bound,
            upper_bound_direction: bound_direction.to_array(),
            refinement,
            scale,
            tolerance,
            gpu_ms,
            exits: exits.map(|e| e.iter().map(|t| (*t as f64 * scale) as f32).collect()),
        })
    }

    /// Step 3 in the chosen formulation.
    fn closest_point(&self, unit: &[Polytope], options: &Options) -> anyhow::Result<Outcome> {
        match options.formulation {
            Formulation::Classic => self.classic(unit, options),
            Formulation::Compute => self.compute(unit, options),
        }
    }

    /// The classic passes: (smallest T, its pixel), passes, GPU ms, T if kept.
    fn classic(&self, unit: &[Polytope], options: &Options) -> anyhow::Result<Outcome> {
        let buffers = SumBuffers::new(&self.ctx, unit)?;
        let targets = ExitTargets::new(&self.ctx, options.resolution)?;
        let (current, stats) = self.exit_passes.run(&buffers, &targets)?;
        let target = &targets.targets[current];
        let nearest = readback::nearest_exit(&self.ctx, target)?;
        let exits = if options.keep_exits {
            Some(target.color(0).download_f32()?)
        } else {
            None
        };
        Ok((
            (nearest.t, nearest.pixel),
            stats.passes,
            stats.gpu_ms,
            exits,
        ))
    }

    /// The compute counterpart: same outcome, no passes.
    fn compute(&self, unit: &[Polytope], options: &Options) -> anyhow::Result<Outcome> {
        let compute = match &self.compute {
            Some(c) => c,
            None => {
                self.ctx
                    .require_compute("the compute formulation of the penetration-depth query")?;
                anyhow::bail!("no compute program")
            }
        };
        let (exits, ms) = compute.exits(unit, options.resolution)?;
        let nearest = smallest(&exits).ok_or_else(|| anyhow::anyhow!("an empty T buffer"))?;
        Ok((nearest, 0, ms, options.keep_exits.then_some(exits)))
    }
}

/// The smallest T and its pixel.
fn smallest(exits: &[f32]) -> Option<(f32, usize)> {
    exits
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map(|(k, t)| (*t, k))
}

/// (smallest T, its pixel), passes, GPU ms, T if kept.
type Outcome = ((f32, usize), usize, f64, Option<Vec<f32>>);

/// `sum` with every coordinate multiplied by `factor`.
pub fn scaled(sum: &Polytope, factor: f64) -> Polytope {
    Polytope {
        vertices: sum.vertices.iter().map(|v| *v * factor).collect(),
        planes: sum
            .planes
            .iter()
            .map(|p| Plane {
                normal: p.normal,
                offset: p.offset * factor,
            })
            .collect(),
        ..sum.clone()
    }
}

/// The six cube faces of a T buffer as panels with one shared scale (titles name the view
/// directions).
pub fn exit_panels(exits: &[f32], resolution: usize) -> Vec<Panel> {
    let n = resolution;
    let scale = Scale::of([exits]);
    ["+x", "-x", "+y", "-y", "+z", "-z"]
        .iter()
        .enumerate()
        .map(|(f, name)| {
            let mut values = Vec::with_capacity(n * n);
            for j in 0..n {
                values.extend_from_slice(&exits[j * 6 * n + f * n..j * 6 * n + (f + 1) * n]);
            }
            Panel {
                title: format!("T, view {name}"),
                values,
                width: n as u32,
                height: n as u32,
                scale,
            }
        })
        .collect()
}
