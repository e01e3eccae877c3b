//! Input vectors of the text detector (section 4): "the grey values for the pixels at
//! predefined positions inside an M x M window over the input image", M = 11.
//!
//! A pixel's input vector lists the window row by row, each grey value scaled to [0, 1];
//! windows that cross the image border repeat the edge pixels (clamp to edge).

use image::GrayImage;
use ndarray::Array2;

/// The window side of the paper's experiments: 11 x 11 = 121 inputs.
pub const WINDOW: usize = 11;

/// Inputs per pixel: WINDOW^2.
pub const WINDOW_INPUTS: usize = WINDOW * WINDOW;

/// Writes the window around pixel (x, y) into `out` (WINDOW_INPUTS values).
pub fn window_vector(image: &GrayImage, x: u32, y: u32, out: &mut [f32]) {
    debug_assert_eq!(out.len(), WINDOW_INPUTS);
    let half = (WINDOW / 2) as i64;
    let (w, h) = (i64::from(image.width()), i64::from(image.height()));
    let raw = image.as_raw();
    for dy in 0..WINDOW as i64 {
        let sy = (i64::from(y) + dy - half).clamp(0, h - 1);
        for dx in 0..WINDOW as i64 {
            let sx = (i64::from(x) + dx - half).clamp(0, w - 1);
            let grey = raw[(sy * w + sx) as usize];
            out[(dy * WINDOW as i64 + dx) as usize] = f32::from(grey) / 255.0;
        }
    }
}

/// The input vectors of image rows `rows` (all pixels, row-major), as an L x 121 batch:
/// the paper's "accumulating a large number of input vectors" into one matrix.
pub fn window_batch(image: &GrayImage, rows: std::ops::Range<u32>) -> Array2<f32> {
    let width = image.width() as usize;
    let mut batch = Array2::zeros((rows.len() * width, WINDOW_INPUTS));
    for (j, mut row) in batch.outer_iter_mut().enumerate() {
        let (x, y) = ((j % width) as u32, rows.start + (j / width) as u32);
        window_vector(image, x, y, row.as_slice_mut().expect("standard layout"));
    }
    batch
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_are_row_major_and_clamped() {
        let image = GrayImage::from_fn(20, 15, |x, y| image::Luma([(x + 10 * y) as u8]));
        let batch = window_batch(&image, 0..15);
        assert_eq!(batch.dim(), (300, 121));
        // pixel (10, 7): window row 0 is image row 2, columns 5..=15
        let j = 7 * 20 + 10;
        assert_eq!(batch[[j, 0]], (5.0 + 20.0) / 255.0);
        assert_eq!(batch[[j, 120]], (15.0 + 120.0) / 255.0);
        // pixel (0, 0): everything left of / above the image repeats the edge
        assert_eq!(batch[[0, 0]], 0.0);
        assert_eq!(batch[[0, 5 * 11 + 6]], 1.0 / 255.0);
        // a band of rows gives the same vectors as the whole image
        let band = window_batch(&image, 7..8);
        assert_eq!(band.row(10), batch.row(j));
    }
}
