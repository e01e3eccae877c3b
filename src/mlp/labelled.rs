//! Labelled images for training the text detector: a grey image and the truth of every pixel,
//! made by the synthetic generator ([`super::synth`]) or read from a user's image and mask.
//!
//! A mask is the classified image of section 4 (Fig. 2(b)) drawn by hand: the same size as its
//! image, a dark pixel (grey below 128) is text and a light one is not, as in the masks that
//! `mlp detect --out` writes.

use image::GrayImage;

/// An image and its per-pixel truth (true = text), row-major.
pub struct LabelledImage {
    pub image: GrayImage,
    pub text: Vec<bool>,
}

/// Grey values below this are text in a mask.
pub const MASK_TEXT_BELOW: u8 = 128;

/// What is wrong with a mask.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
pub enum MaskError {
    #[error(
        "the mask is {mask_width} x {mask_height} pixels but its image is {width} x {height}; \
         a mask gives the class of every pixel of its image"
    )]
    Size {
        width: u32,
        height: u32,
        mask_width: u32,
        mask_height: u32,
    },
}

impl LabelledImage {
    /// The image labelled by `mask` (dark = text).
    pub fn from_mask(image: GrayImage, mask: &GrayImage) -> Result<LabelledImage, MaskError> {
        if image.dimensions() != mask.dimensions() {
            return Err(MaskError::Size {
                width: image.width(),
                height: image.height(),
                mask_width: mask.width(),
                mask_height: mask.height(),
            });
        }
        let text = mask.pixels().map(|p| p.0[0] < MASK_TEXT_BELOW).collect();
        Ok(LabelledImage { image, text })
    }

    /// Pixels marked text.
    pub fn text_pixels(&self) -> usize {
        self.text.iter().filter(|&&t| t).count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dark_mask_pixels_are_text_and_sizes_must_match() {
        let image = GrayImage::from_pixel(3, 2, image::Luma([200]));
        let mask = GrayImage::from_fn(3, 2, |x, _| image::Luma([if x == 1 { 127 } else { 128 }]));
        let page = LabelledImage::from_mask(image.clone(), &mask).unwrap();
        assert_eq!(page.text, vec![false, true, false, false, true, false]);
        assert_eq!(page.text_pixels(), 2);
        let wrong = GrayImage::new(2, 3);
        let e = LabelledImage::from_mask(image, &wrong).err().unwrap();
        assert!(e.to_string().contains("2 x 3") && e.to_string().contains("3 x 2"));
    }
}
