//! Paper 3 walked (Oh & Jung 2004): a two-layer perceptron on a batch of 48 input vectors,
//! each pass's texture shown and checked against the CPU's forward pass.

use super::{buffer_png, Check, Shot, Step, Walk};
use crate::gl::{Context, Texture};
use crate::mlp::activation::{activation_pass, activation_program};
use crate::mlp::cpu::{self, CpuProduct};
use crate::mlp::fp24::Precision;
use crate::mlp::matmul::{
    float_target, pass_ranges, product_passes, product_targets, ProductPrograms,
};
use crate::mlp::network::{Activation, Layer, Network};
use crate::mlp::textures::{input_texture, layer_textures};
use ndarray::{Array1, Array2};
use std::path::Path;

pub const WALK: Walk = Walk {
    id: "paper3",
    title: "Paper 3 walked: a neural network as render passes",
    source: "Oh & Jung, \"GPU implementation of neural networks\", Pattern Recognition 37(6), \
             2004, section 3.",
    run_is: "a 12-8-1 perceptron with made-up weights on L = 48 input vectors of N = 12 values",
    steps: STEPS,
    run,
};

const STEPS: &[Step] = &[
    Step {
        pass: "texture creation",
        section: "Sec. 3, Table 1 (first column)",
        step: "the two matrices are converted into textures, texture W and texture X",
        reads: "the weights, the biases and the batch of input vectors, on the CPU",
        writes: "texture W (N wide, M high), the 1D bias texture, texture X (L wide, N high: \
                 each input vector a column)",
        code: &[
            ("src/mlp/textures.rs", "weight-textures"),
            ("src/mlp/textures.rs", "input-texture"),
        ],
        lesson: "texture-is-array",
    },
    Step {
        pass: "matrix product W x X",
        section: "Sec. 3, eq. 2",
        step: "matrix multiplication: pixel (i, j) takes the inner product of row i of W with \
               column j of X",
        reads: "textures W and X",
        writes: "texture W x X, L wide and M high",
        code: &[
            ("src/mlp/matmul.rs", "product-passes"),
            ("glsl/mlp/product.frag", "product-main"),
            ("glsl/mlp/inner_product.frag", "inner-product"),
        ],
        lesson: "quad-is-loop",
    },
    Step {
        pass: "bias and sigmoid",
        section: "Sec. 3, eq. 3",
        step: "the pixel shader adds two textures and performs a sigmoid operation",
        reads: "texture W x X and the bias texture",
        writes: "texture R = sigmoid(W x X + B), laid out like X",
        code: &[
            ("src/mlp/activation.rs", "activation-pass"),
            ("glsl/mlp/bias_sigmoid.frag", "bias-sigmoid"),
        ],
        lesson: "quad-is-loop",
    },
    Step {
        pass: "the next layer, from the render target",
        section: "Sec. 3",
        step: "the result of the previous layer is saved as a render target texture, the input \
               of the next layer",
        reads: "texture R of layer 1 as the next layer's X, and layer 2's W and bias",
        writes: "layer 2's R, one output per input vector (L wide, 1 high), then read back",
        code: &[("src/mlp/chain.rs", "layer-chain")],
        lesson: "ping-pong",
    },
];

/// Layer sizes of the small run: N inputs, a hidden layer, one output; L input vectors.
const SIZES: [usize; 3] = [12, 8, 1];
const L: usize = 48;

/// A made-up but fixed value in about [-1, 1] for index `k` of stream `seed`.
fn value(seed: usize, k: usize) -> f32 {
    ((k as f32 * 0.731 + seed as f32 * 1.37).sin() * 43.758).fract()
}

/// The small network and batch.
pub fn small_case() -> anyhow::Result<(Network, Array2<f32>)> {
    let layers = SIZES
        .windows(2)
        .enumerate()
        .map(|(s, w)| Layer {
            weights: Array2::from_shape_fn((w[1], w[0]), |(i, k)| value(2 * s, i * w[0] + k)),
            bias: Array1::from_shape_fn(w[1], |i| 0.5 * value(2 * s + 1, i)),
            activation: Activation::Sigmoid,
        })
        .collect();
    let batch = Array2::from_shape_fn((L, SIZES[0]), |(j, k)| value(9, j * SIZES[0] + k));
    Ok((Network::new(layers)?, batch))
}

