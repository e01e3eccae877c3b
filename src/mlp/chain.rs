//! Layer chaining (section 3): "the result of the previous layer is saved in the form of a
//! render target texture, which is then used as an input for the next layer", so after
//! texture creation every operation of every layer runs on the GPU and only the last layer's
//! output is read back. A layer whose W does not fit a texture (N or M beyond the limit) is
//! refused when the network is loaded, with a message that says so ([`check_network_fits`]).

use super::activation::{activation_pass, activation_program};
use super::fp24::Precision;
use super::matmul::{float_target, pass_ranges, product_passes, product_targets, ProductPrograms};
use super::network::Network;
use super::packed::{
    packed_activation_pass, packed_inputs, packed_layer, packed_product_pass, packed_target,
    read_packed, targets_of, texels, PackedLayer, PackedPrograms, PACK,
};
use super::textures::{input_texture, layer_textures, LayerTextures};
use crate::gl::{Context, GlError, Program, TimerQuery};
use ndarray::{Array2, ArrayView2};
use serde::Serialize;
use std::time::Instant;

/// Which GPU formulation evaluates the network.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Formulation {
    /// The paper's: one float per texel, one inner product per fragment.
    Faithful,
    /// Four floats per texel, a 4 x 4 block of outputs per fragment (MRT).
    Packed,
}

/// Time spent in each elementary operation (Table 1), in milliseconds. Texture creation and
/// readback are wall clock (they involve the CPU); the passes are GL timer queries.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct StepTimes {
    pub texture_creation: f64,
    pub matmul: f64,
    pub activation: f64,
    pub readback: f64,
}

impl StepTimes {
    /// All four steps.
    pub fn total(&self) -> f64 {
        self.texture_creation + self.matmul + self.activation + self.readback
    }

    pub fn add(&mut self, other: &StepTimes) {
        self.texture_creation += other.texture_creation;
        self.matmul += other.matmul;
        self.activation += other.activation;
        self.readback += other.readback;
    }
}

/// The largest side of a texture that is also a render target (under a period GPU's
/// limits, that GPU's: 2048 on the paper's board).
pub(super) fn max_side(ctx: &Context) -> u32 {
    let l = &ctx.info().limits;
    ctx.max_texture_size()
        .min(l.max_viewport_dims[0])
        .min(l.max_viewport_dims[1])
}

/// Why a layer is refused, if it is: its W (N wide, M high) and its output (M high) must fit.
pub fn check_network_fits(
    ctx: &Context,
    net: &Network,
    formulation: Formulation,
) -> Result<(), GlError> {
    let max = max_side(ctx) as usize;
    for (index, layer) in net.layers().iter().enumerate() {
        let (n, m) = (layer.inputs(), layer.outputs());
        let (w_wide, w_high, what) = match formulation {
            Formulation::Faithful => (n, m, "one texel per weight"),
            Formulation::Packed => (texels(n), texels(m) * PACK, "four weights per texel"),
        };
        if w_wide > max || w_high > max {
            let limit = match ctx.period() {
                Some(gpu) => format!("{}'s max_texture_size, assets/period_gpus.toml", gpu.name),
                None => "GL_MAX_TEXTURE_SIZE / viewport".to_string(),
            };
            let renderer = match ctx.period() {
                Some(gpu) => gpu.name.as_str(),
                None => "this renderer",
            };
            return Err(GlError::Limit(format!(
                "layer {index} ({n} inputs, {m} outputs) does not fit {renderer}: its \
                 texture W would be {w_wide} x {w_high} texels ({what}) but textures hold at \
                 most {max} per side ({limit}); only the batch is split into tiles, so a layer \
                 this wide is refused"
            )));
        }
    }
    Ok(())
}

/// The compiled programs of both formulations on one context.
pub struct GpuMlp {
    ctx: Context,
    /// The arithmetic of the faithful passes.
    precision: Precision,
    product: ProductPrograms,
    activation: Program,
    packed: PackedPrograms,
}

enum LayerStack {
    Faithful(Vec<LayerTextures>),
    Packed(Vec<PackedLayer>),
}

/// A network whose weights and biases are textures, ready for batches.
pub struct GpuNetwork<'a> {
    pub(crate) gpu: &'a GpuMlp,
    layers: LayerStack,
    pub(crate) inputs: usize,
    pub(crate) outputs: usize,
    /// Nodes per layer, as errors name the network ("64-32-1").
    pub(crate) shape: String,
    /// At most this many inputs summed per product pass (faithful only; `None`: one pass).
    inputs_per_pass: Option<usize>,
    /// Wall-clock milliseconds spent making the weight and bias textures.
    pub upload_ms: f64,
}

