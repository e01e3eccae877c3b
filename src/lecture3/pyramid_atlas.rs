//! The pyramid laid out in one image, for traversals that read a different level in each
//! pixel: level 0 at the origin, the levels above stacked in a column to its right (the way
//! mipmaps are drawn in textbooks). A traversal then reads any node of any level with one
//! `texelFetch` of level 0 at `node + offset[level]`.
//!
//! Why not read the mipmap levels directly: Mesa's softpipe (the OpenGL 3.3 floor this
//! project checks every path on) takes `texelFetch`'s level of detail from the first pixel
//! of each 2x2 quad, so a per-pixel level reads the wrong level in the other three (seen on
//! Mesa 22.3: a shader fetching level `x % 3` got levels 0, 0, 2, 2, 1, 1, ...); llvmpipe and
//! GPUs honour it per pixel. The atlas costs one small
//! copy pass per level (each with one level for the whole pass) and gives the same answer
//! everywhere.

use crate::gl::{Context, Framebuffer, GlError, Program, Rect, Texture};
use crate::shader;
use glam::IVec2;

/// The size of an atlas holding levels of the given sizes, and each level's offset in it.
pub fn atlas_layout(sizes: &[(u32, u32)]) -> ((u32, u32), Vec<(u32, u32)>) {
    let (w0, h0) = sizes[0];
    let mut offsets = vec![(0, 0)];
    let mut y = 0;
    for &(_, h) in &sizes[1..] {
        offsets.push((w0, y));
        y += h;
    }
    let width = w0 + sizes.get(1).map_or(0, |s| s.0);
    (((width), h0.max(y)), offsets)
}

/// A pyramid in one texture.
pub struct PyramidAtlas {
    pub texture: Texture,
    /// Where each level starts.
    pub offsets: Vec<(u32, u32)>,
    /// Each level's size.
    pub sizes: Vec<(u32, u32)>,
}

impl PyramidAtlas {
    pub fn levels(&self) -> u32 {
        self.sizes.len() as u32
    }

    /// The x offsets of the levels, as the shaders' `int u_level_x[16]` get them.
    pub fn offsets_x(&self) -> Vec<i32> {
        self.offsets.iter().map(|o| o.0 as i32).collect()
    }

    /// The y offsets of the levels (`int u_level_y[16]`).
    pub fn offsets_y(&self) -> Vec<i32> {
        self.offsets.iter().map(|o| o.1 as i32).collect()
    }

    /// Level `level` read back from the atlas (float formats).
    pub fn read_level(&self, level: u32) -> Result<Vec<f32>, GlError> {
        let all = self.texture.download_f32()?;
        let c = self.texture.format().components();
        let (ox, oy) = self.offsets[level as usize];
        let (w, h) = self.sizes[level as usize];
        let stride = self.texture.width() as usize;
        Ok((oy..oy + h)
            .flat_map(|y| {
                let start = (y as usize * stride + ox as usize) * c;
                all[start..start + w as usize * c].iter().copied()
            })
            .collect())
    }
}

/// The most levels the shaders' offset arrays hold (a 16384-texel side has 15).
pub const MAX_LEVELS: u32 = 16;

/// Copies mipmapped pyramids into atlases.
pub struct AtlasBuilder {
    ctx: Context,
    program: Program,
}

impl AtlasBuilder {
    pub fn new(ctx: &Context) -> Result<AtlasBuilder, GlError> {
        Ok(AtlasBuilder {
            ctx: ctx.clone(),
            program: Program::rect(ctx, &[shader!("glsl/lecture3/atlas_copy.frag")])?,
        })
    }

    /// An atlas for `pyramid` (a mipmapped texture), allocated and filled.
    pub fn atlas(&self, pyramid: &Texture) -> Result<PyramidAtlas, GlError> {
        let sizes: Vec<_> = (0..pyramid.levels())
            .map(|l| pyramid.level_size(l))
            .collect();
        if sizes.len() as u32 > MAX_LEVELS {
            return Err(GlError::Limit(format!(
                "a pyramid of {} levels; the atlas holds at most {MAX_LEVELS}",
                sizes.len()
            )));
        }
        let ((w, h), offsets) = atlas_layout(&sizes);
        let atlas = PyramidAtlas {
            texture: Texture::new_2d(&self.ctx, w, h, pyramid.format())?,
            offsets,
            sizes,
        };
        self.fill(pyramid, &atlas)?;
        Ok(atlas)
    }

    /// Copies every level of `pyramid` into its place in `atlas`: one pass per level.
    pub fn fill(&self, pyramid: &Texture, atlas: &PyramidAtlas) -> Result<(), GlError> {
        let target = Framebuffer::new(&self.ctx, "pyramid atlas", &[&atlas.texture], None)?;
        for level in 0..atlas.levels() {
            let (ox, oy) = atlas.offsets[level as usize];
            let (w, h) = atlas.sizes[level as usize];
            target
                .pass(&self.program, "pyramid level into the atlas")?
                .viewport(Rect::new(ox, oy, w, h))
                .texture("u_pyramid", pyramid)
                .uniform("u_level", level as i32)
                .uniform("u_offset", IVec2::new(ox as i32, oy as i32))
                .draw_full()?;
        }
        Ok(())
    }
}
