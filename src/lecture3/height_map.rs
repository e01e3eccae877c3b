//! The height (displacement) map that techniques 1 and 2 work on: any greyscale image, its
//! grey levels taken as heights in [0, 1], and the small map this project ships
//! (`assets/lecture3/height.png`, made by [`HeightMap::generated`]).
//!
//! Samples are stored row by row from the bottom, as GL stores textures: sample (x, y) is
//! `heights[y * width + x]`, and row 0 is the bottom row of the image file.

use super::error::Error;
use std::path::Path;

/// The side of the shipped map.
pub const SHIPPED_SIZE: u32 = 64;

/// Where the shipped map lives, relative to the repository.
pub const SHIPPED_PATH: &str = "assets/lecture3/height.png";

/// A grid of heights in [0, 1], at least 2 x 2 (one bilinear patch).
#[derive(Clone, Debug, PartialEq)]
pub struct HeightMap {
    width: u32,
    height: u32,
    heights: Vec<f32>,
}

impl HeightMap {
    /// A map of `width x height` samples; `name` names it in errors.
    pub fn new(name: &str, width: u32, height: u32, heights: Vec<f32>) -> Result<Self, Error> {
        if width < 2 || height < 2 {
            return Err(Error::input(
                name,
                format!(
                    "a {width}x{height} height map has no bilinear patch: it needs at least \
                     2x2 samples"
                ),
            ));
        }
        if heights.len() != (width * height) as usize {
            return Err(Error::input(
                name,
                format!(
                    "{} heights given for {width}x{height} samples",
                    heights.len()
                ),
            ));
        }
        if let Some(i) = heights
            .iter()
            .position(|h| !h.is_finite() || !(0.0..=1.0).contains(h))
        {
            return Err(Error::input(
                name,
                format!(
                    "height {} at sample ({}, {}) is not a number in [0, 1]",
                    heights[i],
                    i as u32 % width,
                    i as u32 / width
                ),
            ));
        }
        Ok(HeightMap {
            width,
            height,
            heights,
        })
    }

    /// Any greyscale image (PNG, 8 or 16 bits; a colour image is taken by its luminance),
    /// black = 0, white = 1. `max_side` is the largest side the renderer can hold
    /// (`GL_MAX_TEXTURE_SIZE`); a larger image is refused before it is decoded.
    pub fn load(path: &Path, max_side: u32) -> Result<Self, Error> {
        let (width, height, heights) = load_grey(path, max_side, "height map")?;
        HeightMap::new(&path.display().to_string(), width, height, heights)
    }

    /// Writes the map as an 8-bit greyscale PNG (heights rounded to 1/255).
    pub fn save_png(&self, path: &Path) -> Result<(), Error> {
        let name = path.display().to_string();
        let bytes: Vec<u8> = self
            .heights
            .chunks_exact(self.width as usize)
            .rev()
            .flatten()
            .map(|h| (h * 255.0).round() as u8)
            .collect();
        let image =
            image::GrayImage::from_raw(self.width, self.height, bytes).ok_or_else(|| {
                Error::input(name.clone(), "the map's size does not match its heights")
            })?;
        crate::files::write_image(path, &image.into())
            .map_err(|e| Error::input(name, format!("cannot write the PNG: {e:#}")))
    }