fn run(ctx: &Context, dir: &Path) -> anyhow::Result<Vec<Shot>> {
    let (net, batch) = small_case()?;
    let layers = net.layers();
    let precision = Precision::Fp32;
    let products = ProductPrograms::new(ctx, precision)?;
    let activation = activation_program(ctx, precision)?;
    let mut shots = Vec::new();

    // Texture creation.
    let first = layer_textures(ctx, &layers[0])?;
    let x = input_texture(ctx, batch.view())?;
    shots.push(Shot {
        pictures: vec![
            texture_png(dir, "X.png", "texture X", &x)?,
            texture_png(dir, "W1.png", "texture W, layer 1", &first.w)?,
        ],
        key: "X: column j is input vector j (48 columns, 12 rows, row 0 at the bottom); W: row i \
              holds the weights into output node i (12 wide, 8 high); blue below zero, red to \
              yellow above"
            .into(),
        check: None,
    });

    // Layer 1: product, then bias and sigmoid.
    let ranges = pass_ranges(first.n as usize, None);
    let targets = product_targets(ctx, L as u32, first.m, ranges.len())?;
    let product = product_passes(&products, &first, &x, &targets, &ranges)?;
    let gpu_product = product.color(0).download_f32()?;
    let cpu_product = cpu::product(CpuProduct::Plain, layers[0].weights.view(), batch.view());
    shots.push(Shot {
        pictures: vec![texture_png(
            dir,
            "WX1.png",
            "W x X, layer 1",
            product.color(0),
        )?],
        key: "pixel (j, i) = W_i . X_j: column j for input vector j, row i for hidden node i"
            .into(),
        check: Some(compare("W x X of layer 1", &gpu_product, &cpu_product)),
    });
    let hidden = float_target(ctx, "mlp R", L as u32, first.m)?;
    activation_pass(&activation, &first, product.color(0), &hidden)?;
    let gpu_hidden = hidden.color(0).download_f32()?;
    let cpu_hidden = cpu::layer_forward(CpuProduct::Plain, &layers[0], batch.view());
    shots.push(Shot {
        pictures: vec![texture_png(dir, "R1.png", "R, layer 1", hidden.color(0))?],
        key: "sigmoid values, all between 0 and 1: column j the hidden layer's answer to input \
              vector j"
            .into(),
        check: Some(compare("R of layer 1", &gpu_hidden, &cpu_hidden)),
    });

    // Layer 2 reads layer 1's render target as its X.
    let second = layer_textures(ctx, &layers[1])?;
    let ranges = pass_ranges(second.n as usize, None);
    let targets = product_targets(ctx, L as u32, second.m, ranges.len())?;
    let product = product_passes(&products, &second, hidden.color(0), &targets, &ranges)?;
    let output = float_target(ctx, "mlp R", L as u32, second.m)?;
    activation_pass(&activation, &second, product.color(0), &output)?;
    let gpu_output = output.color(0).download_f32()?;
    let cpu_output = cpu::forward(CpuProduct::Plain, &net, batch.view()).outputs;
    shots.push(Shot {
        pictures: vec![texture_png(
            dir,
            "R2.png",
            "R, layer 2 (the output)",
            output.color(0),
        )?],
        key: "one texel per input vector (48 wide, 1 high, stretched upward to be seen): the \
              network's output for each"
            .into(),
        check: Some(compare("the network's output", &gpu_output, &cpu_output)),
    });
    Ok(shots)
}

/// The tolerance of the comparisons: fp32 sums of 12 terms of size 1 in another order, and a
/// sigmoid, stay far inside it.
pub const TOLERANCE: f64 = 1e-5;

/// `gpu` (M rows of L, from the texture) against `cpu` (L x M) within [`TOLERANCE`].
fn compare(what: &str, gpu: &[f32], cpu: &Array2<f32>) -> Check {
    let (l, m) = cpu.dim();
    let mut worst = if gpu.len() == l * m {
        0.0f64
    } else {
        f64::INFINITY
    };
    for i in 0..m {
        for j in 0..l {
            let g = gpu.get(i * l + j).copied().unwrap_or(f32::NAN);
            let d = (g as f64 - cpu[[j, i]] as f64).abs();
            worst = if d.is_nan() {
                f64::INFINITY
            } else {
                worst.max(d)
            };
        }
    }
    Check {
        what: format!(
            "{what} against the CPU's (ndarray, f32): largest difference {worst:.1e} over {} \
             values (tolerance {TOLERANCE:.0e})",
            l * m
        ),
        passed: worst <= TOLERANCE,
    }
}

fn texture_png(dir: &Path, file: &str, title: &str, texture: &Texture) -> anyhow::Result<String> {
    let values = texture.download_f32()?;
    let dims = (texture.width(), texture.height());
    buffer_png(dir, file, title, &values, 1, &["value"], dims)
}
