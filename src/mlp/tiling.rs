//! Batches larger than a texture: "the GPU's performance is maximized by accumulating a large
//! number of input vectors to create a two-dimensional texture", up to the maximum texture
//! size (footnote 1: 2048 on the paper's ATI RADEON 9700 PRO). Larger batches are split into
//! tiles of input vectors, each run through all layers on the GPU in turn. Only the batch is
//! split: a layer whose W does not fit a texture is refused when the network is loaded
//! ([`super::chain::check_network_fits`]).

use super::chain::{max_side, Formulation, GpuNetwork, StepTimes};
use super::packed::PACK;
use crate::gl::{ensure_finite, Context, GlError};
use ndarray::{s, Array2, ArrayView2};

/// The outputs of a (possibly tiled) batch.
#[derive(Clone, Debug)]
pub struct GpuForward {
    /// L x M of the last layer.
    pub outputs: Array2<f32>,
    /// Summed over tiles.
    pub times: StepTimes,
    pub tiles: usize,
    /// Input vectors per tile.
    pub tile_vectors: usize,
    /// Rendering passes of each layer's matrix product, per tile.
    pub product_passes: Vec<usize>,
}

/// Input vectors that fit one texture in `formulation`: the texture width, four times that
/// when packed.
pub fn max_vectors_per_texture(ctx: &Context, formulation: Formulation) -> usize {
    let side = max_side(ctx) as usize;
    match formulation {
        Formulation::Faithful => side,
        Formulation::Packed => side * PACK,
    }
}

impl GpuNetwork<'_> {
    /// Runs a batch (L x N, row j = input vector j) through the network in tiles of at most
    /// `max_vectors` input vectors (default and upper limit: what one texture holds).
    /// Outputs that overflow fp32 (or are NaN) are an error naming the network, the input
    /// vectors and the pass.
    pub fn forward(
        &self,
        batch: ArrayView2<f32>,
        max_vectors: Option<usize>,
    ) -> Result<GpuForward, GlError> {
        check_batch(batch, self.inputs)?;
        let limit = max_vectors_per_texture(self.gpu.context(), self.formulation());
        let tile = max_vectors.unwrap_or(limit).clamp(1, limit);
        let mut outputs = Array2::zeros((batch.nrows(), self.outputs));
        let mut times = StepTimes::default();
        let mut tiles = 0;
        for start in (0..batch.nrows()).step_by(tile) {
            let end = (start + tile).min(batch.nrows());
            let (out, t) = self.forward_tile(batch.slice(s![start..end, ..]))?;
            let what = format!(
                "mlp: the outputs of the {} network for input vectors {start}..{end}",
                self.shape
            );
            ensure_finite(out.iter().copied(), &what, self.last_pass())?;
            outputs.slice_mut(s![start..end, ..]).assign(&out);
            times.add(&t);
            tiles += 1;
        }
        Ok(GpuForward {
            outputs,
            times,
            tiles,
            tile_vectors: tile,
            product_passes: self.product_passes(),
        })
    }
}

/// A batch the network can take: `inputs` values per input vector, at least one vector.
pub(super) fn check_batch(batch: ArrayView2<f32>, inputs: usize) -> Result<(), GlError> {
    if batch.ncols() != inputs {
        return Err(GlError::Invalid(format!(
            "the batch has {} values per input vector but the network takes {inputs}",
            batch.ncols()
        )));
    }
    if batch.nrows() == 0 {
        return Err(GlError::Invalid("the batch has no input vectors".into()));
    }
    Ok(())
}
