//! Text detection (section 4, Fig. 2): every pixel's 11 x 11 window goes through the
//! network in one batch; the output compared with a threshold gives the classified image,
//! where a black pixel is a text pixel.

use super::chain::{GpuNetwork, StepTimes};
use super::cpu::{forward, CpuProduct};
use super::network::{FormatError, Network};
use super::window::window_batch;
use crate::gl::GlError;
use image::GrayImage;

/// The output above which a pixel is text.
pub const THRESHOLD: f32 = 0.5;

/// The shipped detector's weights (`classic-gpgpu mlp train` reproduces them).
pub const DETECTOR_JSON: &str = include_str!("../../assets/mlp/text_detector.json");

/// The shipped 121-30-1 detector.
pub fn shipped_detector() -> Result<Network, FormatError> {
    Network::from_json(DETECTOR_JSON)
}

/// The network output of every pixel (row-major), the time spent in each step, and how many
/// batches went through the network (GPU: texture tiles; CPU: bands of rows).
#[derive(Clone, Debug)]
pub struct Classified {
    pub outputs: Vec<f32>,
    pub times: StepTimes,
    pub batches: usize,
}

/// The image's rows in bands whose batch stays near `max_batch` input vectors.
fn bands(image: &GrayImage, max_batch: usize) -> Vec<std::ops::Range<u32>> {
    let rows_per_band = (max_batch / image.width().max(1) as usize).clamp(1, u32::MAX as usize);
    (0..image.height())
        .step_by(rows_per_band)
        .map(|y| y..(y + rows_per_band as u32).min(image.height()))
        .collect()
}

/// Every pixel through the network on the CPU, the image in bands of rows of about
/// `max_batch` input vectors; the product and activation times are measured (the GPU-only
/// steps, texture creation and readback, stay zero).
pub fn classify_cpu(
    net: &Network,
    image: &GrayImage,
    kind: CpuProduct,
    max_batch: usize,
) -> Classified {
    let mut classified = Classified {
        outputs: Vec::with_capacity((image.width() * image.height()) as usize),
        times: StepTimes::default(),
        batches: 0,
    };
    for rows in bands(image, max_batch) {
        let batch = window_batch(image, rows);
        let result = forward(kind, net, batch.view());
        classified.outputs.extend(result.outputs.column(0).iter());
        classified.times.matmul += result.product.as_secs_f64() * 1e3;
        classified.times.activation += result.activation.as_secs_f64() * 1e3;
        classified.batches += 1;
    }
    classified
}

/// Every pixel through the network on the GPU: the windows of a band of rows accumulated into
/// one batch, split into tiles of at most `max_vectors` input vectors by
/// [`GpuNetwork::forward`] (default: one texture's worth).
pub fn classify_gpu(
    net: &GpuNetwork,
    image: &GrayImage,
    max_batch: usize,
    max_vectors: Option<usize>,
) -> Result<Classified, GlError> {
    let mut classified = Classified {
        outputs: Vec::with_capacity((image.width() * image.height()) as usize),
        times: StepTimes::default(),
        batches: 0,
    };
    for rows in bands(image, max_batch) {
        let batch = window_batch(image, rows);
        let result = net.forward(batch.view(), max_vectors)?;
        classified.outputs.extend(result.outputs.column(0).iter());
        classified.times.add(&result.times);
        classified.batches += result.tiles;
    }
    Ok(classified)
}

/// The classified image: black where the output exceeds `threshold` (text), white elsewhere.
pub fn mask_image(outputs: &[f32], width: u32, height: u32, threshold: f32) -> GrayImage {
    GrayImage::from_fn(width, height, |x, y| {
        let text = outputs[(y * width + x) as usize] > threshold;
        image::Luma([if text { 0 } else { 255 }])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mlp::train::{evaluate, window_set};
    use crate::mlp::window::WINDOW_INPUTS;

    #[test]
    fn shipped_detector_is_the_papers_shape_and_finds_text() {
        let net = shipped_detector().unwrap();
        let shape: Vec<usize> = net.layers().iter().map(|l| l.outputs()).collect();
        assert_eq!((net.inputs(), shape), (WINDOW_INPUTS, vec![30, 1]));
        // windows from images it was not trained on (another seed); the full held-out run of
        // `mlp train` measured 89% accuracy
        let test = window_set(77, 40, 30);
        let out = forward(CpuProduct::Optimised, &net, test.inputs.view()).outputs;
        let quality = evaluate(out.column(0), &test.labels, THRESHOLD);
        assert!(quality.accuracy > 0.8, "{quality:?}");
        assert!(
            quality.precision > 0.75 && quality.recall > 0.7,
            "{quality:?}"
        );
    }

    #[test]
    fn banded_classification_equals_one_batch() {
        let net = shipped_detector().unwrap();
        let image =
            GrayImage::from_fn(23, 9, |x, y| image::Luma([((x * 37 + y * 91) % 256) as u8]));
        let whole = classify_cpu(&net, &image, CpuProduct::Plain, 1 << 20);
        let banded = classify_cpu(&net, &image, CpuProduct::Plain, 50);
        assert_eq!((whole.batches, banded.batches), (1, 5)); // 2 rows of 23 per band
        assert_eq!(whole.outputs, banded.outputs);
        assert!(whole.times.matmul > 0.0 && whole.times.activation > 0.0);
        let whole = whole.outputs;
        let mask = mask_image(&whole, 23, 9, THRESHOLD);
        let black = whole.iter().filter(|&&v| v > THRESHOLD).count();
        assert_eq!(mask.pixels().filter(|p| p.0[0] == 0).count(), black);
    }
}
