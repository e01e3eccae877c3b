//! Texture creation (section 3, Table 1's first column): "the two matrices are converted into
//! textures, denoted by texture W and texture X", plus the one-dimensional bias texture.
//!
//! Layouts (texel (x, y), one R32F value each):
//! - W, N wide and M high: texel (k, i) = w_ik, row i of the texture is W_i;
//! - X, L wide and N high: texel (j, k) = x_kj, column j of the texture is input vector X_j;
//! - b, a 1D texture of M texels: texel i = b_i.
//!
//! The output of a layer, R, is laid out like X (L wide, M high), so it is the next layer's X.

use super::network::{Activation, Layer};
use crate::gl::{Context, GlError, Texture, TextureFormat};
use ndarray::ArrayView2;

/// One layer on the GPU in the paper's layout.
pub struct LayerTextures {
    /// Texture W, N x M.
    pub w: Texture,
    /// The bias texture, 1D, M texels.
    pub bias: Texture,
    pub activation: Activation,
    /// N, inputs.
    pub n: u32,
    /// M, outputs.
    pub m: u32,
}

/// Texture W and the bias texture of a layer.
pub fn layer_textures(ctx: &Context, layer: &Layer) -> Result<LayerTextures, GlError> {
    // region: weight-textures
    let (m, n) = (layer.outputs() as u32, layer.inputs() as u32);
    let weights: Vec<f32> = layer.weights.iter().copied().collect(); // row-major: texel (k, i)
    let w = Texture::from_f32(ctx, n, m, TextureFormat::R32F, &weights)?;
    let bias = Texture::new_1d(ctx, m, TextureFormat::R32F)?;
    bias.upload_f32(layer.bias.as_slice().expect("contiguous bias"))?;
    // endregion
    Ok(LayerTextures {
        w,
        bias,
        activation: layer.activation,
        n,
        m,
    })
}

/// Texture X of a batch (L x N, row j = input vector j): the input vectors become the
/// texture's columns, the paper's "accumulating a lot of input feature vectors".
pub fn input_texture(ctx: &Context, batch: ArrayView2<f32>) -> Result<Texture, GlError> {
    // region: input-texture
    let (l, n) = batch.dim();
    let transposed: Vec<f32> = batch.t().iter().copied().collect(); // texel (j, k) = x_kj
    Texture::from_f32(ctx, l as u32, n as u32, TextureFormat::R32F, &transposed)
    // endregion
}
