//! Training the text detector on the CPU: plain online backpropagation with momentum,
//! deterministic (one seeded ChaCha8 generator for the data, the initial weights and the
//! sample order; every sum in a fixed order; one thread).
//!
//! The network is the paper's: 11 x 11 window inputs, one hidden layer of 30 sigmoid nodes,
//! one sigmoid output (text when above 0.5). The loss is the cross-entropy of the output,
//! whose gradient at the output's input is simply `y - t`. Inputs are centred (x - 1/2)
//! while training, and the shift is folded into the first bias at the end, so the shipped
//! network takes grey values in [0, 1] like [`super::window`] makes them.

use super::labelled::LabelledImage;
use super::network::{Activation, Layer, Network};
use super::synth::labelled_image;
use super::window::{window_vector, WINDOW_INPUTS};
use ndarray::{Array1, Array2, ArrayView1};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// Everything that decides the trained weights; [`TrainConfig::default`] made the shipped ones.
#[derive(Clone, Debug, Serialize)]
pub struct TrainConfig {
    pub seed: u64,
    /// Synthetic images to sample windows from.
    pub images: usize,
    /// At most this many text and this many non-text windows from each image.
    pub windows_per_class: usize,
    /// Hidden nodes (the paper: 30).
    pub hidden: usize,
    pub epochs: usize,
    pub learning_rate: f32,
    pub momentum: f32,
}

impl Default for TrainConfig {
    fn default() -> Self {
        TrainConfig {
            seed: 2004,
            images: 2000,
            windows_per_class: 30,
            hidden: 30,
            epochs: 20,
            learning_rate: 0.01,
            momentum: 0.9,
        }
    }
}

/// Windows (S x 121 grey values in [0, 1]) and their truth (1 = text).
pub struct WindowSet {
    pub inputs: Array2<f32>,
    pub labels: Vec<f32>,
}

/// Detection quality at a threshold.
#[derive(Clone, Debug, Serialize)]
pub struct Evaluation {
    pub windows: usize,
    pub accuracy: f64,
    /// Of the windows called text, the share that are text.
    pub precision: f64,
    /// Of the text windows, the share called text.
    pub recall: f64,
}

/// A trained network and its training curve.
pub struct Trained {
    pub network: Network,
    /// Mean cross-entropy over the training windows after each epoch.
    pub loss_per_epoch: Vec<f64>,
}

/// Samples windows from `images` synthetic images made from `seed`: up to `per_class` text and
/// `per_class` non-text pixels of each, at random positions.
pub fn window_set(seed: u64, images: usize, per_class: usize) -> WindowSet {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mut rows, mut labels) = (Vec::new(), Vec::new());
    for _ in 0..images {
        let page = labelled_image(&mut rng);
        sample_windows(&mut rng, &page, per_class, &mut rows, &mut labels);
    }
    let inputs = Array2::from_shape_vec((labels.len(), WINDOW_INPUTS), rows).expect("shape");
    WindowSet { inputs, labels }
}

/// Up to `per_class` text and `per_class` non-text windows of `page` at random positions,
/// appended to `rows` (121 values each) and `labels`.
fn sample_windows(
    rng: &mut ChaCha8Rng,
    page: &LabelledImage,
    per_class: usize,
    rows: &mut Vec<f32>,
    labels: &mut Vec<f32>,
) {
    let width = page.image.width();
    let mut window = [0.0f32; WINDOW_INPUTS];
    let (mut text, mut plain): (Vec<usize>, Vec<usize>) =
        (0..page.text.len()).partition(|&p| page.text[p]);
    for (pixels, label) in [(&mut text, 1.0), (&mut plain, 0.0)] {
        let (chosen, _) = pixels.partial_shuffle(rng, per_class);
        for &p in chosen.iter() {
            let (x, y) = (p as u32 % width, p as u32 / width);
            window_vector(&page.image, x, y, &mut window);
            rows.extend_from_slice(&window);
            labels.push(label);
        }
    }
}

/// One window in this many is held out of training, for evaluation.
pub const HELD_OUT_EVERY: usize = 5;

