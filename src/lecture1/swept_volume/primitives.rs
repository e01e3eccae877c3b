//! The superset of the swept volume's boundary (Kim et al. 2003, stage 1, a reconstruction):
//! the model's triangles at every sampled pose, and between consecutive poses the ruled
//! surface each edge sweeps, taken as the bilinear quad between the edge's two positions and
//! split into triangles within a tolerance ε.
//!
//! The bilinear quad `P(u, v) = (1-u)(1-v) a0 + u(1-v) b0 + (1-u)v a1 + uv b1` (edge `a b`
//! at poses k and k+1) has the constant twist `w = a0 - b0 - a1 + b1`; split into `m x m` cells
//! of two triangles each, a cell's triangles are within `|w| / (4 m^2)` of the quad, so
//! `m = ceil(sqrt(|w| / (4 ε)))`. Every edge of one step uses the step's largest `m`, so that
//! the quads of edges that share a vertex share their sides' points.

use super::path::Pose;
use crate::mesh::Mesh;
use glam::DVec3;

/// The primitives as one triangle soup, and how it was made.
#[derive(Clone, Debug)]
pub struct Primitives {
    pub mesh: Mesh,
    /// Triangles from the model at the poses.
    pub face_triangles: usize,
    /// Triangles from the ruled quads.
    pub ruled_triangles: usize,
    /// The largest split of a quad side (the `m` above) over the steps.
    pub most_splits: usize,
}

/// The model's distinct undirected edges (by vertex index; weld the model first).
pub fn edges(mesh: &Mesh) -> Vec<[u32; 2]> {
    let mut edges: Vec<[u32; 2]> = mesh
        .triangles
        .iter()
        .flat_map(|t| [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]])
        .filter(|e| e[0] != e[1])
        .map(|[a, b]| [a.min(b), a.max(b)])
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// The primitives of `mesh` (welded) moving through `poses`, ruled quads within `epsilon`.
pub fn primitives(mesh: &Mesh, poses: &[Pose], epsilon: f64) -> anyhow::Result<Primitives> {
    anyhow::ensure!(
        epsilon.is_finite() && epsilon > 0.0,
        "the tolerance ε must be positive and finite, not {epsilon}"
    );
    let posed: Vec<Vec<DVec3>> = poses
        .iter()
        .map(|pose| {
            mesh.positions
                .iter()
                .map(|p| pose.apply(p.as_dvec3()))
                .collect()
        })
        .collect();
    let mut positions: Vec<DVec3> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    // The faces at each pose.
    for at in &posed {
        let first = positions.len() as u32;
        positions.extend(at);
        triangles.extend(mesh.triangles.iter().map(|t| t.map(|v| v + first)));
    }
    let face_triangles = triangles.len();
    // The ruled quads of each step.
    let edges = edges(mesh);
    let mut most_splits = 0;
    for step in posed.windows(2) {
        let (p0, p1) = (&step[0], &step[1]);
        let twist = edges
            .iter()
            .map(|&[a, b]| {
                let (a, b) = (a as usize, b as usize);
                (p0[a] - p0[b] - p1[a] + p1[b]).length()
            })
            .fold(0.0, f64::max);
        let m = ((twist / (4.0 * epsilon)).sqrt().ceil() as usize).max(1);
        anyhow::ensure!(
            m <= 4096,
            "a ruled quad would need {m} x {m} cells for ε = {epsilon}: sample more poses or \
             allow a larger ε"
        );
        most_splits = most_splits.max(m);
        for &[a, b] in &edges {
            let (a, b) = (a as usize, b as usize);
            let point = |u: f64, v: f64| {
                (1.0 - u) * (1.0 - v) * p0[a]
                    + u * (1.0 - v) * p0[b]
                    + (1.0 - u) * v * p1[a]
                    + u * v * p1[b]
            };
            let first = positions.len() as u32;
            for j in 0..=m {
                for i in 0..=m {
                    positions.push(point(i as f64 / m as f64, j as f64 / m as f64));
                }
            }
            let at = |i: usize, j: usize| first + (j * (m + 1) + i) as u32;
            for j in 0..m {
                for i in 0..m {
                    triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                    triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
    }
    let ruled_triangles = triangles.len() - face_triangles;
    let positions = positions.iter().map(|p| p.as_vec3()).collect();
    Ok(Primitives {
        mesh: Mesh::new(positions, triangles),
        face_triangles,
        ruled_triangles,
        most_splits,
    })
}
