//! The CPU reference: the same octree (built by [`super::levels::cpu_levels`]) traversed the
//! same way in f64, and a flat 3D DDA in f64 that also says where a pixel is ill-conditioned.
//!
//! Tolerance, stated once: a ray that passes within `EDGE` grid units of a voxel edge or corner
//! where it changes voxels may be walked either side of it by fp32 rounding (~1e-5 voxel for
//! grids up to 128 seen from a few grid sides away), and so meet another first voxel. The flat
//! DDA marks those rays ambiguous; every other pixel's first voxel must be the reference's
//! exactly, hit or miss, and its entry parameter within `T_TOL`.

use super::cast::{CastFrame, CastPixel, WORLD_SIDE};
use super::levels::Level;
use crate::lecture3::displacement::Camera;
use glam::{DVec3, IVec3};
use serde::Serialize;

/// Distance (grid units) to a voxel edge under which a crossing is ambiguous.
pub const EDGE: f64 = 1e-4;
/// The largest |GPU - CPU| entry parameter (world units) on judged hits: fp32 rounding of
/// parameters up to ~10 world units, with margin.
pub const T_TOL: f64 = 1e-4;

/// What a CPU cast found.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CpuHit {
    pub voxel: [i32; 3],
    pub t: f64,
}

/// The parameter interval of `o + t d` inside `[0, n]^3` from 0 on.
fn box_interval(o: DVec3, d: DVec3, n: f64) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for k in 0..3 {
        if d[k] == 0.0 {
            if o[k] < 0.0 || o[k] > n {
                return None;
            }
            continue;
        }
        let (a, b) = ((0.0 - o[k]) / d[k], (n - o[k]) / d[k]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    (t0 <= t1).then_some((t0, t1))
}

/// The grid-space ray of pixel (px, py).
fn grid_ray(camera: &Camera, n: u32, px: u32, py: u32) -> (DVec3, DVec3) {
    let scale = n as f64 / WORLD_SIDE as f64;
    let eye = camera.eye.as_dvec3();
    (eye * scale, camera.pixel_direction(px, py) * scale)
}

/// Where the ray leaves the box `[lo, hi)` along each axis.
fn exits(o: DVec3, d: DVec3, lo: IVec3, hi: IVec3) -> DVec3 {
    DVec3::from_array(std::array::from_fn(|k| {
        if d[k] > 0.0 {
            (hi[k] as f64 - o[k]) / d[k]
        } else if d[k] < 0.0 {
            (lo[k] as f64 - o[k]) / d[k]
        } else {
            f64::INFINITY
        }
    }))
}

fn exit_axis(t: DVec3) -> usize {
    if t.x <= t.y && t.x <= t.z {
        0
    } else if t.y <= t.z {
        1
    } else {
        2
    }
}

/// The first occupied voxel along the ray, by the octree traversal (as `octree_cast.frag`),
/// and its step count.
pub fn octree_cast(levels: &[Level], o: DVec3, d: DVec3) -> (Option<CpuHit>, u32) {
    let n = levels[0].n as i32;
    let top = levels.len() as i32 - 1;
    let Some((t0, t1)) = box_interval(o, d, n as f64) else {
        return (None, 0);
    };
    let mut t = t0;
    let mut cell = (o + t * d)
        .floor()
        .as_ivec3()
        .clamp(IVec3::ZERO, IVec3::splat(n - 1));
    let mut level = top;
    for it in 1.. {
        let node = cell >> level;
        let (lo, hi) = (node << level, (node << level) + (1 << level));
        if levels[level as usize].at(node.x as u32, node.y as u32, node.z as u32) {
            if level == 0 {
                return (
                    Some(CpuHit {
                        voxel: cell.to_array(),
                        t,
                    }),
                    it,
                );
            }
            level -= 1;
            continue;
        }
        let t_side = exits(o, d, lo, hi);
        let t_exit = t_side.min_element();
        if t_exit >= t1 {
            return (None, it);
        }
        let axis = exit_axis(t_side);
        t = t_exit;
        let mut next = (o + t * d).floor().as_ivec3().clamp(lo, hi - 1);
        next[axis] = if d[axis] > 0.0 {
            hi[axis]
        } else {
            lo[axis] - 1
        };
        if next.min_element() < 0 || next.max_element() >= n {
            return (None, it);
        }
        cell = next;
        level = (level + 1).min(top);
    }
    unreachable!("the loop returns")
}

/// The first occupied voxel along the ray by a flat DDA, and whether the walk passed within
/// `EDGE` of a voxel edge before it (ill-conditioned).
pub fn flat_cast(leaf: &Level, o: DVec3, d: DVec3) -> (Option<CpuHit>, bool) {
    let n = leaf.n as i32;
    let Some((t0, t1)) = box_interval(o, d, n as f64) else {
        return (None, false);
    };
    // Near an edge: some coordinate other than the crossing axis close to an integer.
    let near_edge = |t: f64, axis: Option<usize>| {
        let p = o + t * d;
        (0..3).any(|k| Some(k) != axis && (p[k] - p[k].round()).abs() < EDGE)
    };
    let mut t = t0;
    // The axis whose side the ray enters through (none from inside the box).
    let near_plane = |k: usize| {
        if d[k] == 0.0 {
            f64::NEG_INFINITY
        } else {
            ((0.0 - o[k]) / d[k]).min((n as f64 - o[k]) / d[k])
        }
    };
    let entry = (0..3).max_by(|&a, &b| near_plane(a).total_cmp(&near_plane(b)));
    let mut ambiguous = near_edge(t0, entry.filter(|_| t0 > 0.0));
    let mut cell = (o + t * d)
        .floor()
        .as_ivec3()
        .clamp(IVec3::ZERO, IVec3::splat(n - 1));
    loop {
        if leaf.at(cell.x as u32, cell.y as u32, cell.z as u32) {
            return (
                Some(CpuHit {
                    voxel: cell.to_array(),
                    t,
                }),
                ambiguous,
            );
        }
        let t_side = exits(o, d, cell, cell + 1);
        let t_exit = t_side.min_element();
        let axis = exit_axis(t_side);
        // Also where the exit leaves the box near its edge: another walk may stop inside.
        ambiguous |= near_edge(t_exit, Some(axis));
        if t_exit >= t1 {
            return (None, ambiguous);
        }
        t = t_exit;
        cell[axis] += if d[axis] > 0.0 { 1 } else { -1 };
        if cell[axis] < 0 || cell[axis] >= n {
            return (None, ambiguous);
        }
    }
}

/// How a GPU cast compares with the CPU, pixel by pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct CastComparison {
    pub pixels: usize,
    pub cpu_hits: usize,
    /// Ill-conditioned pixels (not judged).
    pub ambiguous: usize,
    /// Judged pixels whose first voxel (or hit / miss) is not the CPU's.
    pub wrong_voxel: usize,
    /// Judged hits whose entry parameter is more than `T_TOL` from the CPU's.
    pub wrong_t: usize,
    /// Pixels where the CPU octree traversal and the CPU flat DDA disagree (judged ones).
    pub cpu_octree_vs_flat: usize,
    pub unfinished: usize,
    /// Mean steps per pixel of the CPU octree traversal (the GPU's should match it).
    pub cpu_octree_steps: f64,
}

