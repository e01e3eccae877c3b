//! Render-to-VBO [section 2]: the render target is copied into a vertex buffer object
//! through a pixel buffer object, RGBA32F (xyzw) as the paper chose for accuracy. The GL
//! buffer is bound as the pixel pack buffer for the copy and as the vertex buffer for
//! pass 2, so the vertices never leave the GPU.
//!
//! Layout: the positions of the whole target, row by row (vertex v of character c at
//! texel `v * W + c`), then the normals in the same order.

use crate::gl::{Buffer, BufferUsage, Context, GlError, Rect};

use super::pass1_skinning::SkinningTarget;

const TEXEL_BYTES: usize = 16;

/// One character's skinned vertices read back: positions and normals, xyzw each.
pub type SkinnedColumn = (Vec<[f32; 4]>, Vec<[f32; 4]>);

/// The vertex buffer pass 2 draws from.
pub struct SkinnedVbo {
    pub buffer: Buffer,
    /// W: characters per row of the render target.
    pub characters: u32,
    /// m: rows.
    pub vertices: u32,
}

impl SkinnedVbo {
    pub fn new(ctx: &Context, characters: u32, vertices: u32) -> Result<Self, GlError> {
        let bytes = 2 * characters as usize * vertices as usize * TEXEL_BYTES;
        Ok(Self {
            buffer: Buffer::new(ctx, bytes, BufferUsage::GpuCopy)?,
            characters,
            vertices,
        })
    }

    fn positions_bytes(&self) -> usize {
        self.characters as usize * self.vertices as usize * TEXEL_BYTES
    }

    /// Copies the whole render target (positions, then normals) into the buffer.
    pub fn copy_from(&self, target: &SkinningTarget) -> Result<(), GlError> {
        if (target.characters, target.vertices) != (self.characters, self.vertices) {
            return Err(GlError::Invalid(format!(
                "render target {}x{} copied into a VBO laid out for {}x{}",
                target.characters, target.vertices, self.characters, self.vertices
            )));
        }
        let all = Rect::sized(self.characters, self.vertices);
        target
            .framebuffer
            .read_into_buffer(0, all, &self.buffer, 0)?;
        target
            .framebuffer
            .read_into_buffer(1, all, &self.buffer, self.positions_bytes())
    }

    /// Bytes between consecutive vertices of one character (a row of the target).
    pub fn stride(&self) -> usize {
        self.characters as usize * TEXEL_BYTES
    }

    /// Byte offset of character `c`'s vertex 0 position.
    pub fn position_offset(&self, c: u32) -> usize {
        c as usize * TEXEL_BYTES
    }

    /// Byte offset of character `c`'s vertex 0 normal.
    pub fn normal_offset(&self, c: u32) -> usize {
        self.positions_bytes() + c as usize * TEXEL_BYTES
    }

    /// Reads back character `c`'s skinned positions and normals (xyzw each), for tests.
    pub fn read_character(&self, c: u32) -> Result<SkinnedColumn, GlError> {
        let all: Vec<[f32; 4]> = self.buffer.read()?;
        let (w, m) = (self.characters as usize, self.vertices as usize);
        let at = |base: usize, v: usize| all[base + v * w + c as usize];
        Ok((
            (0..m).map(|v| at(0, v)).collect(),
            (0..m).map(|v| at(w * m, v)).collect(),
        ))
    }
}
