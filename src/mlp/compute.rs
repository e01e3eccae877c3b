//! The compute formulation (OpenGL 4.3), "then and now" for section 3: each layer is one
//! compute pass, a matrix product tiled through work-group shared memory with the bias and
//! the sigmoid fused in (`glsl/mlp/compute/layer.comp`). Layers chain through storage
//! buffers instead of render-target textures; there is no separate activation pass, no
//! texture-size limit on the batch, and no split of the product into passes.

use super::chain::StepTimes;
use super::network::{Activation, Network};
use super::tiling::check_batch;
use crate::gl::{
    ensure_finite, memory_barrier, time_finished, Barrier, Buffer, BufferUsage, ComputeProgram,
    Context, GlError,
};
use crate::shader;
use ndarray::{Array2, ArrayView2};
use std::time::Instant;

/// Side of the square tile a work group computes.
pub const TILE: u32 = 16;

/// The layer program.
pub struct ComputeMlp {
    ctx: Context,
    program: ComputeProgram,
}

struct LayerBuffers {
    n: u32,
    m: u32,
    sigmoid: bool,
    weights: Buffer,
    bias: Buffer,
}

/// A network whose weights and biases are storage buffers.
pub struct ComputeNetwork<'a> {
    mlp: &'a ComputeMlp,
    layers: Vec<LayerBuffers>,
    inputs: usize,
    outputs: usize,
    /// Wall-clock milliseconds spent uploading the weights and biases.
    pub upload_ms: f64,
}

/// The outputs of a batch and the time of each step (`activation` is zero: it is fused).
#[derive(Clone, Debug)]
pub struct ComputeForward {
    /// L x M of the last layer.
    pub outputs: Array2<f32>,
    pub times: StepTimes,
}

impl ComputeMlp {
    /// On a context below OpenGL 4.3, the error naming it.
    pub fn new(ctx: &Context) -> Result<ComputeMlp, GlError> {
        ctx.require_compute("the compute formulation of paper 3")?;
        Ok(ComputeMlp {
            ctx: ctx.clone(),
            program: ComputeProgram::new(ctx, &[shader!("glsl/mlp/compute/layer.comp")])?,
        })
    }

    /// Upload the weights and biases of `net`.
    pub fn load(&self, net: &Network) -> Result<ComputeNetwork<'_>, GlError> {
        let start = Instant::now();
        let layers = net
            .layers()
            .iter()
            .map(|layer| {
                let weights = layer.weights.as_standard_layout();
                Ok(LayerBuffers {
                    n: layer.inputs() as u32,
                    m: layer.outputs() as u32,
                    sigmoid: layer.activation == Activation::Sigmoid,
                    weights: Buffer::from_slice(
                        &self.ctx,
                        weights.as_slice().expect("standard layout"),
                        BufferUsage::Static,
                    )?,
                    bias: Buffer::from_slice(&self.ctx, &layer.bias.to_vec(), BufferUsage::Static)?,
                })
            })
            .collect::<Result<Vec<_>, GlError>>()?;
        self.ctx.finish_all();
        Ok(ComputeNetwork {
            mlp: self,
            layers,
            inputs: net.inputs(),
            outputs: net.outputs(),
            upload_ms: start.elapsed().as_secs_f64() * 1e3,
        })
    }
}

impl ComputeNetwork<'_> {
    /// Run a batch (L x N, row j = input vector j) through every layer.
    pub fn forward(&self, batch: ArrayView2<f32>) -> Result<ComputeForward, GlError> {
        check_batch(batch, self.inputs)?;
        let ctx = &self.mlp.ctx;
        let l = batch.nrows() as u32;
        let mut times = StepTimes::default();
        let start = Instant::now();
        let x = batch.as_standard_layout();
        let mut x = Buffer::from_slice(ctx, x.as_slice().expect("standard"), BufferUsage::Static)?;
        ctx.finish_all();
        times.texture_creation = start.elapsed().as_secs_f64() * 1e3;
        let run = || -> Result<Buffer, GlError> {
            for layer in &self.layers {
                let r = Buffer::new(ctx, l as usize * layer.m as usize * 4, BufferUsage::GpuCopy)?;
                self.mlp
                    .program
                    .dispatch("layer product + bias + sigmoid (compute)")
                    .storage(0, &x)
                    .storage(1, &layer.weights)
                    .storage(2, &layer.bias)
                    .storage(3, &r)
                    .uniform("u_l", l)
                    .uniform("u_n", layer.n)
                    .uniform("u_m", layer.m)
                    .uniform("u_sigmoid", layer.sigmoid)
                    .run([layer.m.div_ceil(TILE), l.div_ceil(TILE), 1])?;
                memory_barrier(ctx, &[Barrier::Storage, Barrier::BufferUpdate]);
                x = r;
            }
            Ok(x.clone())
        };
        let (result, matmul_ms) = time_finished(ctx, run)?;
        let start = Instant::now();
        let data: Vec<f32> = result.read()?;
        times.readback = start.elapsed().as_secs_f64() * 1e3;
        times.matmul = matmul_ms;
        ensure_finite(
            data.iter().copied(),
            "mlp: the outputs of the compute network",
            "layer product + bias + sigmoid (compute)",
        )?;
        let outputs =
            Array2::from_shape_vec((l as usize, self.outputs), data).expect("L x M outputs");
        Ok(ComputeForward { outputs, times })
    }
}
