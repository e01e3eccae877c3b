//! Step 3c, "a min-reduction read back": the smallest T over all pixels and the pixel that
//! holds it. The ping-pong reduction ([`crate::gl::reduce`]) takes the T target down to one
//! minimum per 16 x 16 block; those few values come back, and then only the texels of the
//! block with the smallest minimum, to find its pixel (so the ray's direction comes with the
//! bound).

use crate::gl::reduce::{ReduceOp, Reducer};
use crate::gl::{Context, Framebuffer, GlError, Rect};

/// Side of the blocks reduced before the read back.
pub const BLOCK: u32 = 16;

/// The smallest T and its pixel index in the `6N x N` layout (row-major from the bottom).
#[derive(Clone, Copy, Debug)]
pub struct Nearest {
    pub t: f32,
    pub pixel: usize,
    /// Floats read back (block minima and one block).
    pub floats_read: usize,
}

/// Min-reduce `target` (colour 0, R32F) and find its smallest texel.
pub fn nearest_exit(ctx: &Context, target: &Framebuffer) -> Result<Nearest, GlError> {
    let (w, h) = (target.width(), target.height());
    let reducer = Reducer::new(ctx, w, h)?;
    let block = BLOCK.min(w.max(h).next_power_of_two()).max(2);
    let minima = reducer.reduce_blocks(target.color(0), ReduceOp::Min, block)?;
    let per_row = w.div_ceil(block) as usize;
    let (best, _) = minima
        .iter()
        .enumerate()
        .min_by(|a, b| a.1[0].total_cmp(&b.1[0]))
        .ok_or_else(|| GlError::Invalid("an empty T target".into()))?;
    let (bx, by) = (
        (best % per_row) as u32 * block,
        (best / per_row) as u32 * block,
    );
    let rect = Rect::new(bx, by, block.min(w - bx), block.min(h - by));
    let texels = target.read_f32(0, rect)?;
    let (k, &t) = texels
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .ok_or_else(|| GlError::Invalid("an empty block".into()))?;
    let (x, y) = (
        bx as usize + k % rect.w as usize,
        by as usize + k / rect.w as usize,
    );
    Ok(Nearest {
        t,
        pixel: y * w as usize + x,
        floats_read: minima.len() + texels.len(),
    })
}
