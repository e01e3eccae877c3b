//! The receivers: the scene from the camera into a G-buffer (position, normal, albedo per
//! pixel), which the gathers light.

use super::light::Receiver;
use super::scene::Scene;
use crate::gl::{
    Compare, Context, DepthTest, DrawState, Framebuffer, GlError, Primitive, Program, Rect,
    Texture, TextureFormat, VertexArray,
};
use crate::shader;
use glam::DVec3;

/// A G-buffer and the pass that fills it.
pub struct GBuffer {
    pub framebuffer: Framebuffer,
    program: Program,
}

impl GBuffer {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<GBuffer, GlError> {
        let target = || Texture::new_2d(ctx, width, height, TextureFormat::Rgba32F);
        let (p, n, a) = (target()?, target()?, target()?);
        let depth = Texture::new_2d(ctx, width, height, TextureFormat::Depth32F)?;
        Ok(GBuffer {
            framebuffer: Framebuffer::new(ctx, "G-buffer", &[&p, &n, &a], Some(&depth))?,
            program: Program::new(
                ctx,
                &[shader!("glsl/lecture3/scene.vert")],
                &[shader!("glsl/lecture3/gbuffer.frag")],
            )?,
        })
    }

    pub fn position(&self) -> &Texture {
        self.framebuffer.color(0)
    }
    pub fn normal(&self) -> &Texture {
        self.framebuffer.color(1)
    }
    pub fn albedo(&self) -> &Texture {
        self.framebuffer.color(2)
    }

    /// Draws the scene from its camera.
    pub fn draw(&self, scene: &Scene, vertices: &VertexArray, count: usize) -> Result<(), GlError> {
        let fb = &self.framebuffer;
        fb.clear_colors([0.0; 4])?;
        fb.clear_depth_stencil(1.0, 0)?;
        let aspect = fb.width() as f32 / fb.height() as f32;
        fb.pass(&self.program, "G-buffer")?
            .uniform("u_view_projection", scene.camera.view_projection(aspect))
            .state(DrawState {
                depth: Some(DepthTest {
                    func: Compare::Less,
                    write: true,
                }),
                ..DrawState::default()
            })
            .draw_arrays(vertices, Primitive::Triangles, 0, count)
    }

    /// The receivers read back, `None` where the camera sees nothing.
    pub fn receivers(&self) -> Result<Vec<Option<Receiver>>, GlError> {
        let rect = Rect::sized(self.framebuffer.width(), self.framebuffer.height());
        let p = self.framebuffer.read_f32(0, rect)?;
        let n = self.framebuffer.read_f32(1, rect)?;
        Ok(p.chunks_exact(4)
            .zip(n.chunks_exact(4))
            .map(|(p, n)| {
                (p[3] != 0.0).then(|| Receiver {
                    position: DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64),
                    normal: DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64),
                })
            })
            .collect())
    }
}
