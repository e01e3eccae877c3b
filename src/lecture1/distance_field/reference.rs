//! The CPU reference: every voxel against every triangle, exact point-triangle distances in
//! f64 (quadratic; for tests and small grids).

use super::point_triangle::point_triangle;
use super::{DistanceField, Grid};
use crate::mesh::Mesh;
use glam::DVec3;

/// The field of `mesh` on `grid` by brute force, `min(distance, clamp)` with a clamp.
pub fn brute_force(mesh: &Mesh, grid: &Grid, clamp: Option<f64>) -> DistanceField {
    let triangles: Vec<[DVec3; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| mesh.positions[v as usize].as_dvec3()))
        .collect();
    let mut values = vec![0.0f32; grid.len()];
    for z in 0..grid.n {
        for y in 0..grid.n {
            for x in 0..grid.n {
                let p = grid.point(x, y, z);
                let d = distance(p, &triangles).min(clamp.unwrap_or(f64::INFINITY));
                values[grid.index(x, y, z)] = d as f32;
            }
        }
    }
    DistanceField {
        grid: *grid,
        values,
        clamp,
    }
}

/// Distance from `p` to the nearest of `triangles`.
pub fn distance(p: DVec3, triangles: &[[DVec3; 3]]) -> f64 {
    triangles
        .iter()
        .map(|&t| point_triangle(p, t))
        .fold(f64::INFINITY, f64::min)
}
