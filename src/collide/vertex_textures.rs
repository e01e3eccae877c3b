//! Vertex textures [Sec. 4.2.2]: the unique vertices of each leaf, packed into one 2D
//! texture of `2^d_max x n_max` texels. Texel `(k, i)` holds vertex `i` of the leaf in
//! slot `k` (virtual slots copy their leaf, so their boxes copy their parent's); RGB is
//! the position and alpha is 1, or alpha 0 for an empty texel when the leaf has fewer
//! than `n_max` vertices. (The paper defines `n_max` as the most triangles in a leaf, yet
//! stores a leaf's unique vertices, one per texel; `n_max` here is the most unique vertices
//! in a leaf, the number of texels a column needs.)

use super::stream_setup::AabbStream;
use crate::gl::{Context, GlError, Texture, TextureFormat};
use glam::Vec3;

/// Marks an empty texel in [`VertexLayout::vertex`].
const EMPTY: u32 = u32::MAX;

/// Which vertex goes into which texel, for one segment of a stream; computed once, so the
/// per-frame packing is a gather.
#[derive(Clone, Debug)]
pub struct VertexLayout {
    /// Texture width: slots in the segment.
    pub width: usize,
    /// Texture height: `n_max`.
    pub height: usize,
    /// Row-major `height x width`: the vertex of each texel, or `EMPTY`.
    vertex: Vec<u32>,
}

impl VertexLayout {
    /// The layout for slots `range` of `stream`.
    pub fn new(stream: &AabbStream, range: std::ops::Range<usize>) -> VertexLayout {
        let width = range.len();
        let height = stream.n_max.max(1);
        let mut vertex = vec![EMPTY; width * height];
        for (col, slot) in range.enumerate() {
            let leaf = &stream.leaves[stream.slot_leaf[slot] as usize];
            for (row, &v) in leaf.vertices.iter().enumerate() {
                vertex[row * width + col] = v;
            }
        }
        VertexLayout {
            width,
            height,
            vertex,
        }
    }

    /// The texels (RGBA32F, row-major) for the current `positions`.
    pub fn pack(&self, positions: &[Vec3], texels: &mut Vec<[f32; 4]>) {
        texels.clear();
        texels.extend(self.vertex.iter().map(|&v| {
            if v == EMPTY {
                [0.0; 4]
            } else {
                let p = positions[v as usize];
                [p.x, p.y, p.z, 1.0]
            }
        }));
    }
}

/// The vertex texture of one segment on the GPU, refilled every frame.
pub struct VertexTexture {
    pub layout: VertexLayout,
    /// RGBA32F, `width x n_max`.
    pub texture: Texture,
    texels: Vec<[f32; 4]>,
}

impl VertexTexture {
    pub fn new(
        ctx: &Context,
        stream: &AabbStream,
        range: std::ops::Range<usize>,
    ) -> Result<VertexTexture, GlError> {
        let layout = VertexLayout::new(stream, range);
        let limit = ctx.info().limits.max_texture_size as usize;
        if layout.height > limit {
            return Err(GlError::Limit(format!(
                "a leaf holds {} vertices, more than the {limit} rows a vertex texture can have \
                 on this renderer; use a smaller leaf size",
                layout.height
            )));
        }
        let texture = Texture::new_2d(
            ctx,
            layout.width as u32,
            layout.height as u32,
            TextureFormat::Rgba32F,
        )?;
        Ok(VertexTexture {
            layout,
            texture,
            texels: Vec::new(),
        })
    }

    /// Texture download (CPU to GPU): the deformed vertices of every leaf.
    pub fn upload(&mut self, positions: &[Vec3]) -> Result<(), GlError> {
        self.layout.pack(positions, &mut self.texels);
        self.texture.upload_f32(self.texels.as_flattened())
    }

    /// Bytes sent per frame.
    pub fn bytes(&self) -> usize {
        self.layout.width * self.layout.height * 16
    }
}