/// The CPU's answers for every pixel of `camera`.
pub struct CastReference {
    /// Per pixel: the flat DDA's hit, the octree traversal's hit and steps, ambiguous.
    pixels: Vec<(Option<CpuHit>, Option<CpuHit>, u32, bool)>,
}

impl CastReference {
    pub fn trace(levels: &[Level], camera: &Camera) -> CastReference {
        let n = levels[0].n;
        let pixels = (0..camera.height)
            .flat_map(|py| (0..camera.width).map(move |px| (px, py)))
            .map(|(px, py)| {
                let (o, d) = grid_ray(camera, n, px, py);
                let (flat, ambiguous) = flat_cast(&levels[0], o, d);
                let (octree, steps) = octree_cast(levels, o, d);
                (flat, octree, steps, ambiguous)
            })
            .collect();
        CastReference { pixels }
    }

    /// The CPU's first voxel per pixel (the flat DDA's), rows from the bottom.
    pub fn hits(&self) -> Vec<Option<CpuHit>> {
        self.pixels.iter().map(|p| p.0).collect()
    }

    pub fn judge(&self, frame: &CastFrame) -> CastComparison {
        let mut c = CastComparison {
            pixels: self.pixels.len(),
            ..CastComparison::default()
        };
        let mut steps = 0.0;
        for (pixel, &(flat, octree, cpu_steps, ambiguous)) in
            frame.pixels().iter().zip(&self.pixels)
        {
            steps += cpu_steps as f64;
            c.cpu_hits += flat.is_some() as usize;
            if *pixel == CastPixel::Unfinished {
                c.unfinished += 1;
                continue;
            }
            if ambiguous {
                c.ambiguous += 1;
                continue;
            }
            c.cpu_octree_vs_flat += (flat != octree) as usize;
            match (*pixel, flat) {
                (CastPixel::Miss, None) => {}
                (CastPixel::Hit { voxel, t, .. }, Some(h)) if voxel.to_array() == h.voxel => {
                    c.wrong_t += ((t - h.t).abs() > T_TOL) as usize;
                }
                _ => c.wrong_voxel += 1,
            }
        }
        c.cpu_octree_steps = steps / self.pixels.len().max(1) as f64;
        c
    }
}
