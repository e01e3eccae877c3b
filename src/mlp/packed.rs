//! The packed formulation, the faster variant kept beside the faithful one: four values per
//! RGBA32F texel and a 4 x 4 block of outputs per fragment through four render targets
//! (layouts in `glsl/mlp/packed_product.frag`). Eight texture lookups feed 64 multiply-adds,
//! where the faithful pass looks up twice per multiply-add. Sizes are padded to multiples of
//! four with zero weights, so padding never reaches a real output.

use super::network::{Activation, Layer};
use crate::gl::{Context, Framebuffer, GlError, Program, Texture, TextureFormat};
use crate::shader;
use glam::Vec2;
use ndarray::{Array2, ArrayView2};

/// Values per texel, and input vectors (columns) per fragment.
pub const PACK: usize = 4;

/// `n` rounded up to whole texels.
pub fn texels(n: usize) -> usize {
    n.div_ceil(PACK)
}

/// One layer in the packed layout.
pub struct PackedLayer {
    /// N/4 wide, M (padded to 4) high, RGBA32F: texel (k', i) = w_i,4k'..4k'+3.
    pub w: Texture,
    /// 1D, M/4 texels, RGBA32F: texel i' = b_4i'..4i'+3.
    pub bias: Texture,
    pub activation: Activation,
    /// N/4 and M/4 (rounded up).
    pub n4: u32,
    pub m4: u32,
}

/// The four textures X_0..X_3 of a batch or of a layer's output: texture c holds input
/// vectors j = 4j' + c, four inputs per texel (L/4 wide, N/4 high).
pub type PackedBatch = [Texture; PACK];

/// The product and activation programs.
pub struct PackedPrograms {
    pub product: Program,
    pub activation: Program,
}

impl PackedPrograms {
    pub fn new(ctx: &Context) -> Result<PackedPrograms, GlError> {
        Ok(PackedPrograms {
            product: Program::new(
                ctx,
                &[shader!("glsl/mlp/packed.vert")],
                &[shader!("glsl/mlp/packed_product.frag")],
            )?,
            activation: Program::new(
                ctx,
                &[shader!("glsl/mlp/packed.vert")],
                &[shader!("glsl/mlp/packed_bias_sigmoid.frag")],
            )?,
        })
    }
}

/// Texture W and the bias texture of a layer, packed and zero-padded.
pub fn packed_layer(ctx: &Context, layer: &Layer) -> Result<PackedLayer, GlError> {
    let (m, n) = (layer.outputs(), layer.inputs());
    let (m4, n4) = (texels(m), texels(n));
    let mut w = vec![0.0f32; n4 * PACK * m4 * PACK];
    for ((i, k), &value) in layer.weights.indexed_iter() {
        w[i * n4 * PACK + k] = value; // row i, texel k / 4, component k % 4
    }
    let mut bias = vec![0.0f32; m4 * PACK];
    bias[..m].copy_from_slice(layer.bias.as_slice().expect("contiguous bias"));
    let w = Texture::from_f32(
        ctx,
        n4 as u32,
        (m4 * PACK) as u32,
        TextureFormat::Rgba32F,
        &w,
    )?;
    let bias_texture = Texture::new_1d(ctx, m4 as u32, TextureFormat::Rgba32F)?;
    bias_texture.upload_f32(&bias)?;
    Ok(PackedLayer {
        w,
        bias: bias_texture,
        activation: layer.activation,
        n4: n4 as u32,
        m4: m4 as u32,
    })
}

/// X_0..X_3 of a batch (L x N).
pub fn packed_inputs(ctx: &Context, batch: ArrayView2<f32>) -> Result<PackedBatch, GlError> {
    let (l, n) = batch.dim();
    let (l4, n4) = (texels(l), texels(n));
    let make = |c: usize| -> Result<Texture, GlError> {
        let mut data = vec![0.0f32; l4 * n4 * PACK];
        for j4 in 0..l4 {
            let j = j4 * PACK + c;
            if j >= l {
                break;
            }
            for (k, &value) in batch.row(j).iter().enumerate() {
                // texel (j', k / 4), component k % 4
                data[((k / PACK) * l4 + j4) * PACK + k % PACK] = value;
            }
        }
        Texture::from_f32(ctx, l4 as u32, n4 as u32, TextureFormat::Rgba32F, &data)
    };
    Ok([make(0)?, make(1)?, make(2)?, make(3)?])
}

/// Four RGBA32F targets of `l4 x m4` texels in one framebuffer (MRT).
pub fn packed_target(ctx: &Context, name: &str, l4: u32, m4: u32) -> Result<Framebuffer, GlError> {
    let t: Vec<Texture> = (0..PACK)
        .map(|_| Texture::new_2d(ctx, l4, m4, TextureFormat::Rgba32F))
        .collect::<Result<_, _>>()?;
    Framebuffer::new(ctx, name, &[&t[0], &t[1], &t[2], &t[3]], None)
}

/// The four colour textures of a packed target, as the next pass's input.
pub fn targets_of(fb: &Framebuffer) -> PackedBatch {
    [0, 1, 2, 3].map(|c| fb.color(c).clone())
}

/// Draws the 4 x 4-block product W x X into `target` (L/4 wide, M/4 high, four targets).
pub fn packed_product_pass(
    programs: &PackedPrograms,
    layer: &PackedLayer,
    x: &PackedBatch,
    target: &Framebuffer,
) -> Result<(), GlError> {
    target
        .pass(&programs.product, "mlp packed product W x X")?
        .texture("u_w", &layer.w)
        .texture("u_x0", &x[0])
        .texture("u_x1", &x[1])
        .texture("u_x2", &x[2])
        .texture("u_x3", &x[3])
        .uniform("u_n4", layer.n4 as i32)
        .uniform("u_w_texel", texel_size(&layer.w))
        .uniform("u_x_texel", texel_size(&x[0]))
        .draw_full()
}

/// The size of one texel in texture coordinates, for nearest lookups at texel centres.
fn texel_size(t: &Texture) -> Vec2 {
    Vec2::new(1.0 / t.width() as f32, 1.0 / t.height() as f32)
}

/// The name of the packed activation pass (the last pass of every layer).
pub const PACKED_ACTIVATION_PASS: &str = "mlp packed bias + sigmoid";

/// Draws `sigmoid(W x X + B)` on the packed layout into `target`.
pub fn packed_activation_pass(
    programs: &PackedPrograms,
    layer: &PackedLayer,
    product: &PackedBatch,
    target: &Framebuffer,
) -> Result<(), GlError> {
    target
        .pass(&programs.activation, PACKED_ACTIVATION_PASS)?
        .texture("u_product0", &product[0])
        .texture("u_product1", &product[1])
        .texture("u_product2", &product[2])
        .texture("u_product3", &product[3])
        .texture("u_bias", &layer.bias)
        .uniform("u_sigmoid", layer.activation == Activation::Sigmoid)
        .draw_full()
}

/// Reads the L x M outputs back from a packed result.
pub fn read_packed(fb: &Framebuffer, l: usize, m: usize) -> Result<Array2<f32>, GlError> {
    let (l4, m4) = (fb.width() as usize, fb.height() as usize);
    let mut out = Array2::zeros((l, m));
    for c in 0..PACK {
        let data = fb.read_f32(c, fb.rect())?;
        for i4 in 0..m4 {
            for j4 in 0..l4 {
                let j = j4 * PACK + c;
                for q in 0..PACK {
                    let i = i4 * PACK + q;
                    if j < l && i < m {
                        out[[j, i]] = data[(i4 * l4 + j4) * PACK + q];
                    }
                }
            }
        }
    }
    Ok(out)
}
