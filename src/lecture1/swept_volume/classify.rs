//! Outside and inside (Kim et al. 2003, stage 3, a reconstruction: the paper propagates a
//! front by fast marching; here a flood fill): the voxels reached from the grid's border are
//! outside, the rest inside, and the signed field is `+d` outside, `-d` inside.
//!
//! Two face-neighbour voxels are connected when the segment between their centres crosses no
//! primitive. Every point of that segment is within `h = spacing / 2` of one of its ends, so
//! when both ends are farther than `h` from every primitive (their unsigned distances say so)
//! the segment is free without a test; otherwise an exact segment-triangle test (Shewchuk's
//! orientation predicates) decides, against the primitives bucketed near the segment. So the
//! fill runs through the voxels with `d > h` and then as close to the surface as the voxel
//! centres allow, and a voxel centre is outside exactly when it is outside the closed surface
//! the primitives make.

use super::super::distance_field::{DistanceField, Grid};
use crate::mesh::Mesh;
use glam::DVec3;
use std::collections::VecDeque;

/// Coarse cells of this many voxels per side hold the primitives for the segment tests.
const BUCKET: usize = 4;

/// The classification and its cost.
#[derive(Clone, Debug, Default)]
pub struct Classification {
    pub outside: Vec<bool>,
    /// Exact segment-triangle tests run.
    pub segment_tests: u64,
    /// Voxels outside.
    pub outside_voxels: usize,
}

/// Classify every voxel of `field` (the unsigned field of `primitives`, clamped or not).
pub fn classify(field: &DistanceField, primitives: &Mesh) -> anyhow::Result<Classification> {
    let grid = &field.grid;
    let n = grid.n;
    let h = 0.5 * grid.spacing * (1.0 + 1e-4);
    let buckets = Buckets::new(grid, primitives);
    let d = &field.values;
    let mut out = Classification {
        outside: vec![false; grid.len()],
        ..Classification::default()
    };
    let mut queue = VecDeque::new();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let border = [x, y, z].iter().any(|&c| c == 0 || c == n - 1);
                if !border {
                    continue;
                }
                let i = grid.index(x, y, z);
                anyhow::ensure!(
                    d[i] as f64 > h,
                    "the swept surface reaches the grid's border (voxel {x}, {y}, {z}): grow \
                     the margin"
                );
                out.outside[i] = true;
                queue.push_back([x, y, z]);
            }
        }
    }
    while let Some([x, y, z]) = queue.pop_front() {
        let i = grid.index(x, y, z);
        let p = grid.point(x, y, z);
        for (axis, step) in NEIGHBOURS {
            let Some([cx, cy, cz]) = neighbour([x, y, z], axis, step, n) else {
                continue;
            };
            let j = grid.index(cx, cy, cz);
            if out.outside[j] {
                continue;
            }
            let free = if (d[i] as f64).min(d[j] as f64) > h {
                true
            } else {
                out.segment_tests += 1;
                !buckets.crosses(p, grid.point(cx, cy, cz), [x, y, z])
            };
            if free {
                out.outside[j] = true;
                queue.push_back([cx, cy, cz]);
            }
        }
    }
    out.outside_voxels = out.outside.iter().filter(|&&o| o).count();
    Ok(out)
}

