//! The GPU tracers: the displaced box drawn with front faces culled, each fragment tracing its
//! pixel's ray, by the pyramid traversal or by relief mapping's search, into three targets:
//! the hit (grid position and ray parameter), statistics (iterations, surface or wall), a
//! shaded colour and the normal shaded with, plus the hit's depth. [`supersampled`] averages
//! a frame with many rays per pixel: the reference the prefilter's quality is measured
//! against ([`super::prefilter::image_error`]).

use super::bounds::BoundPyramidBuilder;
use super::camera::Camera;
use super::prefilter::{box_filter, shown_of_rgba8, Shown};
use super::surface::Surface;
use super::visible_shading::VisibleShadingPyramid;
use crate::gl::{
    Compare, Context, DepthTest, DrawState, Face, Framebuffer, GlError, Pass, Primitive, Program,
    Rect, Texture, TextureFormat,
};
use crate::lecture3::error::Error;
use crate::lecture3::pyramid::{Extreme, Pyramid};
use crate::lecture3::pyramid_atlas::{AtlasBuilder, PyramidAtlas};
use crate::shader;
use glam::{DVec3, IVec2};
use serde::Serialize;

/// How the fragment shader finds the hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Top-down traversal of the max pyramid, exact bilinear intersection at the finest level.
    Pyramid,
    /// The same traversal with the minification prefilter: it stops at the nodes the pixel's
    /// footprint covers and meets the prefiltered surface there ([`super::prefilter`]).
    Prefiltered,
    /// Relief mapping: equal linear steps along the ray, then binary search.
    Relief {
        linear_steps: u32,
        binary_steps: u32,
    },
}

impl Method {
    /// Relief mapping with a generous budget: 32 linear steps, then 8 binary steps.
    pub const RELIEF: Method = Method::Relief {
        linear_steps: 32,
        binary_steps: 8,
    };

    pub fn name(&self) -> String {
        match self {
            Method::Pyramid => "pyramid".into(),
            Method::Prefiltered => "pyramid, prefiltered".into(),
            Method::Relief {
                linear_steps,
                binary_steps,
            } => format!("relief {linear_steps}+{binary_steps}"),
        }
    }
}

/// A surface ready to be traced on the GPU: its height texture and bound pyramid.
pub struct DisplacementRenderer {
    ctx: Context,
    surface: Surface,
    heights: Texture,
    bounds: Pyramid,
    bounds_atlas: PyramidAtlas,
    /// The mean pyramid of the height samples (the prefilter's surfaces).
    means_atlas: PyramidAtlas,
    /// The min pyramid of the patch bounds (each node's lowest point), laid out as the bound
    /// atlas: with it, each node's height range (the prefilter's test of what a footprint
    /// covers).
    lows_atlas: PyramidAtlas,
    /// The shading pyramid toward the eye (the prefilter's shading), drawn for each
    /// prefiltered frame.
    shading: VisibleShadingPyramid,
    pyramid_program: Program,
    relief_program: Program,
}

/// Where frames are drawn: hit, statistics and colour targets and a depth buffer.
pub struct FrameTarget {
    framebuffer: Framebuffer,
}

/// What the fragment of one pixel found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pixel {
    /// No fragment, or the ray left the box without a hit.
    Miss,
    Hit {
        /// Grid position (x, y in patches, z the height).
        grid: DVec3,
        /// Distance from the eye.
        tau: f64,
        wall: bool,
        /// The normal the pixel is shaded with (world; a wall's is horizontal; a prefiltered
        /// hit's is the effective one of [`super::visible_shading`], shorter than 1).
        normal: DVec3,
        iterations: u32,
    },
    /// The traversal ran out of iterations (a bug if it ever happens).
    Unfinished,
}

/// A frame read back.
pub struct Frame {
    pub width: u32,
    pub height: u32,
    hit: Vec<f32>,
    stats: Vec<f32>,
    normal: Vec<f32>,
    /// RGBA8, row by row from the bottom.
    pub colour: Vec<u8>,
    /// Window depth, 1 where nothing was hit.
    pub depth: Vec<f32>,
}

