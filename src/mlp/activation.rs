//! The bias + sigmoid pass (section 3, eq. 3): one rendering pass over texture W x X with the
//! bias texture; the pixel shader adds the two and applies the sigmoid. The result is a
//! render-target texture that is the next layer's texture X.

use super::fp24::Precision;
use super::network::Activation;
use super::textures::LayerTextures;
use crate::gl::{Context, Framebuffer, GlError, Program, Texture};
use crate::shader;

/// The program of the bias + sigmoid pass at `precision`.
pub fn activation_program(ctx: &Context, precision: Precision) -> Result<Program, GlError> {
    Program::new(
        ctx,
        &[shader!("glsl/mlp/bias_sigmoid.vert")],
        &[
            precision.shader_define(),
            shader!("glsl/mlp/fp24.glsl"),
            shader!("glsl/mlp/bias_sigmoid.frag"),
        ],
    )
}

/// The name of the activation pass (the last pass of every layer).
pub const ACTIVATION_PASS: &str = "mlp bias + sigmoid";

/// Draws `R = sigmoid(W x X + B)` (or `W x X + B` for an identity layer) into `target`.
pub fn activation_pass(
    program: &Program,
    layer: &LayerTextures,
    product: &Texture,
    target: &Framebuffer,
) -> Result<(), GlError> {
    // region: activation-pass
    target
        .pass(program, ACTIVATION_PASS)?
        .texture("u_product", product)
        .texture("u_bias", &layer.bias)
        .uniform("u_sigmoid", layer.activation == Activation::Sigmoid)
        .draw_full()
    // endregion
}
