//! Technique 1, the image pyramid: a quadtree of an image in which each node keeps the
//! maximum (or minimum) of the four nodes below it, built on the GPU by render passes, each
//! level drawn from the one below (the ping-pong shape of [`crate::gl::reduce`], but keeping
//! every level, as the mipmap levels of one texture).
//!
//! Layout, stated once: level 0 is the image padded to a power of two on each side with the
//! operation's identity (`-f32::MAX` for a max pyramid, `f32::MAX` for a min pyramid), so the
//! quadtree is complete; level k is `max(1, W >> k) x max(1, H >> k)` and node (i, j) of level
//! k + 1 combines nodes (2i..2i+1, 2j..2j+1) of level k (a side already 1 repeats its one
//! node). Max and min are exact in floating point, so the GPU pyramid equals the CPU pyramid
//! bit for bit.
//!
//! The mean (averaging) pyramid, as image processing uses it, sits beside them: each node is
//! the mean of the image pixels it covers. Padding covers none, so for sizes that are not
//! powers of two each node weights its children by how many image pixels they cover (a node
//! on the image's right edge of an odd-sized level averages fewer pixels); its level 0 is
//! padded with 0, and a node that covers nothing is 0. Its GPU levels are the CPU's (f64, from
//! the image) within fp32 rounding, not bit for bit.
//!
//! The lecture names the image pyramid and its use for displacement mapping (technique 2)
//! without giving a construction; this is the standard mipmap-style construction, a
//! reconstruction.

use crate::gl::{Context, Framebuffer, GlError, Program, Texture, TextureFormat};
use crate::shader;
use serde::Serialize;

/// Which extreme the pyramid keeps (or, for `Mean`, the average instead).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Extreme {
    Max,
    Min,
    /// The mean of the image pixels each node covers: an averaging pyramid, not an extreme.
    Mean,
}

impl Extreme {
    /// The value padding contributes nothing with.
    pub fn identity(self) -> f32 {
        match self {
            Extreme::Max => -f32::MAX,
            Extreme::Min => f32::MAX,
            Extreme::Mean => 0.0,
        }
    }

    /// Two values combined (for `Mean`, two values of equal weight).
    pub fn combine(self, a: f32, b: f32) -> f32 {
        match self {
            Extreme::Max => a.max(b),
            Extreme::Min => a.min(b),
            Extreme::Mean => 0.5 * (a + b),
        }
    }

    /// The shader's `u_op`.
    fn shader_op(self) -> i32 {
        match self {
            Extreme::Max => 0,
            Extreme::Min => 1,
            Extreme::Mean => 2,
        }
    }
}

/// One level of a pyramid, row by row from the bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    pub width: u32,
    pub height: u32,
    pub values: Vec<f32>,
}

impl Level {
    pub fn at(&self, x: u32, y: u32) -> f32 {
        self.values[(y * self.width + x) as usize]
    }
}

/// The size of level 0: each side rounded up to a power of two.
pub fn padded_size(width: u32, height: u32) -> (u32, u32) {
    (width.next_power_of_two(), height.next_power_of_two())
}

/// Levels of the pyramid of a `width x height` image, down to one node.
pub fn level_count(width: u32, height: u32) -> u32 {
    let (w, h) = padded_size(width, height);
    w.max(h).trailing_zeros() + 1
}

/// The CPU pyramid: level 0 (the padded image) up to the 1 x 1 root. A mean pyramid is
/// computed from the image itself at every level (f64 means of the pixels each node covers,
/// rounded to f32), not level from level.
pub fn cpu_pyramid(width: u32, height: u32, values: &[f32], extreme: Extreme) -> Vec<Level> {
    assert_eq!(values.len(), (width * height) as usize, "image size");
    if extreme == Extreme::Mean {
        return cpu_mean_pyramid(width, height, values);
    }
    let mut levels = vec![padded(width, height, values, extreme)];
    for _ in 1..level_count(width, height) {
        let next = next_level(levels.last().expect("level 0"), extreme);
        levels.push(next);
    }
    levels
}

/// The image pixels along one axis (of `pixels`) that node `node` covers when each node of its
/// level spans `span` pixels.
fn covered(node: u32, span: u32, pixels: u32) -> u32 {
    pixels.saturating_sub(node * span).min(span)
}

/// Every level of the mean pyramid, each node the f64 mean of the image pixels it covers (0
/// where it covers none).
fn cpu_mean_pyramid(width: u32, height: u32, values: &[f32]) -> Vec<Level> {
    let (pw, ph) = padded_size(width, height);
    (0..level_count(width, height))
        .map(|k| {
            let (w, h) = ((pw >> k).max(1), (ph >> k).max(1));
            let (sx, sy) = (pw / w, ph / h);
            let mut out = Vec::with_capacity((w * h) as usize);
            for y in 0..h {
                for x in 0..w {
                    let (nx, ny) = (covered(x, sx, width), covered(y, sy, height));
                    let sum: f64 = (y * sy..y * sy + ny)
                        .flat_map(|py| (x * sx..x * sx + nx).map(move |px| (px, py)))
                        .map(|(px, py)| values[(py * width + px) as usize] as f64)
                        .sum();
                    let count = (nx * ny) as f64;
                    out.push(if count > 0.0 {
                        (sum / count) as f32
                    } else {
                        0.0
                    });
                }
            }
            Level {
                width: w,
                height: h,
                values: out,
            }
        })
        .collect()
}

