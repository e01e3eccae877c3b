//! The matrix-product passes (section 3, eq. 2, Fig. 1; Moravanszky's method): a rectangle
//! covering the whole L x M output is drawn, and the pixel shader of every pixel (i, j) takes
//! the inner product of row i of texture W with column j of texture X.
//!
//! "The number of rendering passes required for matrix multiplication depends on the
//! capability of the GPU, including the number of pixel shader operations and number of
//! texture load operations": a pass sums at most a given number of the N inputs, and each
//! later pass reads the running sum from the previous pass's render target and adds its own
//! inputs (ping-pong between two targets). A GLSL 330 loop has no such limit, so by default
//! the whole product is one pass.

use super::fp24::Precision;
use super::textures::LayerTextures;
use crate::gl::{Context, Framebuffer, GlError, Program, Texture, TextureFormat};
use crate::shader;
use std::ops::Range;

/// Inputs per pass the paper's ATI RADEON 9700 PRO could sum, by our estimate (the paper gives
/// no number): its pixel shaders (ps_2_0) allow 32 texture loads and 64 arithmetic
/// instructions per pass; one load goes to the running sum, and each input takes two loads
/// (w_ik and x_kj) and about three instructions (two coordinates, one multiply-add), so
/// (32 - 1) / 2 = 15 inputs, within the 64 / 3 = 21 the instructions allow.
pub const RADEON_9700_INPUTS_PER_PASS: usize = 15;

/// The programs of the product: the first (or only) pass, and the passes after it.
pub struct ProductPrograms {
    first: Program,
    accumulate: Program,
}

impl ProductPrograms {
    /// The programs at `precision` (fp32, or each step rounded to the R300's 24-bit floats).
    pub fn new(ctx: &Context, precision: Precision) -> Result<ProductPrograms, GlError> {
        let vertex = [shader!("glsl/mlp/product.vert")];
        let fragment = |main| {
            [
                precision.shader_define(),
                shader!("glsl/mlp/fp24.glsl"),
                shader!("glsl/mlp/inner_product.frag"),
                main,
            ]
        };
        Ok(ProductPrograms {
            first: Program::new(ctx, &vertex, &fragment(shader!("glsl/mlp/product.frag")))?,
            accumulate: Program::new(
                ctx,
                &vertex,
                &fragment(shader!("glsl/mlp/product_accumulate.frag")),
            )?,
        })
    }
}

/// The inputs each pass of an N-input product sums: `0..N` in one pass when there is no
/// limit, else consecutive ranges of at most `inputs_per_pass` inputs.
pub fn pass_ranges(n: usize, inputs_per_pass: Option<usize>) -> Vec<Range<usize>> {
    let step = inputs_per_pass.unwrap_or(n).max(1);
    (0..n).step_by(step).map(|k| k..(k + step).min(n)).collect()
}

/// A render target texture of `width x height` single floats and its framebuffer.
pub fn float_target(
    ctx: &Context,
    name: &str,
    width: u32,
    height: u32,
) -> Result<Framebuffer, GlError> {
    let texture = Texture::new_2d(ctx, width, height, TextureFormat::R32F)?;
    Framebuffer::new(ctx, name, &[&texture], None)
}

/// The render targets of a product of `passes` passes, L wide and M high: one, or the two
/// that the passes ping-pong between.
pub fn product_targets(
    ctx: &Context,
    l: u32,
    m: u32,
    passes: usize,
) -> Result<Vec<Framebuffer>, GlError> {
    let count = if passes > 1 { 2 } else { 1 };
    (0..count)
        .map(|_| float_target(ctx, "mlp W x X", l, m))
        .collect()
}

/// Draws `W x X` (L wide, M high) in one pass per range of inputs, into `targets` (from
/// [`product_targets`]); returns the target that holds the product.
pub fn product_passes<'t>(
    programs: &ProductPrograms,
    layer: &LayerTextures,
    x: &Texture,
    targets: &'t [Framebuffer],
    ranges: &[Range<usize>],
) -> Result<&'t Framebuffer, GlError> {
    debug_assert_eq!(x.height(), layer.n);
    debug_assert!(ranges.len() == 1 || targets.len() == 2);
    // region: product-passes
    for (p, k) in ranges.iter().enumerate() {
        let target = &targets[p % targets.len()];
        debug_assert_eq!(target.height(), layer.m);
        let mut pass = if p == 0 {
            target.pass(&programs.first, "mlp product W x X")?
        } else {
            let previous = &targets[(p - 1) % targets.len()];
            let mut pass = target.pass(&programs.accumulate, "mlp product W x X, next inputs")?;
            pass.texture("u_partial", previous.color(0));
            pass
        };
        pass.texture("u_w", &layer.w)
            .texture("u_x", x)
            .uniform("u_n", layer.n as i32)
            .uniform("u_k_begin", k.start as i32)
            .uniform("u_k_end", k.end as i32)
            .draw_full()?;
    }
    // endregion
    Ok(&targets[(ranges.len() - 1) % targets.len()])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pass_ranges_cover_the_inputs_in_order() {
        assert_eq!(pass_ranges(121, None), vec![0..121]);
        let r = pass_ranges(121, Some(RADEON_9700_INPUTS_PER_PASS));
        assert_eq!(r.len(), 9);
        assert_eq!((r[0].clone(), r[8].clone()), (0..15, 120..121));
        assert!(r.windows(2).all(|w| w[0].end == w[1].start));
        assert_eq!(pass_ranges(30, Some(15)), vec![0..15, 15..30]);
        assert_eq!(pass_ranges(5, Some(100)), vec![0..5]);
        assert_eq!(pass_ranges(3, Some(1)), vec![0..1, 1..2, 2..3]);
    }
}
