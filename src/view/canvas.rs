//! The canvas a demo draws a frame into: an RGBA8 colour target of the window's size with a
//! depth buffer. The window copies it to the screen; the headless path reads it back.

use crate::gl::{Context, Framebuffer, GlError, Program, Rect, Texture, TextureFormat};
use crate::shader;

pub struct Canvas {
    target: Framebuffer,
    /// Draws text and insets over the frame (`glsl/view/overlay.frag`), compiled once.
    overlay: Program,
}

impl Canvas {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<Canvas, GlError> {
        let colour = Texture::new_2d(ctx, width.max(1), height.max(1), TextureFormat::Rgba8)?;
        let depth = Texture::new_2d(ctx, width.max(1), height.max(1), TextureFormat::Depth32F)?;
        Ok(Canvas {
            target: Framebuffer::new(ctx, "viewer canvas", &[&colour], Some(&depth))?,
            overlay: Program::rect(ctx, &[shader!("glsl/view/overlay.frag")])?,
        })
    }

    /// The program that blends an RGBA image over the canvas.
    pub fn overlay_program(&self) -> &Program {
        &self.overlay
    }

    /// The framebuffer to draw into.
    pub fn target(&self) -> &Framebuffer {
        &self.target
    }

    pub fn width(&self) -> u32 {
        self.target.width()
    }

    pub fn height(&self) -> u32 {
        self.target.height()
    }

    pub fn context(&self) -> &Context {
        self.target.context()
    }

    /// Clear colour and depth.
    pub fn clear(&self, colour: [f32; 4]) -> Result<(), GlError> {
        self.target.clear_colors(colour)?;
        self.target.clear_depth_stencil(1.0, 0)
    }

    /// The pixels, RGBA, rows from the bottom.
    pub fn pixels(&self) -> Result<Vec<u8>, GlError> {
        let mut out = self
            .target
            .read_u8(0, Rect::sized(self.width(), self.height()))?;
        for px in out.chunks_exact_mut(4) {
            px[3] = 255;
        }
        Ok(out)
    }

    /// Width over height.
    pub fn aspect(&self) -> f32 {
        self.width() as f32 / self.height() as f32
    }
}
