//! Stream update as a compute pass (OpenGL 4.3; the "then and now" of Sec. 6): one
//! invocation per real leaf gathers the leaf's vertices through its vertex list and writes
//! the min/max box [Eq. 1] into a storage buffer. The vertex texture's `2^d_max x n_max`
//! packing, the virtual slots and the MRT line draw are not needed: positions go up as they
//! are, one `vec4` per mesh vertex.

use super::aabb::Aabb;
use super::stream_setup::AabbStream;
use crate::gl::{Buffer, BufferUsage, ComputeProgram, Context, GlError};
use crate::shader;
use glam::{Vec3, Vec4};

/// One model's leaves on the GPU: vertex positions, the leaves' vertex lists, and the boxes.
pub struct LeafBoxes {
    pub leaves: u32,
    positions: Buffer,
    leaf_start: Buffer,
    vertex_index: Buffer,
    /// Two `vec4` per leaf: minimum, maximum.
    pub boxes: Buffer,
    staging: Vec<Vec4>,
}

impl LeafBoxes {
    /// The vertex lists of `stream`'s real leaves, for a mesh of `vertices` vertices.
    pub fn new(ctx: &Context, stream: &AabbStream, vertices: usize) -> Result<LeafBoxes, GlError> {
        let mut leaf_start = vec![0u32];
        let mut vertex_index = Vec::new();
        for leaf in &stream.leaves {
            vertex_index.extend_from_slice(&leaf.vertices);
            leaf_start.push(vertex_index.len() as u32);
        }
        let leaves = stream.leaves.len() as u32;
        Ok(LeafBoxes {
            leaves,
            positions: Buffer::new(ctx, vertices.max(1) * 16, BufferUsage::Dynamic)?,
            leaf_start: Buffer::from_slice(ctx, &leaf_start, BufferUsage::Static)?,
            vertex_index: Buffer::from_slice(ctx, &vertex_index, BufferUsage::Static)?,
            boxes: Buffer::new(ctx, leaves as usize * 32, BufferUsage::GpuCopy)?,
            staging: Vec::new(),
        })
    }

    /// Download (CPU to GPU): the deformed positions, one `vec4` each.
    pub fn upload(&mut self, positions: &[Vec3]) -> Result<(), GlError> {
        self.staging.clear();
        self.staging.extend(positions.iter().map(|p| p.extend(1.0)));
        self.positions.write(0, &self.staging)
    }

    /// Bytes sent per frame.
    pub fn bytes(&self) -> usize {
        self.positions.len_bytes()
    }

    /// The leaf boxes as the GPU holds them (tests).
    pub fn download(&self) -> Result<Vec<Aabb>, GlError> {
        let v: Vec<Vec4> = self.boxes.read()?;
        Ok(v.chunks_exact(2)
            .map(|c| Aabb {
                min: c[0].truncate(),
                max: c[1].truncate(),
            })
            .collect())
    }
}

/// The compute program of the update.
pub struct ComputeUpdate {
    program: ComputeProgram,
}

impl ComputeUpdate {
    pub fn new(ctx: &Context) -> Result<ComputeUpdate, GlError> {
        let program = ComputeProgram::new(ctx, &[shader!("glsl/collide/compute/leaf_boxes.comp")])?;
        Ok(ComputeUpdate { program })
    }

    /// Refit every leaf box of one model to its (already uploaded) positions.
    pub fn run(&self, leaves: &LeafBoxes) -> Result<(), GlError> {
        self.program
            .dispatch("leaf boxes (compute stream update)")
            .storage(0, &leaves.positions)
            .storage(1, &leaves.leaf_start)
            .storage(2, &leaves.vertex_index)
            .storage(3, &leaves.boxes)
            .uniform("u_leaves", leaves.leaves)
            .run_over(leaves.leaves)
    }
}