    /// The map this project ships, made by code: four quadrants that test a height-field
    /// tracer in different ways (heights quantised to 1/255, so that the PNG holds it
    /// exactly):
    /// - bottom left, thin walls one sample wide on a low floor (what linear search steps over);
    /// - bottom right, sharp cones (peaks a step can miss);
    /// - top left, smooth domes;
    /// - top right, a fine ripple (many small patches at grazing angles).
    pub fn generated(size: u32) -> HeightMap {
        let n = size as f32;
        let heights = (0..size * size)
            .map(|i| {
                let (x, y) = ((i % size) as f32, (i / size) as f32);
                let (left, bottom) = (x < n / 2.0, y < n / 2.0);
                // Position within the quadrant, 0..1.
                let qx = (x % (n / 2.0)) / (n / 2.0);
                let qy = (y % (n / 2.0)) / (n / 2.0);
                let h: f32 = match (left, bottom) {
                    (true, true) => {
                        let cell = (n / 8.0).max(2.0) as u32;
                        let wall = (i % size) % cell == cell / 2 || (i / size) % cell == cell / 2;
                        if wall {
                            0.85
                        } else {
                            0.1
                        }
                    }
                    (false, true) => {
                        let (cx, cy) = ((qx * 3.0).fract() - 0.5, (qy * 3.0).fract() - 0.5);
                        let d = (cx * cx + cy * cy).sqrt();
                        (1.0 - d / 0.45).max(0.0) * 0.95 + 0.05
                    }
                    (true, false) => {
                        let (cx, cy) = ((qx * 2.0).fract() - 0.5, (qy * 2.0).fract() - 0.5);
                        let d2 = (cx * cx + cy * cy) / 0.2;
                        (1.0 - d2).max(0.0).sqrt() * 0.7 + 0.1
                    }
                    (false, false) => {
                        let r = (qx * qx + qy * qy).sqrt();
                        0.35 + 0.25 * (r * std::f32::consts::TAU * 5.0).cos()
                    }
                };
                (h.clamp(0.0, 1.0) * 255.0).round() / 255.0
            })
            .collect();
        HeightMap::new("the generated height map", size, size, heights)
            .expect("generated heights lie in [0, 1]")
    }

    pub fn width(&self) -> u32 {
        self.width
    }
    pub fn height(&self) -> u32 {
        self.height
    }
    /// Every height, row by row from the bottom.
    pub fn heights(&self) -> &[f32] {
        &self.heights
    }
    /// The height of sample (x, y).
    pub fn at(&self, x: u32, y: u32) -> f32 {
        self.heights[(y * self.width + x) as usize]
    }
    /// The bilinear patches: `(width - 1) x (height - 1)`, patch (i, j) spanning samples
    /// i..=i+1 and j..=j+1.
    pub fn patches(&self) -> (u32, u32) {
        (self.width - 1, self.height - 1)
    }
}

/// The grey levels (0..1, rows from the bottom as GL stores them) of any image (PNG, 8 or 16
/// bits; a colour image by its luminance), and its size; `what` names it in errors ("height
/// map", "image"). A side over `max_side` is refused before the image is decoded.
pub fn load_grey(path: &Path, max_side: u32, what: &str) -> Result<(u32, u32, Vec<f32>), Error> {
    let name = path.display().to_string();
    let reader = image::ImageReader::open(path)
        .map_err(|e| Error::input(&name, format!("cannot open the {what}: {e}")))?
        .with_guessed_format()
        .map_err(|e| Error::input(&name, format!("cannot read the {what}: {e}")))?;
    if reader.format().is_none() {
        return Err(Error::input(
            &name,
            format!("is not an image this program reads (a PNG {what} is expected)"),
        ));
    }
    let (width, height) = reader
        .into_dimensions()
        .map_err(|e| Error::input(&name, format!("is not a readable image: {e}")))?;
    if width > max_side || height > max_side {
        return Err(Error::input(
            &name,
            format!(
                "a {width}x{height} {what} does not fit this renderer: each side must be at \
                 most GL_MAX_TEXTURE_SIZE = {max_side}"
            ),
        ));
    }
    let image = image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .map_err(|e| Error::input(&name, format!("cannot read the {what}: {e}")))?
        .decode()
        .map_err(|e| Error::input(&name, format!("is not a readable image: {e}")))?
        .to_luma32f();
    // Image rows run from the top; GL rows from the bottom.
    let grey = image
        .as_raw()
        .chunks_exact(width as usize)
        .rev()
        .flatten()
        .map(|h| h.clamp(0.0, 1.0))
        .collect();
    Ok((width, height, grey))
}