impl Frame {
    pub fn pixel(&self, px: u32, py: u32) -> Pixel {
        let i = (py * self.width + px) as usize;
        let (hit, stats) = (&self.hit[4 * i..4 * i + 4], &self.stats[4 * i..4 * i + 4]);
        if stats[1] < 0.0 {
            return Pixel::Unfinished;
        }
        if stats[1] == 0.0 {
            return Pixel::Miss;
        }
        let n = &self.normal[4 * i..4 * i + 3];
        Pixel::Hit {
            grid: DVec3::new(hit[0] as f64, hit[1] as f64, hit[2] as f64),
            tau: hit[3] as f64,
            wall: stats[1] == 2.0,
            normal: DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64),
            iterations: stats[0] as u32,
        }
    }

    /// The hit target as read back: per pixel grid x, y, z and the ray parameter (0, 0, 0, -1
    /// for an unfinished traversal, zeros where nothing was hit), rows from the bottom.
    pub fn hits(&self) -> &[f32] {
        &self.hit
    }

    /// What each pixel shows, as the shader wrote it: 0 nothing, 1 the surface, 2 the box's
    /// wall, -1 an unfinished traversal; rows from the bottom.
    pub fn kinds(&self) -> Vec<f32> {
        self.stats.chunks_exact(4).map(|s| s[1]).collect()
    }

    /// The shown colour of pixel (px, py), RGB in [0, 1].
    pub fn rgb(&self, px: u32, py: u32) -> [f64; 3] {
        let i = 4 * (py * self.width + px) as usize;
        [0, 1, 2].map(|k| self.colour[i + k] as f64 / 255.0)
    }

    /// Every pixel, row by row from the bottom.
    pub fn pixels(&self) -> Vec<Pixel> {
        (0..self.height)
            .flat_map(|py| (0..self.width).map(move |px| (px, py)))
            .map(|(px, py)| self.pixel(px, py))
            .collect()
    }

    /// Pixels whose traversal did not end; an error if there is any.
    pub fn check_finished(&self) -> Result<(), Error> {
        let unfinished = self
            .pixels()
            .iter()
            .filter(|p| **p == Pixel::Unfinished)
            .count();
        if unfinished > 0 {
            return Err(Error::Result(format!(
                "{unfinished} pixels' traversals did not end within their iteration bound"
            )));
        }
        Ok(())
    }
}

impl DisplacementRenderer {
    /// Uploads the height map and draws its bound pyramid.
    pub fn new(ctx: &Context, surface: Surface) -> Result<DisplacementRenderer, Error> {
        let map = &surface.map;
        let heights = Texture::from_f32(
            ctx,
            map.width(),
            map.height(),
            TextureFormat::R32F,
            map.heights(),
        )?;
        let bounds =
            BoundPyramidBuilder::new(ctx)?.build(&heights, surface.patches(), Extreme::Max)?;
        let bounds_atlas = AtlasBuilder::new(ctx)?.atlas(&bounds.texture)?;
        // The lowest point of each node, for the prefilter's test of what a footprint covers.
        let lows =
            BoundPyramidBuilder::new(ctx)?.build(&heights, surface.patches(), Extreme::Min)?;
        let lows_atlas = AtlasBuilder::new(ctx)?.atlas(&lows.texture)?;
        let means_atlas = super::prefilter::mean_atlas(ctx, map)?;
        let shading = VisibleShadingPyramid::new(ctx, &surface)?;
        // The traversal reads both with the bound pyramid's offsets (both span the patches).
        if shading.atlas.offsets != bounds_atlas.offsets
            || lows_atlas.offsets != bounds_atlas.offsets
        {
            return Err(
                GlError::Invalid("the shading and bound atlases differ in layout".into()).into(),
            );
        }
        let vertex = [shader!("glsl/lecture3/displace_box.vert")];
        let ray = shader!("glsl/lecture3/pixel_ray.glsl");
        let normal = shader!("glsl/lecture3/displace_normal.glsl");
        let common = shader!("glsl/lecture3/displace_common.glsl");
        Ok(DisplacementRenderer {
            ctx: ctx.clone(),
            pyramid_program: Program::new(
                ctx,
                &vertex,
                &[
                    ray,
                    normal,
                    common,
                    shader!("glsl/lecture3/displace_prefilter.glsl"),
                    shader!("glsl/lecture3/displace_pyramid.frag"),
                ],
            )?,
            relief_program: Program::new(
                ctx,
                &vertex,
                &[
                    ray,
                    normal,
                    common,
                    shader!("glsl/lecture3/displace_relief.frag"),
                ],
            )?,
            surface,
            heights,
            bounds,
            bounds_atlas,
            means_atlas,
            lows_atlas,
            shading,
        })
    }

    pub fn surface(&self) -> &Surface {
        &self.surface
    }

    /// The bound pyramid (max of each patch's corners, then max per node).
    pub fn bounds(&self) -> &Pyramid {
        &self.bounds
    }

    /// The bound pyramid as the traversal reads it, in one image.
    pub fn bounds_atlas(&self) -> &PyramidAtlas {
        &self.bounds_atlas
    }

    /// Targets for `width x height` frames.
    pub fn target(&self, width: u32, height: u32) -> Result<FrameTarget, GlError> {
        let hit = Texture::new_2d(&self.ctx, width, height, TextureFormat::Rgba32F)?;
        let stats = Texture::new_2d(&self.ctx, width, height, TextureFormat::Rgba32F)?;
        let colour = Texture::new_2d(&self.ctx, width, height, TextureFormat::Rgba8)?;
        let normal = Texture::new_2d(&self.ctx, width, height, TextureFormat::Rgba32F)?;
        let depth = Texture::new_2d(&self.ctx, width, height, TextureFormat::Depth32F)?;
        Ok(FrameTarget {
            framebuffer: Framebuffer::new(
                &self.ctx,
                "displacement frame",
                &[&hit, &stats, &colour, &normal],
                Some(&depth),
            )?,
        })
    }

    /// The largest number of loop iterations a traversal may take: far more than a ray that
    /// crosses every patch once needs (each patch visited once, each level entered and left).
    pub fn max_iterations(&self) -> i32 {
        let (wp, hp) = self.surface.patches();
        4 * (wp + hp + 2) as i32 * (self.bounds.levels() as i32 + 1)
    }

