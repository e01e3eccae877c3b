//! Render-to-VBO [section 2]: the render target is copied into a vertex buffer object
//! through a pixel buffer object, RGBA32F (xyzw) as the paper chose for accuracy. The GL
//! buffer is bound as the pixel pack buffer for the copy and as the vertex buffer for
//! pass 2, so the vertices never leave the GPU.
//!
//! Layout: the positions of the whole target, row by row (vertex v of character c at
//! texel `(b * m + v) * W + x` for block `b = c / W`, column `x = c % W`, W characters per
//! row), then the normals in the same order.

use crate::gl::{Buffer, BufferUsage, Context, GlError, Rect};

use super::pass1_skinning::SkinningTarget;

const TEXEL_BYTES: usize = 16;

/// One character's skinned vertices read back: positions and normals, xyzw each.
pub type SkinnedColumn = (Vec<[f32; 4]>, Vec<[f32; 4]>);

/// The vertex buffer pass 2 draws from.
pub struct SkinnedVbo {
    pub buffer: Buffer,
    /// Characters the buffer holds.
    pub characters: u32,
    /// m: vertices per character.
    pub vertices: u32,
    /// W: characters per row of the render target.
    pub row_characters: u32,
    pub blocks: u32,
}

impl SkinnedVbo {
    /// A buffer laid out like `target`.
    pub fn new(ctx: &Context, target: &SkinningTarget) -> Result<Self, GlError> {
        let texels = target.row_characters as usize * (target.blocks * target.vertices) as usize;
        Ok(Self {
            buffer: Buffer::new(ctx, 2 * texels * TEXEL_BYTES, BufferUsage::GpuCopy)?,
            characters: target.characters,
            vertices: target.vertices,
            row_characters: target.row_characters,
            blocks: target.blocks,
        })
    }

    fn positions_texels(&self) -> usize {
        self.row_characters as usize * (self.blocks * self.vertices) as usize
    }

    /// Copies the rows of the first `n` characters (positions, then normals) into the
    /// buffer.
    pub fn copy_from(&self, target: &SkinningTarget, n: u32) -> Result<(), GlError> {
        let same = (target.row_characters, target.blocks, target.vertices)
            == (self.row_characters, self.blocks, self.vertices);
        if !same || n > self.characters {
            return Err(GlError::Invalid(format!(
                "copying {n} characters of a {}x{} render target into a VBO laid out for {} \
                 characters of {} vertices",
                target.row_characters,
                target.blocks * target.vertices,
                self.characters,
                self.vertices
            )));
        }
        // region: copy-to-vbo
        let rows = Rect::sized(self.row_characters, target.rows_for(n));
        target
            .framebuffer
            .read_into_buffer(0, rows, &self.buffer, 0)?;
        let normals = self.positions_texels() * TEXEL_BYTES;
        target
            .framebuffer
            .read_into_buffer(1, rows, &self.buffer, normals)
        // endregion
    }

    /// Bytes between consecutive vertices of one character (a row of the target).
    pub fn stride(&self) -> usize {
        self.row_characters as usize * TEXEL_BYTES
    }

    /// Texel index of character `c`'s vertex 0.
    fn first_texel(&self, c: u32) -> usize {
        let (w, m) = (self.row_characters as usize, self.vertices as usize);
        let c = c as usize;
        (c / w) * m * w + c % w
    }

    /// Byte offset of character `c`'s vertex 0 position.
    pub fn position_offset(&self, c: u32) -> usize {
        self.first_texel(c) * TEXEL_BYTES
    }

    /// Byte offset of character `c`'s vertex 0 normal.
    pub fn normal_offset(&self, c: u32) -> usize {
        (self.positions_texels() + self.first_texel(c)) * TEXEL_BYTES
    }

    /// The texels (positions, then normals) that hold characters `0..n`.
    pub fn used_texels(&self, n: u32) -> impl Iterator<Item = usize> + '_ {
        let (w, m) = (self.row_characters as usize, self.vertices as usize);
        let normals = self.positions_texels();
        (0..n).flat_map(move |c| {
            let first = self.first_texel(c);
            (0..m).flat_map(move |v| [first + v * w, normals + first + v * w])
        })
    }

    /// Reads back character `c`'s skinned positions and normals (xyzw each), for tests.
    pub fn read_character(&self, c: u32) -> Result<SkinnedColumn, GlError> {
        let all: Vec<[f32; 4]> = self.buffer.read()?;
        Ok(self.column_of(&all, c))
    }

    /// Character `c`'s vertices out of the whole buffer's contents.
    pub fn column_of(&self, all: &[[f32; 4]], c: u32) -> SkinnedColumn {
        let w = self.row_characters as usize;
        let first = self.first_texel(c);
        let normals = self.positions_texels();
        let m = self.vertices as usize;
        (
            (0..m).map(|v| all[first + v * w]).collect(),
            (0..m).map(|v| all[normals + first + v * w]).collect(),
        )
    }
}
