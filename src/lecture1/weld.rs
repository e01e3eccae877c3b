//! Which triangles are neighbours: self-collision ignores pairs that share a vertex, and
//! vertices at equal positions count as one (an OBJ often splits a vertex along a seam of
//! normals or texture coordinates). Welding by position makes that one rule.

use crate::mesh::Mesh;
use std::collections::HashMap;

/// `mesh` with every group of vertices at bit-equal positions (`-0.0` equal to `0.0`) merged
/// into the first of them. Triangle indices and order are kept; only their vertex indices
/// change, so triangle `t` of the result is triangle `t` of `mesh`.
pub fn weld(mesh: &Mesh) -> Mesh {
    let mut first: HashMap<[u32; 3], u32> = HashMap::new();
    let mut canonical = Vec::with_capacity(mesh.positions.len());
    for (v, p) in mesh.positions.iter().enumerate() {
        // Adding +0.0 turns -0.0 into +0.0 and leaves every other value as it is.
        let key = [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits());
        canonical.push(*first.entry(key).or_insert(v as u32));
    }
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| canonical[v as usize]))
        .collect();
    Mesh::new(mesh.positions.clone(), triangles)
}

/// Do two triangles of a welded mesh share a vertex?
pub fn share_vertex(a: &[u32; 3], b: &[u32; 3]) -> bool {
    a.iter().any(|v| b.contains(v))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn split_vertices_at_one_position_become_one() {
        // Two triangles meeting along an edge, stored with their own copies of it (one copy
        // at -0.0), and a third triangle apart.
        let p = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(-0.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(5.0, 5.0, 5.0),
            Vec3::new(6.0, 5.0, 5.0),
            Vec3::new(5.0, 6.0, 5.0),
        ];
        let mesh = Mesh::new(p, vec![[0, 1, 2], [3, 4, 5], [6, 7, 8]]);
        let welded = weld(&mesh);
        assert_eq!(welded.triangles[1], [0, 2, 5]);
        assert!(share_vertex(&welded.triangles[0], &welded.triangles[1]));
        assert!(!share_vertex(&welded.triangles[0], &welded.triangles[2]));
        assert!(!share_vertex(&mesh.triangles[0], &mesh.triangles[1]));
    }
}