    /// Draws the prefilter's shading pyramid toward `camera` (what a prefiltered frame does
    /// first, where some pixel may stop above level 0).
    pub fn draw_shading(&self, camera: &Camera) -> Result<(), GlError> {
        let top = self.bounds.levels() - 1;
        self.shading.draw(
            &self.surface,
            &self.heights,
            camera.eye,
            super::prefilter::deepest_stop_level(camera, &self.surface, top),
        )
    }

    /// Draws one frame into `target` (its size must be the camera's). A prefiltered frame
    /// first draws the shading pyramid toward the camera, where some pixel may stop above
    /// level 0.
    pub fn render(
        &self,
        target: &FrameTarget,
        camera: &Camera,
        method: Method,
    ) -> Result<(), GlError> {
        if method == Method::Prefiltered && super::prefilter::may_act(camera, &self.surface) {
            self.draw_shading(camera)?;
        }
        let fb = &target.framebuffer;
        fb.clear_colors([0.0; 4])?;
        fb.clear_depth_stencil(1.0, 0)?;
        let program = match method {
            Method::Pyramid | Method::Prefiltered => &self.pyramid_program,
            Method::Relief { .. } => &self.relief_program,
        };
        let mut pass = fb.pass(program, "displacement mapping")?;
        camera.set_ray_uniforms(&mut pass, fb)?;
        self.set_frame_uniforms(&mut pass, camera);
        match method {
            Method::Pyramid | Method::Prefiltered => pass
                .texture("u_bounds", &self.bounds_atlas.texture)
                .texture("u_means", &self.means_atlas.texture)
                .texture("u_lows", &self.lows_atlas.texture)
                .texture("u_shading", &self.shading.atlas.texture)
                .uniform("u_mean_x", &self.means_atlas.offsets_x()[..])
                .uniform("u_mean_y", &self.means_atlas.offsets_y()[..])
                .uniform("u_prefilter", (method == Method::Prefiltered) as i32)
                .uniform(
                    "u_footprint",
                    super::prefilter::footprint_per_unit(camera, &self.surface),
                )
                .uniform("u_level_x", &self.bounds_atlas.offsets_x()[..])
                .uniform("u_level_y", &self.bounds_atlas.offsets_y()[..])
                .uniform("u_top", self.bounds.levels() as i32 - 1)
                .uniform("u_max_iterations", self.max_iterations()),
            Method::Relief {
                linear_steps,
                binary_steps,
            } => pass
                .uniform("u_linear_steps", linear_steps.max(1) as i32)
                .uniform("u_binary_steps", binary_steps as i32),
        };
        pass.state(DrawState {
            depth: Some(DepthTest {
                func: Compare::Less,
                write: true,
            }),
            // The far faces: a camera close to the box has its near faces clipped by the near
            // plane (at --distance 0.5, four pixels in ten), the far ones never; each fragment
            // traces its pixel's ray from the eye anyway, and writes the hit's depth.
            cull: Some(Face::Front),
            ..DrawState::default()
        })
        .draw_attributeless(Primitive::Triangles, 36, 1)
    }

    fn set_frame_uniforms(&self, pass: &mut Pass, camera: &Camera) {
        let (wp, hp) = self.surface.patches();
        pass.texture("u_heights", &self.heights)
            .uniform("u_world_to_grid", self.surface.world_to_grid())
            .uniform("u_patches", IVec2::new(wp as i32, hp as i32))
            .uniform("u_view_projection", camera.view_projection())
            .uniform("u_box", self.surface.size);
    }

    /// The frame in `target`, read back.
    pub fn read(&self, target: &FrameTarget) -> Result<Frame, GlError> {
        let fb = &target.framebuffer;
        let rect = Rect::sized(fb.width(), fb.height());
        Ok(Frame {
            width: fb.width(),
            height: fb.height(),
            hit: fb.read_f32(0, rect)?,
            stats: fb.read_f32(1, rect)?,
            colour: fb.read_u8(2, rect)?,
            normal: fb.read_f32(3, rect)?,
            depth: fb.read_depth(rect)?,
        })
    }

    /// The colour target, for PNG dumps.
    pub fn colour_texture<'a>(&self, target: &'a FrameTarget) -> &'a Texture {
        target.framebuffer.color(2)
    }
}

/// The image of `camera` with `samples x samples` unfiltered rays per pixel, averaged: the
/// quality reference. The rays are the pixels of one frame `samples` times larger, whose pixel
/// centres divide each pixel evenly.
pub fn supersampled(
    renderer: &DisplacementRenderer,
    camera: &Camera,
    samples: u32,
) -> Result<Shown, Error> {
    let big = camera.enlarged(samples);
    let target = renderer.target(big.width, big.height)?;
    renderer.render(&target, &big, Method::Pyramid)?;
    let frame = renderer.read(&target)?;
    frame.check_finished()?;
    Ok(box_filter(
        &shown_of_rgba8(&frame.colour),
        camera.width,
        camera.height,
        samples,
    ))
}
