//! CPU baselines and references: the forward pass `R = sigmoid(W x X + B)` (eq. 2-3) layer by
//! layer, with the matrix product done two ways.
//!
//! - [`CpuProduct::Plain`]: one inner product `W_i . X_j` per output, a plain loop in fp32,
//!   summed in index order: what the paper's CPU-only text detector did.
//! - [`CpuProduct::Optimised`]: `matrixmultiply`'s blocked, SIMD sgemm (through `ndarray`,
//!   two threads), the best a CPU does without hand-written kernels.
//!
//! Batches are L x N (row j = input vector X_j, the paper's column j), outputs L x M.

use super::network::{Activation, Layer, Network};
use ndarray::{linalg::general_mat_mul, Array2, ArrayView1, ArrayView2};
use std::time::{Duration, Instant};

/// Which CPU matrix product to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CpuProduct {
    Plain,
    Optimised,
}

impl CpuProduct {
    pub fn name(self) -> &'static str {
        match self {
            CpuProduct::Plain => "CPU plain loop",
            CpuProduct::Optimised => "CPU matrixmultiply sgemm",
        }
    }
}

/// The outputs of a forward pass and the time spent in each elementary operation.
#[derive(Clone, Debug)]
pub struct CpuForward {
    /// L x M of the last layer.
    pub outputs: Array2<f32>,
    pub product: Duration,
    pub activation: Duration,
}

/// `W x X` for a batch: `out[j][i] = W_i . X_j`, L x M.
pub fn product(kind: CpuProduct, weights: ArrayView2<f32>, batch: ArrayView2<f32>) -> Array2<f32> {
    assert_eq!(weights.ncols(), batch.ncols(), "N of W and X");
    match kind {
        CpuProduct::Plain => product_plain(weights, batch),
        CpuProduct::Optimised => product_optimised(weights, batch),
    }
}

/// The plain loop: every output is one inner product, accumulated in order k = 1..N.
fn product_plain(weights: ArrayView2<f32>, batch: ArrayView2<f32>) -> Array2<f32> {
    let (m, l) = (weights.nrows(), batch.nrows());
    let mut out = Array2::zeros((l, m));
    for (x_j, mut out_j) in batch.outer_iter().zip(out.outer_iter_mut()) {
        for (w_i, out_ji) in weights.outer_iter().zip(out_j.iter_mut()) {
            *out_ji = inner_product(w_i, x_j);
        }
    }
    out
}

fn inner_product(a: ArrayView1<f32>, b: ArrayView1<f32>) -> f32 {
    let mut sum = 0.0f32;
    for (x, y) in a.iter().zip(b.iter()) {
        sum += x * y;
    }
    sum
}

/// sgemm: out = X^T-as-stored x W^T, i.e. (L x N)(N x M), with no copies (strided views).
fn product_optimised(weights: ArrayView2<f32>, batch: ArrayView2<f32>) -> Array2<f32> {
    let mut out = Array2::zeros((batch.nrows(), weights.nrows()));
    general_mat_mul(1.0, &batch, &weights.t(), 0.0, &mut out);
    out
}

/// `R = activation(M + B)` in place on an L x M product (eq. 3): the bias of output node i
/// is added to column i of every row.
pub fn bias_activation(product: &mut Array2<f32>, bias: ArrayView1<f32>, activation: Activation) {
    for mut row in product.outer_iter_mut() {
        for (m, &b) in row.iter_mut().zip(bias.iter()) {
            *m = activation.apply(*m + b);
        }
    }
}

/// One layer on the CPU.
pub fn layer_forward(kind: CpuProduct, layer: &Layer, batch: ArrayView2<f32>) -> Array2<f32> {
    let mut out = product(kind, layer.weights.view(), batch);
    bias_activation(&mut out, layer.bias.view(), layer.activation);
    out
}

/// The whole network on a batch (L x N), timing the products and activations apart.
pub fn forward(kind: CpuProduct, net: &Network, batch: ArrayView2<f32>) -> CpuForward {
    assert_eq!(batch.ncols(), net.inputs(), "input length");
    let mut timings = (Duration::ZERO, Duration::ZERO);
    let mut current: Option<Array2<f32>> = None;
    for layer in net.layers() {
        let start = Instant::now();
        let mut out = match &current {
            Some(previous) => product(kind, layer.weights.view(), previous.view()),
            None => product(kind, layer.weights.view(), batch),
        };
        timings.0 += start.elapsed();
        let start = Instant::now();
        bias_activation(&mut out, layer.bias.view(), layer.activation);
        timings.1 += start.elapsed();
        current = Some(out);
    }
    CpuForward {
        outputs: current.expect("a network has at least one layer"),
        product: timings.0,
        activation: timings.1,
    }
}

