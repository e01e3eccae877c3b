//! Checks on the input surface that decide whether a result can be trusted: the analytic
//! method needs a closed, outward-oriented mesh; the GPU method runs on anything renderable
//! but a hole lets the ray parity (and so eq. 4) go wrong, so it is reported.

use crate::mesh::Mesh;
use serde::Serialize;
use std::collections::HashMap;

/// What [`check`] found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct SurfaceReport {
    /// Directed edges whose reverse is missing (edges of holes).
    pub open_edges: usize,
    /// Directed edges used by more than one triangle in the same direction (a flipped
    /// neighbour or a non-manifold edge).
    pub inconsistent_edges: usize,
    /// Triangles of zero area.
    pub degenerate_triangles: usize,
    /// Triangles whose three corners another triangle already has (duplicated faces).
    pub duplicate_triangles: usize,
}

impl SurfaceReport {
    /// Closed and consistently oriented: the divergence theorem applies.
    pub fn is_closed(&self) -> bool {
        self.open_edges == 0 && self.inconsistent_edges == 0
    }

    /// What keeps the surface from being closed, in words (empty when it is closed).
    pub fn problems(&self) -> String {
        let mut parts = Vec::new();
        if self.open_edges > 0 {
            parts.push(format!("{} open edges", self.open_edges));
        }
        if self.inconsistent_edges > 0 {
            parts.push(format!(
                "{} edges used in the same direction by two faces",
                self.inconsistent_edges
            ));
        }
        if self.duplicate_triangles > 0 {
            parts.push(format!(
                "{} faces that repeat another face's corners",
                self.duplicate_triangles
            ));
        }
        parts.join(", ")
    }
}

/// Counts open and inconsistent edges. Vertices are matched by position, so meshes with
/// duplicated seam vertices (UV spheres, OBJ files with split normals) count as closed.
pub fn check(mesh: &Mesh) -> SurfaceReport {
    let ids = weld_by_position(mesh);
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    let mut report = SurfaceReport::default();
    let mut faces = std::collections::HashSet::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let mut corners = tri.map(|v| ids[v as usize]);
        corners.sort_unstable();
        if !faces.insert(corners) {
            report.duplicate_triangles += 1;
        }
        let [a, b, c] = mesh.triangle(t);
        if (b - a).cross(c - a).length_squared() == 0.0 {
            report.degenerate_triangles += 1;
        }
        for k in 0..3 {
            let (i, j) = (ids[tri[k] as usize], ids[tri[(k + 1) % 3] as usize]);
            if i != j {
                *directed.entry((i, j)).or_default() += 1;
            }
        }
    }
    for (&(i, j), &count) in &directed {
        let reverse = directed.get(&(j, i)).copied().unwrap_or(0);
        report.open_edges += count.saturating_sub(reverse);
        report.inconsistent_edges += count.saturating_sub(1);
    }
    report
}

/// One id per distinct position (the first index holding it).
pub fn weld_by_position(mesh: &Mesh) -> Vec<u32> {
    let mut first: HashMap<[u32; 3], u32> = HashMap::new();
    mesh.positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let key = p.to_array().map(|c| (c + 0.0).to_bits());
            *first.entry(key).or_insert(i as u32)
        })
        .collect()
}
