//! Fig. 1-(a): the skinning data of a mesh in four 1D float textures of m texels each:
//! position (w = 1), normal (w = 0), up to 4 bone indices (as floats) and their weights.

use crate::gl::{Context, GlError, Texture, TextureFormat};

use super::validate::SkinnedMesh;

/// The four texel arrays, RGBA per vertex.
#[derive(Clone, Debug, PartialEq)]
pub struct VertexTexels {
    pub position: Vec<f32>,
    pub normal: Vec<f32>,
    pub bone_index: Vec<f32>,
    pub bone_weight: Vec<f32>,
}

/// Lays a skinned mesh out as texels (vertex v at texel v).
pub fn pack(mesh: &SkinnedMesh) -> VertexTexels {
    let m = mesh.vertex_count();
    let mut t = VertexTexels {
        position: Vec::with_capacity(4 * m),
        normal: Vec::with_capacity(4 * m),
        bone_index: Vec::with_capacity(4 * m),
        bone_weight: Vec::with_capacity(4 * m),
    };
    for v in 0..m {
        let (p, n) = (mesh.mesh.positions[v], mesh.normals[v]);
        t.position.extend([p.x, p.y, p.z, 1.0]);
        t.normal.extend([n.x, n.y, n.z, 0.0]);
        t.bone_index.extend(mesh.bone_indices[v].map(|i| i as f32));
        t.bone_weight.extend(mesh.bone_weights[v]);
    }
    t
}

/// The vertex textures of one LOD mesh, uploaded once.
pub struct VertexTextures {
    pub position: Texture,
    pub normal: Texture,
    pub bone_index: Texture,
    pub bone_weight: Texture,
    /// m, the number of vertices.
    pub vertices: u32,
}

impl VertexTextures {
    pub fn upload(ctx: &Context, mesh: &SkinnedMesh) -> Result<Self, GlError> {
        // region: vertex-textures
        let texels = pack(mesh);
        let m = mesh.vertex_count() as u32;
        let texture = |data: &[f32]| -> Result<Texture, GlError> {
            let t = Texture::new_1d(ctx, m, TextureFormat::Rgba32F)?;
            t.upload_f32(data)?;
            Ok(t)
        };
        Ok(Self {
            position: texture(&texels.position)?,
            normal: texture(&texels.normal)?,
            bone_index: texture(&texels.bone_index)?,
            bone_weight: texture(&texels.bone_weight)?,
            vertices: m,
        })
        // endregion
    }
}
