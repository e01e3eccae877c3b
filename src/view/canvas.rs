//! The canvas a demo draws a frame into: an RGBA8 colour target of the window's size with a
//! depth buffer. The window copies it to the screen; the headless path reads it back.

use super::inset::Probed;
use crate::gl::{Context, Framebuffer, GlError, Program, Rect, Texture, TextureFormat};
use crate::shader;
use std::cell::RefCell;

pub struct Canvas {
    target: Framebuffer,
    /// Draws text and insets over the frame (`glsl/view/overlay.frag`), compiled once.
    overlay: Program,
    /// The buffers drawn into this frame and where, for the texel probe (cleared each frame).
    probed: RefCell<Vec<Probed>>,
    /// The height of the overlay text at the top of this frame (pixels).
    text_height: std::cell::Cell<u32>,
}

impl Canvas {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<Canvas, GlError> {
        let colour = Texture::new_2d(ctx, width.max(1), height.max(1), TextureFormat::Rgba8)?;
        let depth = Texture::new_2d(ctx, width.max(1), height.max(1), TextureFormat::Depth32F)?;
        Ok(Canvas {
            target: Framebuffer::new(ctx, "viewer canvas", &[&colour], Some(&depth))?,
            overlay: Program::rect(ctx, &[shader!("glsl/view/overlay.frag")])?,
            probed: RefCell::new(Vec::new()),
            text_height: std::cell::Cell::new(0),
        })
    }

    /// Set the height of the overlay text of this frame.
    pub fn set_text_height(&self, height: u32) {
        self.text_height.set(height);
    }

    /// The canvas below the overlay text: where a demo draws a buffer filling the frame.
    pub fn below_text(&self) -> Rect {
        let top = (self.text_height.get() + 4).min(self.height());
        Rect::sized(self.width(), self.height() - top)
    }

    /// Forget the buffers of the last frame (a new frame starts).
    pub fn clear_probed(&self) {
        self.probed.borrow_mut().clear();
    }

    /// A buffer drawn into this frame, for the probe.
    pub fn add_probed(&self, probed: Probed) {
        self.probed.borrow_mut().push(probed);
    }

    /// The probe's lines for canvas pixel (`x`, `y`) (top-left origin, as the mouse gives it):
    /// the topmost buffer drawn there, its texel, its value and its reference's.
    pub fn probe(&self, (x, y): (u32, u32)) -> Vec<String> {
        self.probe_buffer((x, y))
            .unwrap_or_else(|| vec![format!("({x}, {y}): no buffer here")])
    }

    /// [`Canvas::probe`]'s lines where a buffer is under the pixel, `None` elsewhere.
    pub fn probe_buffer(&self, (x, y): (u32, u32)) -> Option<Vec<String>> {
        let probed = self.probed.borrow();
        probed.iter().rev().find_map(|p| p.readout(x, y))
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