/// Why the user's labelled images cannot train a detector.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
pub enum TrainDataError {
    #[error(
        "the masks mark no pixel as text (text is dark, below 128, as in the masks `mlp \
         detect --out` writes); a detector needs text and non-text examples"
    )]
    NoText,
    #[error(
        "the masks mark every pixel as text (text is dark, below 128); a detector needs text \
         and non-text examples"
    )]
    NoBackground,
}

/// Windows of the user's labelled images: up to `per_class` text and `per_class` non-text
/// windows of each image (seeded), shuffled, then split into a training set and a held-out set
/// of one window in [`HELD_OUT_EVERY`] (other windows of the same images).
pub fn labelled_window_sets(
    pages: &[LabelledImage],
    per_class: usize,
    seed: u64,
) -> Result<(WindowSet, WindowSet), TrainDataError> {
    if pages.iter().all(|p| p.text_pixels() == 0) {
        return Err(TrainDataError::NoText);
    }
    if pages.iter().all(|p| p.text_pixels() == p.text.len()) {
        return Err(TrainDataError::NoBackground);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (mut rows, mut labels) = (Vec::new(), Vec::new());
    for page in pages {
        sample_windows(&mut rng, page, per_class, &mut rows, &mut labels);
    }
    let mut order: Vec<usize> = (0..labels.len()).collect();
    order.shuffle(&mut rng);
    let subset = |keep: &dyn Fn(usize) -> bool| {
        let chosen: Vec<usize> = order
            .iter()
            .enumerate()
            .filter(|&(position, _)| keep(position))
            .map(|(_, &s)| s)
            .collect();
        let flat: Vec<f32> = chosen
            .iter()
            .flat_map(|&s| {
                rows[s * WINDOW_INPUTS..(s + 1) * WINDOW_INPUTS]
                    .iter()
                    .copied()
            })
            .collect();
        WindowSet {
            inputs: Array2::from_shape_vec((chosen.len(), WINDOW_INPUTS), flat).expect("shape"),
            labels: chosen.iter().map(|&s| labels[s]).collect(),
        }
    };
    let held_out = |position: usize| position % HELD_OUT_EVERY == HELD_OUT_EVERY - 1;
    Ok((subset(&|p| !held_out(p)), subset(&held_out)))
}

/// Trains a 121-`hidden`-1 sigmoid network by online backpropagation.
pub fn train(config: &TrainConfig, set: &WindowSet) -> Trained {
    let mut rng = ChaCha8Rng::seed_from_u64(config.seed ^ 0x7a11);
    let mut net = Mlp2::random(&mut rng, WINDOW_INPUTS, config.hidden);
    let mut momentum = Mlp2::zeros(WINDOW_INPUTS, config.hidden);
    let mut order: Vec<usize> = (0..set.labels.len()).collect();
    let mut loss_per_epoch = Vec::with_capacity(config.epochs);
    let mut centred = vec![0.0f32; WINDOW_INPUTS];
    for _ in 0..config.epochs {
        order.shuffle(&mut rng);
        let mut loss = 0.0f64;
        for &s in &order {
            for (c, &x) in centred.iter_mut().zip(set.inputs.row(s).iter()) {
                *c = x - 0.5;
            }
            loss += net.backprop_step(
                &centred,
                set.labels[s],
                config.learning_rate,
                config.momentum,
                &mut momentum,
            );
        }
        loss_per_epoch.push(loss / set.labels.len().max(1) as f64);
    }
    Trained {
        network: net.into_network(),
        loss_per_epoch,
    }
}

/// Accuracy, precision and recall of `outputs` (one per window) against `labels`.
pub fn evaluate(outputs: ArrayView1<f32>, labels: &[f32], threshold: f32) -> Evaluation {
    let mut counts = [0usize; 4]; // true positive, false positive, false negative, true negative
    for (&y, &t) in outputs.iter().zip(labels) {
        let index = match (y > threshold, t > 0.5) {
            (true, true) => 0,
            (true, false) => 1,
            (false, true) => 2,
            (false, false) => 3,
        };
        counts[index] += 1;
    }
    let [tp, fp, fn_, tn] = counts.map(|c| c as f64);
    let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { 0.0 };
    Evaluation {
        windows: labels.len(),
        accuracy: ratio(tp + tn, tp + fp + fn_ + tn),
        precision: ratio(tp, tp + fp),
        recall: ratio(tp, tp + fn_),
    }
}

/// The two-layer perceptron being trained: hidden h = sig(W1 x + b1), output y = sig(w2 . h + b2).
struct Mlp2 {
    w1: Array2<f32>,
    b1: Array1<f32>,
    w2: Array1<f32>,
    b2: f32,
}

impl Mlp2 {
    /// Uniform in +-1/sqrt(fan-in), from the seeded generator.
    fn random(rng: &mut impl Rng, inputs: usize, hidden: usize) -> Mlp2 {
        let r1 = 1.0 / (inputs as f32).sqrt();
        let r2 = 1.0 / (hidden as f32).sqrt();
        Mlp2 {
            w1: Array2::from_shape_simple_fn((hidden, inputs), || rng.gen_range(-r1..r1)),
            b1: Array1::zeros(hidden),
            w2: Array1::from_shape_simple_fn(hidden, || rng.gen_range(-r2..r2)),
            b2: 0.0,
        }
    }

    fn zeros(inputs: usize, hidden: usize) -> Mlp2 {
        Mlp2 {
            w1: Array2::zeros((hidden, inputs)),
            b1: Array1::zeros(hidden),
            w2: Array1::zeros(hidden),
            b2: 0.0,
        }
    }

    /// One forward and backward pass on one window; updates the weights with momentum and
    /// returns the window's cross-entropy.
    fn backprop_step(&mut self, x: &[f32], t: f32, rate: f32, mu: f32, v: &mut Mlp2) -> f64 {
        let sigmoid = Activation::Sigmoid;
        let h: Vec<f32> = self
            .w1
            .outer_iter()
            .zip(self.b1.iter())
            .map(|(w, &b)| sigmoid.apply(dot(w.as_slice().expect("row"), x) + b))
            .collect();
        let y = sigmoid.apply(dot(self.w2.as_slice().expect("row"), &h) + self.b2);
        // output delta of sigmoid + cross-entropy, then the hidden deltas (old w2)
        let delta = y - t;
        for (j, &hj) in h.iter().enumerate() {
            let delta_j = delta * self.w2[j] * hj * (1.0 - hj);
            let (w_row, v_row) = (self.w1.row_mut(j), v.w1.row_mut(j));
            for ((w, vel), &xi) in w_row.into_iter().zip(v_row).zip(x) {
                *vel = mu * *vel - rate * delta_j * xi;
                *w += *vel;
            }
            v.b1[j] = mu * v.b1[j] - rate * delta_j;
            self.b1[j] += v.b1[j];
            v.w2[j] = mu * v.w2[j] - rate * delta * hj;
            self.w2[j] += v.w2[j];
        }
        v.b2 = mu * v.b2 - rate * delta;
        self.b2 += v.b2;
        let y = f64::from(y).clamp(1e-7, 1.0 - 1e-7);
        -(f64::from(t) * y.ln() + (1.0 - f64::from(t)) * (1.0 - y).ln())
    }

    /// The network file form, with the input centring folded into b1: W1 (x - 1/2) + b1 =
    /// W1 x + (b1 - W1 1/2).
    fn into_network(self) -> Network {
        let b1 = &self.b1 - &(self.w1.sum_axis(ndarray::Axis(1)) * 0.5);
        let hidden = self.w2.len();
        Network::new(vec![
            Layer {
                weights: self.w1,
                bias: b1,
                activation: Activation::Sigmoid,
            },
            Layer {
                weights: self
                    .w2
                    .into_shape_with_order((1, hidden))
                    .expect("1 x hidden"),
                bias: Array1::from(vec![self.b2]),
                activation: Activation::Sigmoid,
            },
        ])
        .expect("trained weights are finite and shaped")
    }
}

fn dot(a: &[f32], b: &[f32]) -> f32 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mlp::cpu::{forward, CpuProduct};

    fn tiny() -> TrainConfig {
        TrainConfig {
            images: 12,
            windows_per_class: 10,
            hidden: 6,
            epochs: 3,
            ..TrainConfig::default()
        }
    }

    #[test]
    fn training_is_deterministic_and_lowers_the_loss() {
        let config = tiny();
        let set = window_set(config.seed, config.images, config.windows_per_class);
        assert!(set.labels.contains(&1.0) && set.labels.contains(&0.0));
        let a = train(&config, &set);
        let b = train(&config, &set);
        assert_eq!(a.network, b.network);
        assert_eq!(a.loss_per_epoch, b.loss_per_epoch);
        assert!(
            a.loss_per_epoch[2] < a.loss_per_epoch[0],
            "{:?}",
            a.loss_per_epoch
        );
    }

    #[test]
    fn folding_the_centring_keeps_the_outputs() {
        let config = tiny();
        let set = window_set(5, 4, 5);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let mlp = Mlp2::random(&mut rng, WINDOW_INPUTS, config.hidden);
        let expect: Vec<f32> = set
            .inputs
            .outer_iter()
            .map(|x| {
                let c: Vec<f32> = x.iter().map(|v| v - 0.5).collect();
                let h: Vec<f32> = mlp
                    .w1
                    .outer_iter()
                    .zip(mlp.b1.iter())
                    .map(|(w, &b)| Activation::Sigmoid.apply(dot(w.as_slice().unwrap(), &c) + b))
                    .collect();
                Activation::Sigmoid.apply(dot(mlp.w2.as_slice().unwrap(), &h) + mlp.b2)
            })
            .collect();
        let net = mlp.into_network();
        let got = forward(CpuProduct::Plain, &net, set.inputs.view()).outputs;
        for (g, e) in got.iter().zip(&expect) {
            assert!((g - e).abs() < 1e-5, "{g} {e}");
        }
    }

    #[test]
    fn labelled_windows_are_split_and_one_class_masks_refused() {
        let image = image::GrayImage::from_fn(10, 6, |x, y| image::Luma([(x * 20 + y) as u8]));
        let text: Vec<bool> = (0..60).map(|p| p % 10 < 3).collect(); // 18 text pixels
        let page = LabelledImage {
            image: image.clone(),
            text,
        };
        let (train, held_out) = labelled_window_sets(&[page], 100, 1).unwrap();
        assert_eq!(train.labels.len() + held_out.labels.len(), 60);
        assert_eq!(held_out.labels.len(), 60 / HELD_OUT_EVERY);
        let text_windows = train
            .labels
            .iter()
            .chain(&held_out.labels)
            .filter(|&&t| t == 1.0);
        assert_eq!(text_windows.count(), 18);
        // each window is its pixel's: row j of the inputs is the window of a pixel of its class
        let mut window = [0.0f32; WINDOW_INPUTS];
        let found = (0..60u32).any(|p| {
            window_vector(&image, p % 10, p / 10, &mut window);
            window[..] == train.inputs.row(0).as_slice().unwrap()[..]
                && (p % 10 < 3) == (train.labels[0] == 1.0)
        });
        assert!(found);
        let blank = |text| LabelledImage {
            image: image.clone(),
            text: vec![text; 60],
        };
        let e = labelled_window_sets(&[blank(false)], 10, 1).err();
        assert_eq!(e, Some(TrainDataError::NoText));
        let e = labelled_window_sets(&[blank(true)], 10, 1).err();
        assert_eq!(e, Some(TrainDataError::NoBackground));
    }

    #[test]
    fn evaluation_counts() {
        let outputs = ndarray::arr1(&[0.9f32, 0.2, 0.7, 0.1]);
        let e = evaluate(outputs.view(), &[1.0, 1.0, 0.0, 0.0], 0.5);
        assert_eq!((e.accuracy, e.precision, e.recall), (0.5, 0.5, 0.5));
    }
}