/// The signed field: `+d` outside. Inside, `-d` would put the surface in the wrong place
/// wherever a primitive inside the volume (a face at an intermediate pose) is nearer than
/// the boundary, so an inside voxel next to outside ones gets the value that puts the zero
/// crossing of each of its edges to them where the segment first meets a primitive: with
/// `d_u` outside and the hit at `t` of the way, `-d_u (1 - t) / t` (exact for a plane), the
/// mean over its outside neighbours. Deeper inside voxels, which no sign change touches,
/// keep `-d`.
///
/// The sign is the classification's, never the distance's: a voxel centre on a primitive
/// has `d = 0` (and one a rounding error away from it may have too), so every magnitude is
/// at least `f32::MIN_POSITIVE`. A centre exactly on a primitive is never reached by the
/// fill (the segment to it touches the primitive), so it is inside; one the fill reached is
/// outside whatever fp32 distance the GPU gave it. The zero level then stays between the
/// samples, where the extraction places it on the primitives.
pub fn signed_field(field: &DistanceField, c: &Classification, primitives: &Mesh) -> Vec<f32> {
    let grid = &field.grid;
    let n = grid.n;
    let buckets = Buckets::new(grid, primitives);
    // (A NaN stays NaN, for the extraction to refuse.)
    let magnitude = |d: f32| {
        if d.is_nan() {
            d
        } else {
            d.max(f32::MIN_POSITIVE)
        }
    };
    let mut signed: Vec<f32> = field
        .values
        .iter()
        .zip(&c.outside)
        .map(|(&d, &o)| if o { magnitude(d) } else { -magnitude(d) })
        .collect();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let v = grid.index(x, y, z);
                if c.outside[v] {
                    continue;
                }
                let q = grid.point(x, y, z);
                let (mut sum, mut count) = (0.0, 0);
                for (axis, step) in NEIGHBOURS {
                    let Some([ux, uy, uz]) = neighbour([x, y, z], axis, step, n) else {
                        continue;
                    };
                    let u = grid.index(ux, uy, uz);
                    if !c.outside[u] {
                        continue;
                    }
                    if let Some(t) = buckets.first_hit(grid.point(ux, uy, uz), q, [ux, uy, uz]) {
                        let t = t.clamp(1e-3, 1.0);
                        sum += field.values[u] as f64 * (1.0 - t) / t;
                        count += 1;
                    }
                }
                if count > 0 {
                    signed[v] = -((sum / count as f64) as f32).max(f32::MIN_POSITIVE);
                }
            }
        }
    }
    signed
}

const NEIGHBOURS: [(usize, i64); 6] = [(0, -1), (0, 1), (1, -1), (1, 1), (2, -1), (2, 1)];

/// The face neighbour of `at` one `step` along `axis`, if inside the grid.
fn neighbour(at: [usize; 3], axis: usize, step: i64, n: usize) -> Option<[usize; 3]> {
    let mut c = at.map(|v| v as i64);
    c[axis] += step;
    if c.iter().any(|&v| v < 0 || v >= n as i64) {
        return None;
    }
    Some(c.map(|v| v as usize))
}

/// The primitives of non-zero area, each listed in the coarse cells near it.
pub struct Buckets {
    triangles: Vec<[DVec3; 3]>,
    cells: Vec<Vec<u32>>,
    per_axis: usize,
}

