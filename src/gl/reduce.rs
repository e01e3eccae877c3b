//! Ping-pong reduction (the tutorial's "buffer reduction"; paper 4 section 3.3, Fig. 2): a
//! fragment program combines 2x2 texels into one, rendering into the other of two textures,
//! until one texel remains: ceil(log2 max(w, h)) passes, and one texel read back instead of w*h.

use super::{Context, Framebuffer, GlError, Program, Rect, Texture, TextureFormat};
use crate::shader;

/// What the reduction computes, per RGBA component.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReduceOp {
    Sum,
    Min,
    Max,
    /// How many texels have a non-zero component.
    CountNonZero,
    /// 1 if any texel has a non-zero component, else 0.
    Or,
}

impl ReduceOp {
    /// (shader op, map to non-zero on the first pass).
    pub(super) fn shader(self) -> (i32, bool) {
        match self {
            ReduceOp::Sum => (0, false),
            ReduceOp::Min => (1, false),
            ReduceOp::Max => (2, false),
            ReduceOp::CountNonZero => (0, true),
            ReduceOp::Or => (2, true),
        }
    }
}

/// Reduces float textures up to `width x height` (RGBA32F or R32F; components a format lacks
/// read as GL defines them: 0, 0, 0, 1). Keeps its two ping-pong targets between calls.
pub struct Reducer {
    program: Program,
    ping_pong: [Framebuffer; 2],
    width: u32,
    height: u32,
}

/// The number of 2x2 passes that bring `width x height` down to one texel (at least one).
pub fn passes_for(width: u32, height: u32) -> u32 {
    let side = width.max(height).max(2);
    32 - (side - 1).leading_zeros()
}

impl Reducer {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<Reducer, GlError> {
        let program = Program::rect(ctx, &[shader!("glsl/gl/reduce.frag")])?;
        let (w, h) = (width.div_ceil(2).max(1), height.div_ceil(2).max(1));
        let target = |name| -> Result<Framebuffer, GlError> {
            let t = Texture::new_2d(ctx, w, h, TextureFormat::Rgba32F)?;
            Framebuffer::new(ctx, name, &[&t], None)
        };
        Ok(Reducer {
            program,
            ping_pong: [target("reduce ping")?, target("reduce pong")?],
            width,
            height,
        })
    }

    /// Reduce all of `input` to one value.
    pub fn reduce(&self, input: &Texture, op: ReduceOp) -> Result<[f32; 4], GlError> {
        let levels = passes_for(input.width(), input.height());
        let (target, _) = self.run(input, op, levels)?;
        let v = target.read_f32(0, Rect::sized(1, 1))?;
        Ok([v[0], v[1], v[2], v[3]])
    }

    /// Reduce each aligned `block x block` tile of `input` (block a power of two) to one
    /// value: row by row from the bottom, `ceil(w / block) x ceil(h / block)` values. This is
    /// how many small problems packed as tiles of one texture are reduced together.
    pub fn reduce_blocks(
        &self,
        input: &Texture,
        op: ReduceOp,
        block: u32,
    ) -> Result<Vec<[f32; 4]>, GlError> {
        if !block.is_power_of_two() || block < 2 {
            return Err(GlError::Invalid(format!(
                "reduction blocks must be a power of two of at least 2, not {block}"
            )));
        }
        let (target, rect) = self.run(input, op, block.trailing_zeros())?;
        let v = target.read_f32(0, rect)?;
        Ok(v.chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect())
    }

    /// `levels` passes; the framebuffer holding the result and the result's rectangle.
    fn run(
        &self,
        input: &Texture,
        op: ReduceOp,
        levels: u32,
    ) -> Result<(&Framebuffer, Rect), GlError> {
        if input.is_1d() || !input.format().is_float() || input.format().is_depth() {
            return Err(GlError::Invalid(format!(
                "reduction needs a 2D RGBA32F or R32F texture, not a {}{}",
                if input.is_1d() { "1D " } else { "" },
                input.format().name()
            )));
        }
        if input.width() > self.width || input.height() > self.height {
            return Err(GlError::Invalid(format!(
                "a {}x{} texture is larger than this {}x{} reducer",
                input.width(),
                input.height(),
                self.width,
                self.height
            )));
        }
        let (shader_op, nonzero) = op.shader();
        let (mut w, mut h) = (input.width(), input.height());
        let mut source = input;
        let mut index = 0;
        for level in 0..levels.max(1) {
            let (out_w, out_h) = (w.div_ceil(2), h.div_ceil(2));
            let target = &self.ping_pong[index];
            let mut pass = target.pass(&self.program, "reduction")?;
            pass.viewport(Rect::sized(out_w, out_h))
                .texture("u_input", source)
                .uniform("u_input_size", glam::IVec2::new(w as i32, h as i32))
                .uniform("u_op", shader_op)
                .uniform("u_nonzero", nonzero && level == 0);
            pass.draw_full()?;
            source = target.color(0);
            (w, h) = (out_w, out_h);
            index = 1 - index;
        }
        Ok((&self.ping_pong[1 - index], Rect::sized(w, h)))
    }
}

/// Reduce `input` to one value with a reducer made for it.
pub fn reduce(ctx: &Context, input: &Texture, op: ReduceOp) -> Result<[f32; 4], GlError> {
    Reducer::new(ctx, input.width(), input.height())?.reduce(input, op)
}
