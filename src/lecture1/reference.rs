//! The CPU reference answers: every triangle pair tested by brute force with paper 1's exact
//! predicate ([`crate::collide::tri_test`], exact orientation predicates). Quadratic; for
//! tests, for checking small inputs, and as the baseline of the comparison.

use super::weld::share_vertex;
use crate::collide::brute_force::all_pairs;
use crate::collide::{triangles_intersect, Predicate};
use crate::mesh::Mesh;
use glam::Vec3;

/// Self-intersection of one welded mesh ([`super::weld::weld`]): every pair `(i, j)`, `i < j`,
/// of intersecting triangles that share no vertex, sorted.
pub fn self_pairs(mesh: &Mesh, positions: &[Vec3]) -> Vec<(u32, u32)> {
    let corners: Vec<[Vec3; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| positions[v as usize]))
        .collect();
    let mut pairs = Vec::new();
    for i in 0..corners.len() {
        for j in i + 1..corners.len() {
            if !share_vertex(&mesh.triangles[i], &mesh.triangles[j])
                && triangles_intersect(&corners[i], &corners[j], Predicate::Exact)
            {
                pairs.push((i as u32, j as u32));
            }
        }
    }
    pairs
}

/// Two models: every pair `(i, j)`, `i` a triangle of A and `j` of B, that intersects, sorted.
pub fn pairs_between(a: &Mesh, b: &Mesh) -> Vec<(u32, u32)> {
    all_pairs(a, &a.positions, b, &b.positions, Predicate::Exact)
}
