//! Text detection (section 4, Fig. 2): every pixel's 11 x 11 window goes through the
//! network in one batch; the output compared with a threshold gives the classified image,
//! where a black pixel is a text pixel.

use super::cpu::{forward, CpuProduct};
use super::network::{FormatError, Network};
use super::window::window_batch;
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
pub fn classify_cpu(net: &Network, image: &GrayImage, kind: CpuProduct, max_batch: usize) -> Vec<f32> {
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

/// The classified image: black where the output exceeds `threshold` (text), white elsewhere.
pub fn mask_image(outputs: &[f32], width: u32, height: u32, threshold: f32) -> GrayImage {
    GrayImage::from_fn(width, height, |x, y| {
        let text = outputs[(y * width + x) as usize] > threshold;
        image::Luma([if text { 0 } else { 255 }])
    })
}