impl GpuMlp {
    /// Compiles the programs of both formulations, in fp32.
    pub fn new(ctx: &Context) -> Result<GpuMlp, GlError> {
        GpuMlp::with_precision(ctx, Precision::Fp32)
    }

    /// Compiles the programs of both formulations; the faithful passes compute at
    /// `precision` (the packed formulation, not the paper's, stays fp32 and is refused by
    /// [`GpuMlp::load`] at any other precision).
    pub fn with_precision(ctx: &Context, precision: Precision) -> Result<GpuMlp, GlError> {
        let mlp = GpuMlp {
            ctx: ctx.clone(),
            precision,
            product: ProductPrograms::new(ctx, precision)?,
            activation: activation_program(ctx, precision)?,
            packed: PackedPrograms::new(ctx)?,
        };
        Ok(mlp)
    }

    pub fn context(&self) -> &Context {
        &self.ctx
    }

    pub fn precision(&self) -> Precision {
        self.precision
    }

    /// Makes the weight and bias textures of `net`, refusing layers wider than the renderer's
    /// textures (see [`check_network_fits`]).
    pub fn load(&self, net: &Network, formulation: Formulation) -> Result<GpuNetwork<'_>, GlError> {
        if formulation == Formulation::Packed && self.precision != Precision::Fp32 {
            return Err(GlError::Invalid(format!(
                "the {} arithmetic is emulated in the paper's faithful passes only; the packed                  formulation (not the paper's) runs in fp32",
                self.precision.name()
            )));
        }
        check_network_fits(&self.ctx, net, formulation)?;
        let start = Instant::now();
        let layers = match formulation {
            Formulation::Faithful => LayerStack::Faithful(
                net.layers()
                    .iter()
                    .map(|l| layer_textures(&self.ctx, l))
                    .collect::<Result<_, _>>()?,
            ),
            Formulation::Packed => LayerStack::Packed(
                net.layers()
                    .iter()
                    .map(|l| packed_layer(&self.ctx, l))
                    .collect::<Result<_, _>>()?,
            ),
        };
        self.ctx.finish_all();
        Ok(GpuNetwork {
            gpu: self,
            layers,
            inputs: net.inputs(),
            outputs: net.outputs(),
            shape: std::iter::once(net.inputs())
                .chain(net.layers().iter().map(|l| l.outputs()))
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join("-"),
            inputs_per_pass: None,
            upload_ms: start.elapsed().as_secs_f64() * 1e3,
        })
    }
}

/// Timer queries around the passes, read once everything has been drawn.
struct PassTimers {
    matmul: Vec<TimerQuery>,
    activation: Vec<TimerQuery>,
}

impl PassTimers {
    fn new() -> PassTimers {
        PassTimers {
            matmul: Vec::new(),
            activation: Vec::new(),
        }
    }

    fn time<T>(
        ctx: &Context,
        into: &mut Vec<TimerQuery>,
        pass: impl FnOnce() -> Result<T, GlError>,
    ) -> Result<T, GlError> {
        let query = TimerQuery::new(ctx)?;
        query.begin();
        let result = pass();
        query.end();
        into.push(query);
        result
    }

    fn read(&self, times: &mut StepTimes) -> Result<(), GlError> {
        for q in &self.matmul {
            times.matmul += q.milliseconds()?;
        }
        for q in &self.activation {
            times.activation += q.milliseconds()?;
        }
        Ok(())
    }
}

