//! The reference answer: every triangle of X against every triangle of Y, with the same
//! predicate as the pipeline. Quadratic; for tests and for checking small inputs.

use super::tri_test::{triangles_intersect, Predicate};
use crate::mesh::Mesh;
use glam::Vec3;

/// All intersecting pairs `(a, b)` (triangle of X, triangle of Y), sorted.
pub fn all_pairs(
    x: &Mesh,
    positions_x: &[Vec3],
    y: &Mesh,
    positions_y: &[Vec3],
    predicate: Predicate,
) -> Vec<(u32, u32)> {
    let corners = |m: &Mesh, p: &[Vec3]| -> Vec<[Vec3; 3]> {
        m.triangles
            .iter()
            .map(|t| t.map(|v| p[v as usize]))
            .collect()
    };
    let tx = corners(x, positions_x);
    let ty = corners(y, positions_y);
    let mut pairs = Vec::new();
    for (a, ta) in tx.iter().enumerate() {
        for (b, tb) in ty.iter().enumerate() {
            if triangles_intersect(ta, tb, predicate) {
                pairs.push((a as u32, b as u32));
            }
        }
    }
    pairs
}
