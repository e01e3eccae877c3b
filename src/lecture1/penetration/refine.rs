//! Step 4, "the estimate is refined": in object space, on the CPU (a reconstruction; the
//! technical report names refinement by object-space walking, whose details are not public).
//!
//! The nearest point q* of the union's boundary lies inside some face, edge or vertex of that
//! boundary, and there it is the foot of the perpendicular from the origin on the feature's
//! supporting plane, line (two planes) or point (three planes). Those planes pass within
//! |q*| <= the rasterized upper bound of the origin, so only the sums' planes within the bound
//! are combined, by ones, twos and threes. A candidate point counts when no sum holds it in
//! its interior (then it is not inside the union, and |q| bounds the depth from above); the
//! smallest such |q| is the depth. When the bound leaves too many planes for the triples (or
//! pairs), those are skipped and the result says so (`complete: false`): it is still an
//! upper bound, never below the true depth.

use super::minkowski::{Plane, Polytope};
use glam::{DMat3, DVec3};
use serde::Serialize;

/// Most planes within the bound whose pairs are tried.
pub const PAIR_LIMIT: usize = 400;
/// Most planes within the bound whose triples are tried.
pub const TRIPLE_LIMIT: usize = 48;

/// What the refinement found.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Refined {
    pub depth: f64,
    pub direction: [f64; 3],
    /// Planes within the bound.
    pub planes: usize,
    /// Candidate points tried.
    pub candidates: usize,
    /// Whether a candidate beat the rasterized bound.
    pub improved: bool,
    /// Whether pairs and triples were all tried (false: the depth is an upper bound only).
    pub complete: bool,
}

/// Refine the upper bound `bound` (with its direction) over `sums`; points within
/// `tolerance` of a sum's boundary count as outside its interior.
pub fn refine(sums: &[Polytope], bound: f64, direction: DVec3, tolerance: f64) -> Refined {
    let planes: Vec<Plane> = sums
        .iter()
        .flat_map(|s| s.planes.iter().copied())
        .filter(|p| p.offset.abs() <= bound + tolerance)
        .collect();
    let k = planes.len();
    let mut out = Refined {
        depth: bound,
        direction: direction.to_array(),
        planes: k,
        candidates: 0,
        improved: false,
        complete: k <= TRIPLE_LIMIT,
    };
    let mut consider = |q: DVec3, normals: &[DVec3]| {
        out.candidates += 1;
        let length = q.length();
        if length >= out.depth || !outside_interiors(sums, q, tolerance) {
            return;
        }
        let d = if length > tolerance {
            q / length
        } else {
            normals.iter().sum::<DVec3>().normalize_or(normals[0])
        };
        out.depth = length;
        out.direction = d.to_array();
        out.improved = true;
    };
    for p in &planes {
        consider(p.normal * p.offset, &[p.normal]);
    }
    if k <= PAIR_LIMIT {
        for a in 0..k {
            for b in a + 1..k {
                if let Some(q) = foot_on_line(&planes[a], &planes[b]) {
                    consider(q, &[planes[a].normal, planes[b].normal]);
                }
            }
        }
    }
    if k <= TRIPLE_LIMIT {
        for a in 0..k {
            for b in a + 1..k {
                for c in b + 1..k {
                    let (pa, pb, pc) = (&planes[a], &planes[b], &planes[c]);
                    if let Some(q) = corner(pa, pb, pc) {
                        consider(q, &[pa.normal, pb.normal, pc.normal]);
                    }
                }
            }
        }
    }
    out
}

/// No sum holds `q` deeper than `tolerance` inside.
fn outside_interiors(sums: &[Polytope], q: DVec3, tolerance: f64) -> bool {
    sums.iter().all(|s| s.depth_of(q) >= -tolerance)
}

/// The point of the line where two planes meet nearest to the origin (`None` when they are
/// parallel): q = a n1 + b n2 on both planes.
fn foot_on_line(p: &Plane, q: &Plane) -> Option<DVec3> {
    let g = p.normal.dot(q.normal);
    let det = 1.0 - g * g;
    if det < 1e-10 {
        return None;
    }
    let a = (p.offset - g * q.offset) / det;
    let b = (q.offset - g * p.offset) / det;
    Some(p.normal * a + q.normal * b)
}

/// The point where three planes meet (`None` when they do not meet in one point).
fn corner(p: &Plane, q: &Plane, r: &Plane) -> Option<DVec3> {
    let m = DMat3::from_cols(p.normal, q.normal, r.normal).transpose();
    let det = m.determinant();
    if det.abs() < 1e-9 {
        return None;
    }
    Some(m.inverse() * DVec3::new(p.offset, q.offset, r.offset))
}
