//! A triangle mesh on the GPU: positions at attribute location 0 and a `u32` index buffer.

use super::{Buffer, BufferUsage, Context, GlError, VertexArray};

/// Vertex positions (`layout(location = 0) in vec3`) and triangle indices, ready to draw.
pub struct MeshBuffers {
    vertex_array: VertexArray,
    positions: Buffer,
    vertex_count: usize,
    index_count: usize,
}

impl MeshBuffers {
    pub fn new(
        ctx: &Context,
        positions: &[[f32; 3]],
        triangles: &[[u32; 3]],
    ) -> Result<MeshBuffers, GlError> {
        if let Some(bad) = triangles
            .iter()
            .flatten()
            .find(|&&i| i as usize >= positions.len())
        {
            return Err(GlError::Invalid(format!(
                "triangle index {bad} is out of range for {} vertices",
                positions.len()
            )));
        }
        let position_buffer = Buffer::from_slice(ctx, positions, BufferUsage::Dynamic)?;
        let index_buffer = Buffer::from_slice(ctx, triangles, BufferUsage::Static)?;
        let mut vertex_array = VertexArray::new(ctx)?;
        vertex_array.float_attribute(0, &position_buffer, 3, 12, 0, 0)?;
        vertex_array.set_index_buffer(&index_buffer)?;
        Ok(MeshBuffers {
            vertex_array,
            positions: position_buffer,
            vertex_count: positions.len(),
            index_count: triangles.len() * 3,
        })
    }

    /// Replace the positions (a deforming mesh); the vertex count must not change.
    pub fn update_positions(&self, positions: &[[f32; 3]]) -> Result<(), GlError> {
        if positions.len() != self.vertex_count {
            return Err(GlError::Invalid(format!(
                "{} positions given for a mesh of {} vertices",
                positions.len(),
                self.vertex_count
            )));
        }
        self.positions.write(0, positions)
    }

    pub fn vertex_array(&self) -> &VertexArray {
        &self.vertex_array
    }
    pub fn index_count(&self) -> usize {
        self.index_count
    }
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }
}