/// A bound on |computed - exact| of every output of [`forward`], for any fp32 evaluation
/// that sums each inner product in some order (loop, blocked sgemm or a shader): per layer,
/// the rounding of an n-term sum is at most `gamma_n * sum |w x|` with `gamma_n = n u/(1-n u)`
/// (Higham, Accuracy and Stability, 3.1), errors coming in are scaled by `|W|`, a sigmoid
/// scales them by at most 1/4 and adds its own evaluation error (a few ulp of `exp`, and GLSL
/// allows `3 + 2|x|` ulp, taken here as 1e-6 absolute). Two implementations then agree within
/// twice the bound.
pub fn error_bound(net: &Network, batch: ArrayView2<f32>) -> Array2<f32> {
    const SIGMOID_EVALUATION: f64 = 1e-6;
    rounding_bound(
        net,
        batch,
        f64::from(f32::EPSILON) / 2.0,
        0,
        SIGMOID_EVALUATION,
    )
}

/// [`error_bound`] for an arithmetic of unit roundoff `u`, with `extra_steps` more rounded
/// steps per term of each inner product than fp32's one per addition (the 24-bit emulation
/// also rounds each fetched value and product), and a sigmoid evaluated within
/// `sigmoid_evaluation` (absolute).
pub fn rounding_bound(
    net: &Network,
    batch: ArrayView2<f32>,
    u: f64,
    extra_steps: usize,
    sigmoid_evaluation: f64,
) -> Array2<f32> {
    let mut values = batch.mapv(f64::from);
    let mut errors = Array2::<f64>::zeros(batch.raw_dim());
    for layer in net.layers() {
        let n = (layer.inputs() + 1 + extra_steps) as f64;
        let gamma = n * u / (1.0 - n * u) + 4.0 * u;
        let w = layer.weights.mapv(f64::from);
        let abs_w = w.mapv(f64::abs);
        let bias = layer.bias.mapv(f64::from);
        let sum_abs = values.mapv(f64::abs).dot(&abs_w.t()) + bias.mapv(f64::abs);
        let carried = errors.dot(&abs_w.t());
        let mut m = values.dot(&w.t()) + &bias;
        let mut e = carried + sum_abs * gamma;
        match layer.activation {
            Activation::Sigmoid => {
                m.mapv_inplace(|v| 1.0 / (1.0 + (-v).exp()));
                e.mapv_inplace(|v| (0.25 * v).min(1.0) + sigmoid_evaluation);
            }
            Activation::Identity => {}
        }
        values = m;
        errors = e;
    }
    errors.mapv(|e| e as f32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::{array, Array1};

    fn small_net() -> Network {
        Network::new(vec![
            Layer {
                weights: array![[1.0, 2.0, -1.0], [0.5, 0.0, 0.25]],
                bias: Array1::from(vec![0.5, -1.0]),
                activation: Activation::Sigmoid,
            },
            Layer {
                weights: array![[2.0, -3.0]],
                bias: Array1::from(vec![0.25]),
                activation: Activation::Identity,
            },
        ])
        .unwrap()
    }

    #[test]
    fn forward_matches_a_hand_computation() {
        let x = array![[1.0f32, 0.0, 2.0], [0.0, 1.0, 4.0]];
        let sig = |v: f64| 1.0 / (1.0 + (-v).exp());
        for kind in [CpuProduct::Plain, CpuProduct::Optimised] {
            let out = forward(kind, &small_net(), x.view()).outputs;
            // x_0: hidden = sig(1 - 2 + 0.5), sig(0.5 + 0.5 - 1); x_1: sig(2 - 4 + 0.5), sig(1 - 1)
            let expect = [
                2.0 * sig(-0.5) - 3.0 * sig(0.0) + 0.25,
                2.0 * sig(-1.5) - 3.0 * sig(0.0) + 0.25,
            ];
            for (j, e) in expect.iter().enumerate() {
                assert!((f64::from(out[[j, 0]]) - e).abs() < 1e-6, "{kind:?} {j}");
            }
        }
    }

    #[test]
    fn plain_and_optimised_agree_within_the_bound() {
        let w = Array2::from_shape_fn((7, 33), |(i, k)| {
            ((i * 31 + k * 17) % 13) as f32 / 6.5 - 1.0
        });
        let net = Network::new(vec![Layer {
            weights: w,
            bias: Array1::from_shape_fn(7, |i| i as f32 / 7.0),
            activation: Activation::Identity,
        }])
        .unwrap();
        let x = Array2::from_shape_fn((19, 33), |(j, k)| ((j * 7 + k * 3) % 11) as f32 / 3.3);
        let a = forward(CpuProduct::Plain, &net, x.view()).outputs;
        let b = forward(CpuProduct::Optimised, &net, x.view()).outputs;
        let bound = error_bound(&net, x.view());
        for ((a, b), e) in a.iter().zip(b.iter()).zip(bound.iter()) {
            assert!((a - b).abs() <= 2.0 * e, "{a} {b} {e}");
        }
    }
}
