//! The CPU reference: an exact ray tracer of the same bilinear height field, in f64. It walks
//! every patch the ray crosses, in order (a 2D grid walk, no pyramid), and solves each
//! patch's quadratic ([`super::patch`]); the first root is the hit.
//!
//! `offset` raises every height by that much. A tracer whose answer is the exact hit of the
//! field perturbed by at most `delta` hits no earlier than `trace(.., +delta)` and no later
//! than `trace(.., -delta)`: that is how the tests state the GPU's tolerance.

use super::camera::Camera;
use super::patch::{first_hit, Corners, Segment};
use super::surface::Surface;
use glam::DVec3;
use serde::Serialize;

/// Where a ray first meets the height field.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Hit {
    /// Distance from the eye along the unit world direction.
    pub tau: f64,
    /// The hit in grid space (x, y in patches, z the height).
    pub grid: DVec3,
    /// The ray entered the box through one of its four sides, below the surface: it hit the
    /// box's wall. (A ray that enters through the top, at a point where the surface is at the
    /// top, hits the surface there, not a wall.)
    pub wall: bool,
}

/// The parameter interval in which the ray `o + tau d` (grid space) is inside the box
/// `[0, wp] x [0, hp] x [0, 1]`, from tau = 0 on; `None` if it never is.
pub fn box_interval(o: DVec3, d: DVec3, wp: f64, hp: f64) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for (o, d, hi) in [(o.x, d.x, wp), (o.y, d.y, hp), (o.z, d.z, 1.0)] {
        if d == 0.0 {
            if o < 0.0 || o > hi {
                return None;
            }
            continue;
        }
        let (a, b) = ((0.0 - o) / d, (hi - o) / d);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    (t0 <= t1).then_some((t0, t1))
}

/// Whether the ray `o + tau d` (grid space) enters the box `[0, wp] x [0, hp] x [0, 1]`
/// through one of its four sides (x or y planes) rather than its top or bottom, from
/// outside (tau > 0). Where it enters along an edge of the top, it counts as a side.
pub fn enters_through_side(o: DVec3, d: DVec3, wp: f64, hp: f64) -> bool {
    let near = |o: f64, d: f64, hi: f64| {
        if d == 0.0 {
            f64::NEG_INFINITY
        } else {
            ((0.0 - o) / d).min((hi - o) / d)
        }
    };
    let side = near(o.x, d.x, wp).max(near(o.y, d.y, hp));
    side > 0.0 && side >= near(o.z, d.z, 1.0)
}

/// The ray from `eye` along unit `dir` (world), traced through the height field raised by
/// `offset`.
pub fn trace(surface: &Surface, eye: DVec3, dir: DVec3, offset: f64) -> Option<Hit> {
    let scale = surface.world_to_grid().as_dvec3();
    let cells = Cells {
        side: 1.0,
        count: surface.patches(),
        patches: surface.patches(),
    };
    walk(&cells, eye * scale, dir * scale, |i, j| {
        surface.corners(i, j, offset)
    })
}

/// A height field of bilinear cells over the map's patches: `count` cells along x and y,
/// each `side` patches wide (the last ones cut at the map's edge, `patches`). The map's own
/// field is one cell per patch; the prefilter's coarser fields one per pyramid node.
pub struct Cells {
    pub side: f64,
    pub count: (u32, u32),
    pub patches: (u32, u32),
}

/// The exact first hit of the grid-space ray `o + tau d` with the field of `cells` whose cell
/// (i, j) has corners `corners(i, j)`: a walk over every cell the ray crosses, in order, each
/// cell's quadratic solved ([`super::patch`]).
pub fn walk(
    cells: &Cells,
    o: DVec3,
    d: DVec3,
    corners: impl Fn(u32, u32) -> Corners,
) -> Option<Hit> {
    let (wp, hp) = (cells.patches.0 as f64, cells.patches.1 as f64);
    let (nx, ny) = (cells.count.0 as i64, cells.count.1 as i64);
    let side = cells.side;
    let (t_in, t_out) = box_interval(o, d, wp, hp)?;
    let start = o + t_in * d;
    let cell_of = |x: f64, n: i64| ((x / side).floor() as i64).clamp(0, n - 1);
    let (mut i, mut j) = (cell_of(start.x, nx), cell_of(start.y, ny));
    // Where the ray leaves cell `n` along one axis (the last cell ends at the map's edge).
    let exit = |n: i64, o: f64, d: f64, edge: f64| {
        let (lo, hi) = (n as f64 * side, ((n + 1) as f64 * side).min(edge));
        if d > 0.0 {
            (hi - o) / d
        } else if d < 0.0 {
            (lo - o) / d
        } else {
            f64::INFINITY
        }
    };
    let through_side = enters_through_side(o, d, wp, hp);
    let (mut t, mut first) = (t_in, true);
    loop {
        let (tx, ty) = (exit(i, o.x, d.x, wp), exit(j, o.y, d.y, hp));
        let t_exit = tx.min(ty).min(t_out);
        let p = o + t * d;
        let segment = Segment {
            start: [
                (p.x - i as f64 * side) / side,
                (p.y - j as f64 * side) / side,
                p.z,
            ],
            step: [d.x / side, d.y / side, d.z],
            length: (t_exit - t).max(0.0),
        };
        if let Some(u) = first_hit(corners(i as u32, j as u32), &segment) {
            let tau = t + u;
            return Some(Hit {
                tau,
                grid: o + tau * d,
                wall: first && u == 0.0 && through_side,
            });
        }
        if t_exit >= t_out {
            return None;
        }
        if tx <= ty {
            i += d.x.signum() as i64;
        } else {
            j += d.y.signum() as i64;
        }
        if i < 0 || j < 0 || i >= nx || j >= ny {
            return None;
        }
        t = t_exit;
        first = false;
    }
}

/// Every pixel of `camera`'s image traced (row by row from the bottom).
pub fn trace_image(surface: &Surface, camera: &Camera, offset: f64) -> Vec<Option<Hit>> {
    let eye = camera.eye.as_dvec3();
    (0..camera.height)
        .flat_map(|py| (0..camera.width).map(move |px| (px, py)))
        .map(|(px, py)| trace(surface, eye, camera.pixel_direction(px, py), offset))
        .collect()
}
