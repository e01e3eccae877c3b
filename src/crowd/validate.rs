//! Validation of skinning data: every vertex has at most 4 influences whose weights are
//! non-negative and sum to one, and whose bone indices exist in the skeleton.
//!
//! A skinned mesh that breaks these rules would be skinned to garbage by both the pixel
//! shader and the vertex shader without any GL error, so it is rejected before upload.

use thiserror::Error;

use crate::mesh::Mesh;
use glam::Vec3;

/// How far a vertex's weights may sum from one (fp32 weights rounded from f64 differ by
/// a few ulp; anything beyond 1e-4 is an authoring error, not rounding).
pub const WEIGHT_SUM_TOLERANCE: f32 = 1e-4;

/// Everything that can be wrong with a skeleton or its skinning data.
#[derive(Debug, Error, PartialEq)]
pub enum SkinError {
    #[error("skeleton has no bones")]
    EmptySkeleton,
    #[error("bone {bone} has no parent but is not the first bone (one root only)")]
    SecondRoot { bone: usize },
    #[error("bone {bone} names parent {parent}, which does not come before it")]
    ParentAfterChild { bone: usize, parent: usize },
    #[error(
        "vertex {vertex}: bone weights sum to {sum}, not 1 (tolerance {WEIGHT_SUM_TOLERANCE})"
    )]
    WeightSum { vertex: usize, sum: f32 },
    #[error("vertex {vertex}: weight {slot} is {weight}, weights must be finite and >= 0")]
    BadWeight {
        vertex: usize,
        slot: usize,
        weight: f32,
    },
    #[error("vertex {vertex}: bone index {index} in slot {slot} is out of range (skeleton has {bones} bones)")]
    BoneIndex {
        vertex: usize,
        slot: usize,
        index: u32,
        bones: usize,
    },
    #[error("skinning data has {got} {what} for {vertices} vertices")]
    LengthMismatch {
        what: &'static str,
        got: usize,
        vertices: usize,
    },
    #[error("triangle {triangle} uses vertex {index}, but the mesh has {vertices} vertices")]
    TriangleIndex {
        triangle: usize,
        index: u32,
        vertices: usize,
    },
}

/// A mesh with linear-blend-skinning data, in the bind pose, model space.
#[derive(Clone, Debug, PartialEq)]
pub struct SkinnedMesh {
    pub mesh: Mesh,
    pub normals: Vec<Vec3>,
    /// Up to 4 bones per vertex; unused slots have weight 0 (and any valid index).
    pub bone_indices: Vec<[u32; 4]>,
    pub bone_weights: Vec<[f32; 4]>,
}

impl SkinnedMesh {
    /// Builds a skinned mesh, rejecting data that breaks the skinning rules.
    pub fn new(
        mesh: Mesh,
        normals: Vec<Vec3>,
        bone_indices: Vec<[u32; 4]>,
        bone_weights: Vec<[f32; 4]>,
        bone_count: usize,
    ) -> Result<Self, SkinError> {
        let skinned = Self {
            mesh,
            normals,
            bone_indices,
            bone_weights,
        };
        skinned.validate(bone_count)?;
        Ok(skinned)
    }

    pub fn vertex_count(&self) -> usize {
        self.mesh.positions.len()
    }

    pub fn triangle_count(&self) -> usize {
        self.mesh.triangles.len()
    }

    /// Checks lengths, triangle indices, weights (finite, >= 0, sum 1) and bone indices.
    pub fn validate(&self, bone_count: usize) -> Result<(), SkinError> {
        let vertices = self.vertex_count();
        for (what, got) in [
            ("normals", self.normals.len()),
            ("bone index sets", self.bone_indices.len()),
            ("weight sets", self.bone_weights.len()),
        ] {
            if got != vertices {
                return Err(SkinError::LengthMismatch {
                    what,
                    got,
                    vertices,
                });
            }
        }
        for (triangle, tri) in self.mesh.triangles.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= vertices) {
                return Err(SkinError::TriangleIndex {
                    triangle,
                    index,
                    vertices,
                });
            }
        }
        for vertex in 0..vertices {
            validate_influences(
                vertex,
                &self.bone_indices[vertex],
                &self.bone_weights[vertex],
                bone_count,
            )?;
        }
        Ok(())
    }
}

/// One vertex's influences: weights finite and >= 0, summing to one; indices of bones
/// that carry weight inside the skeleton (an index with weight 0 is still checked, since
/// the shaders fetch it).
fn validate_influences(
    vertex: usize,
    indices: &[u32; 4],
    weights: &[f32; 4],
    bones: usize,
) -> Result<(), SkinError> {
    for (slot, &weight) in weights.iter().enumerate() {
        if !weight.is_finite() || weight < 0.0 {
            return Err(SkinError::BadWeight {
                vertex,
                slot,
                weight,
            });
        }
    }
    for (slot, &index) in indices.iter().enumerate() {
        if index as usize >= bones {
            return Err(SkinError::BoneIndex {
                vertex,
                slot,
                index,
                bones,
            });
        }
    }
    let sum: f32 = weights.iter().sum();
    if (sum - 1.0).abs() > WEIGHT_SUM_TOLERANCE {
        return Err(SkinError::WeightSum { vertex, sum });
    }
    Ok(())
}