fn padded(width: u32, height: u32, values: &[f32], extreme: Extreme) -> Level {
    let (w, h) = padded_size(width, height);
    let mut out = vec![extreme.identity(); (w * h) as usize];
    for y in 0..height {
        let row = &values[(y * width) as usize..((y + 1) * width) as usize];
        out[(y * w) as usize..(y * w + width) as usize].copy_from_slice(row);
    }
    Level {
        width: w,
        height: h,
        values: out,
    }
}

/// One level from the one below: each node the extreme of its (up to) four children. (For a
/// mean pyramid this is the plain mean of the children, right only where every child covers
/// as many image pixels: [`cpu_pyramid`] weights them.)
pub fn next_level(below: &Level, extreme: Extreme) -> Level {
    let (w, h) = ((below.width / 2).max(1), (below.height / 2).max(1));
    let mut values = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let (x0, y0) = (2 * x, 2 * y);
            let (x1, y1) = (
                (x0 + 1).min(below.width - 1),
                (y0 + 1).min(below.height - 1),
            );
            let a = extreme.combine(below.at(x0, y0), below.at(x1, y0));
            let b = extreme.combine(below.at(x0, y1), below.at(x1, y1));
            values.push(extreme.combine(a, b));
        }
    }
    Level {
        width: w,
        height: h,
        values,
    }
}

/// A pyramid on the GPU: one R32F texture whose mipmap levels are the pyramid's levels,
/// and a framebuffer on each level.
pub struct Pyramid {
    pub texture: Texture,
    pub extreme: Extreme,
    targets: Vec<Framebuffer>,
    /// The image's size before padding (a mean pyramid weights nodes by it).
    image: (u32, u32),
}

impl Pyramid {
    /// The image's size before padding.
    pub fn image_size(&self) -> (u32, u32) {
        self.image
    }

    pub fn levels(&self) -> u32 {
        self.texture.levels()
    }

    /// The framebuffer drawing into level `level`.
    pub fn target(&self, level: u32) -> &Framebuffer {
        &self.targets[level as usize]
    }

    /// Every level read back.
    pub fn read_levels(&self) -> Result<Vec<Level>, GlError> {
        (0..self.levels())
            .map(|level| {
                let (width, height) = self.texture.level_size(level);
                Ok(Level {
                    width,
                    height,
                    values: self.texture.download_level_f32(level)?,
                })
            })
            .collect()
    }
}

/// Builds pyramids by render passes; compile once, build many.
pub struct PyramidBuilder {
    ctx: Context,
    level_program: Program,
}

impl PyramidBuilder {
    pub fn new(ctx: &Context) -> Result<PyramidBuilder, GlError> {
        Ok(PyramidBuilder {
            ctx: ctx.clone(),
            level_program: Program::rect(ctx, &[shader!("glsl/lecture3/pyramid_level.frag")])?,
        })
    }

    /// An empty pyramid texture for a `width x height` image (level 0 padded).
    pub fn allocate(&self, width: u32, height: u32, extreme: Extreme) -> Result<Pyramid, GlError> {
        self.allocate_as(width, height, extreme, TextureFormat::R32F)
    }

    /// An empty pyramid of `format` (`Rgba32F`: four values per node, each channel combined
    /// alike).
    pub fn allocate_as(
        &self,
        width: u32,
        height: u32,
        extreme: Extreme,
        format: TextureFormat,
    ) -> Result<Pyramid, GlError> {
        let (w, h) = padded_size(width, height);
        let texture =
            Texture::new_2d_mipmapped(&self.ctx, w, h, format, level_count(width, height))?;
        let targets = (0..texture.levels())
            .map(|level| {
                Framebuffer::new_at_level(&self.ctx, "pyramid level", &[&texture], None, level)
            })
            .collect::<Result<_, _>>()?;
        Ok(Pyramid {
            texture,
            extreme,
            targets,
            image: (width, height),
        })
    }

    /// The pyramid of an image given on the CPU: level 0 uploaded (padded), the rest drawn.
    pub fn from_image(
        &self,
        width: u32,
        height: u32,
        values: &[f32],
        extreme: Extreme,
    ) -> Result<Pyramid, GlError> {
        if values.len() != (width * height) as usize {
            return Err(GlError::Invalid(format!(
                "{} values given for a {width}x{height} image",
                values.len()
            )));
        }
        // region: pyramid-upload
        let pyramid = self.allocate(width, height, extreme)?;
        pyramid
            .texture
            .upload_f32(&padded(width, height, values, extreme).values)?;
        self.build_levels(&pyramid)?;
        // endregion
        Ok(pyramid)
    }

    /// Draws levels 1.. of `pyramid` from its level 0: one pass per level, each reading only
    /// the level below (the texture's readable range is narrowed to it while the next level is
    /// its render target).
    pub fn build_levels(&self, pyramid: &Pyramid) -> Result<(), GlError> {
        let texture = &pyramid.texture;
        // region: pyramid-levels
        let result = (1..texture.levels()).try_for_each(|level| {
            texture.set_level_range(level - 1, level - 1)?;
            let (below_w, below_h) = texture.level_size(level - 1);
            let (pw, ph) = texture.level_size(0);
            let (iw, ih) = pyramid.image;
            pyramid
                .target(level)
                .pass(&self.level_program, "pyramid level from the one below")?
                .texture("u_below", texture)
                .uniform(
                    "u_below_size",
                    glam::IVec2::new(below_w as i32, below_h as i32),
                )
                .uniform("u_op", pyramid.extreme.shader_op())
                .uniform("u_image", glam::IVec2::new(iw as i32, ih as i32))
                .uniform(
                    "u_below_span",
                    glam::IVec2::new((pw / below_w) as i32, (ph / below_h) as i32),
                )
                .draw_full()
        });
        // endregion
        texture.set_level_range(0, texture.levels() - 1)?;
        result
    }
}
