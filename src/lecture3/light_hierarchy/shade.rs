//! The picture: direct light from the spot (shadowed by its depth image) plus the gathered
//! indirect light, tone mapped into an RGBA8 target.

use super::clusters::GpuClusters;
use super::gbuffer::GBuffer;
use super::scene::Scene;
use crate::gl::{Context, Framebuffer, GlError, Program, Texture, TextureFormat};
use crate::shader;

/// Which light terms the picture shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Terms {
    Direct,
    Indirect,
    Both,
}

/// The shading pass and its RGBA8 target.
pub struct ShadePass {
    program: Program,
    pub target: Framebuffer,
}

impl ShadePass {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<ShadePass, GlError> {
        let colour = Texture::new_2d(ctx, width, height, TextureFormat::Rgba8)?;
        Ok(ShadePass {
            program: Program::rect(ctx, &[shader!("glsl/lecture3/vpl_shade.frag")])?,
            target: Framebuffer::new(ctx, "indirect lighting picture", &[&colour], None)?,
        })
    }

    /// Shades the G-buffer with `gathered` (irradiance per pixel) and the spot light.
    pub fn shade(
        &self,
        scene: &Scene,
        gbuffer: &GBuffer,
        clusters: &GpuClusters,
        gathered: &Texture,
        terms: Terms,
        exposure: f32,
    ) -> Result<(), GlError> {
        let light_depth = clusters.level0.depth().ok_or_else(|| {
            GlError::Invalid("the VPL image has no depth buffer to shadow with".into())
        })?;
        let (direct, indirect) = match terms {
            Terms::Direct => (1.0f32, 0.0f32),
            Terms::Indirect => (0.0, 1.0),
            Terms::Both => (1.0, 1.0),
        };
        self.target
            .pass(&self.program, "shade")?
            .texture("u_receiver_position", gbuffer.position())
            .texture("u_receiver_normal", gbuffer.normal())
            .texture("u_receiver_albedo", gbuffer.albedo())
            .texture("u_gathered", gathered)
            .texture("u_light_depth", light_depth)
            .uniform("u_light_view_projection", scene.light.view_projection(1.0))
            .uniform("u_light_position", scene.light.eye)
            .uniform("u_intensity", scene.intensity)
            .uniform("u_direct", direct)
            .uniform("u_indirect", indirect)
            .uniform("u_exposure", exposure)
            .draw_full()
    }
}
