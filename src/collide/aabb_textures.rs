//! AABB textures [Sec. 4.2.1]: the stream `S^X` (one segment of it when tiled) as two 1D
//! RGBA32F textures `T_min`, `T_max`, one texel per slot, and the 1D stencil array marking
//! which slots take part in the overlap test. `T_min`/`T_max` are also the two render
//! targets of the stream update (MRT), so they live in one framebuffer.

use super::aabb::Aabb;
use super::stream_setup::AabbStream;
use crate::gl::{Context, Framebuffer, GlError, Texture, TextureFormat, Wrap};
use glam::Vec3;

/// `T_min`, `T_max` and the stencil array of slots `range` of a stream.
pub struct AabbTextures {
    pub t_min: Texture,
    pub t_max: Texture,
    /// R8: 255 (1) for slots that are tested, 0 for the other virtual copies.
    pub stencil: Texture,
    /// `[T_min, T_max]` as COLOR0 / COLOR1, the stream update's render targets.
    pub targets: Framebuffer,
}

impl AabbTextures {
    pub fn new(
        ctx: &Context,
        stream: &AabbStream,
        range: std::ops::Range<usize>,
    ) -> Result<AabbTextures, GlError> {
        let width = range.len() as u32;
        let t_min = Texture::new_1d(ctx, width, TextureFormat::Rgba32F)?;
        let t_max = Texture::new_1d(ctx, width, TextureFormat::Rgba32F)?;
        // The rectangle is textured periodically: one period of T^X per column.
        t_min.set_wrap(Wrap::Repeat);
        t_max.set_wrap(Wrap::Repeat);
        let stencil = Texture::new_1d(ctx, width, TextureFormat::R8)?;
        let marks: Vec<u8> = stream.stencil[range].iter().map(|&s| s * 255).collect();
        stencil.upload_u8(&marks)?;
        let targets = Framebuffer::new(ctx, "T_min/T_max", &[&t_min, &t_max], None)?;
        Ok(AabbTextures {
            t_min,
            t_max,
            stencil,
            targets,
        })
    }

    /// Read both textures back as boxes (for tests and dumps).
    pub fn download(&self) -> Result<Vec<Aabb>, GlError> {
        let lo = self.t_min.download_f32()?;
        let hi = self.t_max.download_f32()?;
        Ok(lo
            .chunks_exact(4)
            .zip(hi.chunks_exact(4))
            .map(|(a, b)| Aabb {
                min: Vec3::new(a[0], a[1], a[2]),
                max: Vec3::new(b[0], b[1], b[2]),
            })
            .collect())
    }
}