impl GpuNetwork<'_> {
    /// The pass whose output is read back (the last layer's activation).
    pub(crate) fn last_pass(&self) -> &'static str {
        match self.layers {
            LayerStack::Faithful(_) => super::activation::ACTIVATION_PASS,
            LayerStack::Packed(_) => super::packed::PACKED_ACTIVATION_PASS,
        }
    }

    pub fn formulation(&self) -> Formulation {
        match self.layers {
            LayerStack::Faithful(_) => Formulation::Faithful,
            LayerStack::Packed(_) => Formulation::Packed,
        }
    }

    /// Splits every matrix product into rendering passes of at most `inputs` of the layer's N
    /// inputs each, as the paper's GPU required (see [`super::matmul`]); `None` keeps one pass
    /// per product. Only the faithful formulation is split: the packed one is not the paper's.
    pub fn split_products(mut self, inputs: Option<usize>) -> Result<Self, GlError> {
        if inputs == Some(0) {
            return Err(GlError::Invalid(
                "a product pass must sum at least one input (inputs per pass is 0)".into(),
            ));
        }
        if inputs.is_some() && self.formulation() == Formulation::Packed {
            return Err(GlError::Invalid(
                "the product is split into passes only in the paper's faithful formulation; the \
                 packed formulation always takes one pass"
                    .into(),
            ));
        }
        self.inputs_per_pass = inputs;
        Ok(self)
    }

    /// The rendering passes of each layer's matrix product, for one tile of input vectors.
    pub fn product_passes(&self) -> Vec<usize> {
        match &self.layers {
            LayerStack::Faithful(layers) => layers
                .iter()
                .map(|l| pass_ranges(l.n as usize, self.inputs_per_pass).len())
                .collect(),
            LayerStack::Packed(layers) => vec![1; layers.len()],
        }
    }

    /// All layers on one batch that fits one texture (L x N in, L x M out).
    pub(crate) fn forward_tile(
        &self,
        batch: ArrayView2<f32>,
    ) -> Result<(Array2<f32>, StepTimes), GlError> {
        match &self.layers {
            LayerStack::Faithful(layers) => self.faithful_tile(layers, batch),
            LayerStack::Packed(layers) => self.packed_tile(layers, batch),
        }
    }

    fn faithful_tile(
        &self,
        layers: &[LayerTextures],
        batch: ArrayView2<f32>,
    ) -> Result<(Array2<f32>, StepTimes), GlError> {
        let (ctx, gpu) = (&self.gpu.ctx, self.gpu);
        let l = batch.nrows() as u32;
        let mut times = StepTimes::default();
        let start = Instant::now();
        let mut x = input_texture(ctx, batch)?;
        ctx.finish_all();
        times.texture_creation = start.elapsed().as_secs_f64() * 1e3;
        let mut timers = PassTimers::new();
        let mut last = None;
        // region: layer-chain
        for layer in layers {
            let ranges = pass_ranges(layer.n as usize, self.inputs_per_pass);
            let targets = product_targets(ctx, l, layer.m, ranges.len())?;
            let product = PassTimers::time(ctx, &mut timers.matmul, || {
                product_passes(&gpu.product, layer, &x, &targets, &ranges)
            })?;
            let result = float_target(ctx, "mlp R", l, layer.m)?;
            PassTimers::time(ctx, &mut timers.activation, || {
                activation_pass(&gpu.activation, layer, product.color(0), &result)
            })?;
            x = result.color(0).clone();
            last = Some(result);
        }
        // endregion
        let result = last.expect("a network has layers");
        let start = Instant::now();
        let data = result.read_f32(0, result.rect())?; // M rows of L
        let outputs = Array2::from_shape_vec((self.outputs, l as usize), data)
            .expect("M x L")
            .reversed_axes()
            .as_standard_layout()
            .into_owned();
        times.readback = start.elapsed().as_secs_f64() * 1e3;
        timers.read(&mut times)?;
        Ok((outputs, times))
    }

    fn packed_tile(
        &self,
        layers: &[PackedLayer],
        batch: ArrayView2<f32>,
    ) -> Result<(Array2<f32>, StepTimes), GlError> {
        let (ctx, programs) = (&self.gpu.ctx, &self.gpu.packed);
        let l = batch.nrows();
        let l4 = texels(l) as u32;
        let mut times = StepTimes::default();
        let start = Instant::now();
        let mut x = packed_inputs(ctx, batch)?;
        ctx.finish_all();
        times.texture_creation = start.elapsed().as_secs_f64() * 1e3;
        let mut timers = PassTimers::new();
        let mut last = None;
        for layer in layers {
            let product = packed_target(ctx, "mlp packed W x X", l4, layer.m4)?;
            PassTimers::time(ctx, &mut timers.matmul, || {
                packed_product_pass(programs, layer, &x, &product)
            })?;
            let result = packed_target(ctx, "mlp packed R", l4, layer.m4)?;
            let product = targets_of(&product);
            PassTimers::time(ctx, &mut timers.activation, || {
                packed_activation_pass(programs, layer, &product, &result)
            })?;
            x = targets_of(&result);
            last = Some(result);
        }
        let result = last.expect("a network has layers");
        let start = Instant::now();
        let outputs = read_packed(&result, l, self.outputs)?;
        times.readback = start.elapsed().as_secs_f64() * 1e3;
        timers.read(&mut times)?;
        Ok((outputs, times))
    }
}
