//! Text detection (section 4, Fig. 2): every pixel's 11 x 11 window goes through the
//! network in one batch; the output compared with a threshold gives the classified image,
//! where a black pixel is a text pixel.

use super::chain::GpuNetwork;
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

/// The network output of every pixel (row-major), on the CPU, the image in bands of rows
/// so that a band's batch stays near `max_batch` input vectors.
pub fn classify_cpu(
    net: &Network,
    image: &GrayImage,
    kind: CpuProduct,
    max_batch: usize,
) -> Vec<f32> {
    let rows_per_band = (max_batch / image.width().max(1) as usize).max(1) as u32;
    let mut outputs = Vec::with_capacity((image.width() * image.height()) as usize);
    let mut y = 0;
    while y < image.height() {
        let end = (y + rows_per_band).min(image.height());
        let batch = window_batch(image, y..end);
        outputs.extend(forward(kind, net, batch.view()).outputs.column(0).iter());
        y = end;
    }
    outputs
}

/// The network output of every pixel on the GPU: the windows of a band of rows accumulated
/// into one batch (tiled to the texture size by [`GpuNetwork::forward`]). Also returns the
/// summed step times.
pub fn classify_gpu(
    net: &GpuNetwork,
    image: &GrayImage,
    max_batch: usize,
) -> Result<(Vec<f32>, super::chain::StepTimes), GlError> {
    let rows_per_band = (max_batch / image.width().max(1) as usize).max(1) as u32;
    let mut outputs = Vec::with_capacity((image.width() * image.height()) as usize);
    let mut times = super::chain::StepTimes::default();
    let mut y = 0;
    while y < image.height() {
        let end = (y + rows_per_band).min(image.height());
        let batch = window_batch(image, y..end);
        let result = net.forward(batch.view(), None)?;
        outputs.extend(result.outputs.column(0).iter());
        times.add(&result.times);
        y = end;
    }
    Ok((outputs, times))
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
        assert_eq!(whole, banded);
        let mask = mask_image(&whole, 23, 9, THRESHOLD);
        let black = whole.iter().filter(|&&v| v > THRESHOLD).count();
        assert_eq!(mask.pixels().filter(|p| p.0[0] == 0).count(), black);
    }
}
