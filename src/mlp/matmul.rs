//! The matrix-product pass (section 3, eq. 2, Fig. 1; Moravanszky's method): a rectangle
//! covering the whole L x M output is drawn, and the pixel shader of every pixel (i, j) takes
//! the inner product of row i of texture W with column j of texture X.

use super::textures::LayerTextures;
use crate::gl::{Context, Framebuffer, GlError, Program, Texture, TextureFormat};
use crate::shader;

/// The program of the product pass.
pub fn product_program(ctx: &Context) -> Result<Program, GlError> {
    Program::new(
        ctx,
        &[shader!("glsl/mlp/product.vert")],
        &[shader!("glsl/mlp/product.frag")],
    )
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

/// Draws `W x X` into `target` (L wide, M high): one rendering pass.
pub fn product_pass(
    program: &Program,
    layer: &LayerTextures,
    x: &Texture,
    target: &Framebuffer,
) -> Result<(), GlError> {
    debug_assert_eq!((x.height(), target.height()), (layer.n, layer.m));
    target
        .pass(program, "mlp product W x X")?
        .texture("u_w", &layer.w)
        .texture("u_x", x)
        .uniform("u_n", layer.n as i32)
        .draw_full()
}