impl Buckets {
    pub fn new(grid: &Grid, mesh: &Mesh) -> Buckets {
        let per_axis = grid.n.div_ceil(BUCKET);
        let mut cells = vec![Vec::new(); per_axis * per_axis * per_axis];
        let mut triangles = Vec::new();
        let cell_side = BUCKET as f64 * grid.spacing;
        // A cell's centre to its corner, plus how far a tested segment reaches beyond the
        // voxel it starts from: a cube's diagonal (the extraction's tetrahedra use them).
        let reach = 0.5 * 3f64.sqrt() * cell_side + 3f64.sqrt() * grid.spacing;
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|v| mesh.positions[v as usize].as_dvec3());
            let normal = (b - a).cross(c - a);
            if normal.length_squared() == 0.0 {
                continue; // zero area: it separates nothing
            }
            let unit = normal.normalize();
            let id = triangles.len() as u32;
            triangles.push([a, b, c]);
            // The cells the triangle's box (grown by one voxel) overlaps, near its plane.
            let to_cell = |p: DVec3| (p - grid.origin) / cell_side;
            let lo = to_cell(a.min(b).min(c) - DVec3::splat(grid.spacing)).floor();
            let hi = to_cell(a.max(b).max(c) + DVec3::splat(grid.spacing)).floor();
            let clamp = |v: f64| v.clamp(0.0, (per_axis - 1) as f64) as usize;
            for cz in clamp(lo.z)..=clamp(hi.z) {
                for cy in clamp(lo.y)..=clamp(hi.y) {
                    for cx in clamp(lo.x)..=clamp(hi.x) {
                        let centre = grid.origin
                            + cell_side * DVec3::new(cx as f64, cy as f64, cz as f64)
                            + DVec3::splat(0.5 * cell_side - 0.5 * grid.spacing);
                        if (centre - a).dot(unit).abs() <= reach {
                            cells[(cz * per_axis + cy) * per_axis + cx].push(id);
                        }
                    }
                }
            }
        }
        Buckets {
            triangles,
            cells,
            per_axis,
        }
    }

    /// Whether the segment `p q` (from voxel `from` to a face neighbour) meets a primitive.
    fn crosses(&self, p: DVec3, q: DVec3, from: [usize; 3]) -> bool {
        let [cx, cy, cz] = from.map(|c| c / BUCKET);
        self.cells[(cz * self.per_axis + cy) * self.per_axis + cx]
            .iter()
            .any(|&t| segment_meets_triangle(p, q, self.triangles[t as usize]))
    }

    /// Where the segment `p q` (from voxel `from`) first meets a primitive, as a fraction
    /// of its length (f64 ray-triangle intersection); `None` if it meets none.
    fn first_hit(&self, p: DVec3, q: DVec3, from: [usize; 3]) -> Option<f64> {
        self.first_crossing(p, q, from).map(|(t, _)| t)
    }

    /// `Buckets::first_hit` and the unit normal of the primitive met there (either way
    /// round). `p` and `q` may be any two corners of one grid cube, `from` being `p`'s voxel.
    pub fn first_crossing(&self, p: DVec3, q: DVec3, from: [usize; 3]) -> Option<(f64, DVec3)> {
        let [cx, cy, cz] = from.map(|c| c / BUCKET);
        self.cells[(cz * self.per_axis + cy) * self.per_axis + cx]
            .iter()
            .map(|&t| self.triangles[t as usize])
            .filter_map(|tri| segment_hit(p, q, tri).map(|t| (t, tri)))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(t, [a, b, c])| (t, (b - a).cross(c - a).normalize()))
    }
}

/// The fraction of `p q` at which it crosses the triangle (Möller and Trumbore, f64, edges
/// included with a relative slack of 1e-12); `None` when parallel or missing.
fn segment_hit(p: DVec3, q: DVec3, [a, b, c]: [DVec3; 3]) -> Option<f64> {
    let dir = q - p;
    let (e1, e2) = (b - a, c - a);
    let h = dir.cross(e2);
    let det = e1.dot(h);
    if det.abs() <= 1e-300 {
        return None;
    }
    let s = p - a;
    let u = s.dot(h) / det;
    let k = s.cross(e1);
    let v = dir.dot(k) / det;
    let t = e2.dot(k) / det;
    let slack = 1e-12;
    (u >= -slack && v >= -slack && u + v <= 1.0 + slack && (-slack..=1.0 + slack).contains(&t))
        .then_some(t.clamp(0.0, 1.0))
}

fn c3(p: DVec3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}

/// Whether the closed segment `p q` meets the closed triangle `a b c` (non-zero area): its
/// ends not strictly on one side of the plane, and the line through it not strictly outside
/// an edge. A segment lying in the triangle's plane counts as meeting it when it touches the
/// plane inside the triangle's box (conservative: it blocks the fill).
pub fn segment_meets_triangle(p: DVec3, q: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    if sp > 0.0 && sq > 0.0 || sp < 0.0 && sq < 0.0 {
        return false;
    }
    if sp == 0.0 && sq == 0.0 {
        let lo = a.min(b).min(c);
        let hi = a.max(b).max(c);
        return p.min(q).cmple(hi).all() && p.max(q).cmpge(lo).all();
    }
    let e = [orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a)];
    !(e.iter().any(|&s| s > 0.0) && e.iter().any(|&s| s < 0.0))
}
