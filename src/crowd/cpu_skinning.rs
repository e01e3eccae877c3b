//! The CPU reference: linear blend skinning in f64,
//! `v' = sum_i w_i M_{b_i} v` and `n' = normalize(sum_i w_i R_{b_i} n)`,
//! the same formula the pixel shader of pass 1 and the vertex-shader baseline evaluate in
//! fp32. Tests compare the GPU's vertices with these.

use glam::{DAffine3, DVec3};

use super::validate::SkinnedMesh;

/// Skinned positions and normals of one character.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SkinnedVertices {
    pub positions: Vec<DVec3>,
    pub normals: Vec<DVec3>,
}

/// Linear blend skinning of `mesh` by the skinning matrices `bones` (bind pose to world).
pub fn skin(mesh: &SkinnedMesh, bones: &[DAffine3]) -> SkinnedVertices {
    let mut out = SkinnedVertices {
        positions: Vec::with_capacity(mesh.vertex_count()),
        normals: Vec::with_capacity(mesh.vertex_count()),
    };
    for v in 0..mesh.vertex_count() {
        let p = mesh.mesh.positions[v].as_dvec3();
        let n = mesh.normals[v].as_dvec3();
        let mut position = DVec3::ZERO;
        let mut normal = DVec3::ZERO;
        for (&bone, &weight) in mesh.bone_indices[v].iter().zip(&mesh.bone_weights[v]) {
            let m = &bones[bone as usize];
            position += weight as f64 * m.transform_point3(p);
            normal += weight as f64 * m.transform_vector3(n);
        }
        out.positions.push(position);
        out.normals.push(normal.normalize_or_zero());
    }
    out
}
