//! Paper 3: Oh & Jung, "GPU implementation of neural networks", Pattern Recognition 37(6),
//! 2004: a multilayer perceptron evaluated as render passes, applied to text detection.
//!
//! Each layer computes `R = sigmoid(W x X + B)` (section 3, eq. 1-3): W (M x N) holds the
//! weights into the M output nodes, X (N x L) holds L accumulated input vectors as columns,
//! B repeats the bias b_i along row i. The code keeps this notation (W, X, B, M, N, L, R).
//! On the CPU a batch is stored L x N, row j being the paper's column X_j.
//!
//! One file per step: [`network`] (the network and input files), [`cpu`] (the CPU baselines
//! and references), [`textures`] (texture creation), [`matmul`] (the matrix-product passes),
//! [`activation`] (the bias + sigmoid pass), [`chain`] (layers chained through render
//! targets), [`packed`] (the faster RGBA formulation), [`tiling`] (batches beyond the maximum
//! texture size), [`window`] (the 11 x 11 input windows of section 4), [`labelled`] (images
//! and their per-pixel truth), [`synth`] (synthetic training images), [`train`]
//! (backpropagation), [`detect`] (classifying every pixel of an image), [`fp24`] (the paper's
//! board's 24-bit arithmetic, emulated). Shaders: `glsl/mlp/`.
//! The `mlp` commands live in the binary (`src/cli/mlp.rs`).

pub mod activation;
pub mod chain;
pub mod compute;
pub mod cpu;
pub mod detect;
pub mod fp24;
pub mod labelled;
pub mod matmul;
pub mod network;
pub mod packed;
pub mod synth;
pub mod textures;
pub mod tiling;
pub mod train;
pub mod window;

pub use chain::{Formulation, GpuMlp, GpuNetwork, StepTimes};
pub use network::{Activation, FormatError, Layer, Network};
pub use tiling::GpuForward;
