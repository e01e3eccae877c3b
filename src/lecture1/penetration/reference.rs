//! The CPU reference. For one convex sum the depth is exact: with the origin inside, the
//! nearest boundary point is the foot of the perpendicular on the nearest face plane, so the
//! depth is the smallest plane offset and the direction that plane's normal. For a union, the
//! same per-ray exit the GPU computes, in f64, pixel by pixel of the same cube layout, so that
//! the tests compare the two T buffers texel by texel.

use super::cube_map::{faces, NEAR};
use super::minkowski::{Plane, Polytope};
use glam::DVec3;

/// Exact depth of one convex sum and its direction; `None` when the origin lies outside it by
/// more than `tolerance` (the pieces do not overlap).
pub fn convex_depth(sum: &Polytope, tolerance: f64) -> Option<(f64, DVec3)> {
    let nearest = sum
        .planes
        .iter()
        .min_by(|p, q| p.offset.total_cmp(&q.offset))?;
    (nearest.offset >= -tolerance).then(|| (nearest.offset.max(0.0), nearest.normal))
}

/// (entry, exit) of the ray `t * direction` (direction of unit length) through a sum given by
/// its planes; entry > exit when the ray misses it.
pub fn ray_interval(planes: &[Plane], direction: DVec3) -> (f64, f64) {
    let (mut entry, mut exit) = (f64::NEG_INFINITY, f64::INFINITY);
    for p in planes {
        let along = p.normal.dot(direction);
        if along > 0.0 {
            exit = exit.min(p.offset / along);
        } else if along < 0.0 {
            entry = entry.max(p.offset / along);
        } else if p.offset < 0.0 {
            entry = f64::INFINITY;
        }
    }
    (entry, exit)
}

/// Where the ray from the origin along `direction` (unit) first leaves the union of `sums`:
/// starting from T = 0, every sum entered at or before T and left after it raises T to its
/// exit, until none does. Exits nearer than `near` are not counted (the views' near plane).
pub fn union_exit(sums: &[Polytope], direction: DVec3, near: f64) -> f64 {
    let intervals: Vec<(f64, f64)> = sums
        .iter()
        .map(|s| ray_interval(&s.planes, direction))
        .filter(|&(entry, exit)| exit > near && entry <= exit)
        .collect();
    let mut t = 0.0;
    loop {
        let raised = intervals
            .iter()
            .filter(|&&(entry, exit)| entry <= t && exit > t)
            .map(|&(_, exit)| exit)
            .fold(t, f64::max);
        if raised == t {
            return t;
        }
        t = raised;
    }
}

/// The T buffer of the `6N x N` cube layout (row-major from the bottom row), for sums in the
/// unit frame, as the GPU computes it.
pub fn t_buffer(sums: &[Polytope], resolution: usize) -> Vec<f32> {
    let faces = faces();
    let n = resolution;
    let mut out = vec![0.0f32; 6 * n * n];
    for j in 0..n {
        for (f, face) in faces.iter().enumerate() {
            for i in 0..n {
                let d = face.ray(i, j, n).normalize();
                out[j * 6 * n + f * n + i] = union_exit(sums, d, NEAR as f64) as f32;
            }
        }
    }
    out
}

/// The sums' planes rounded to fp32, as the GPU receives them (for a like-for-like
/// comparison of T buffers).
pub fn rounded_to_f32(sums: &[Polytope]) -> Vec<Polytope> {
    sums.iter()
        .map(|s| Polytope {
            planes: s
                .planes
                .iter()
                .map(|p| Plane {
                    normal: p.normal.as_vec3().as_dvec3(),
                    offset: p.offset as f32 as f64,
                })
                .collect(),
            ..s.clone()
        })
        .collect()
}
