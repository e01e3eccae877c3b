//! Look at it: any texture or framebuffer attachment as a PNG (the tutorial's first debugging
//! tip, and how the report and the viewer show intermediate buffers).
//!
//! # The mapping of float buffers, the same in the report, the viewer and every dump
//!
//! - **One channel, one picture.** A float buffer's channels are separate quantities (a peel's
//!   `rx, ry, rz, V`), so each is drawn as its own panel ([`super::picture`]); a channel is
//!   never a colour component, which would mix them into hues that mean nothing.
//! - **Zero is a fixed neutral colour** (dark grey, [`super::picture::NEUTRAL`]) in every
//!   picture: most buffers are mostly zero, and an empty texel must look the same in all.
//! - **Sequential for non-negative data, diverging for signed data.** Non-negative values run
//!   from the neutral grey through dark red and orange to pale yellow; negative values, when
//!   there are any, run from the same grey through dark blue to pale cyan, both halves scaled
//!   by the largest magnitude. Lightness rises with the magnitude in both halves (the picture
//!   reads in grey and for colour-blind readers), hue tells the sign, and the sequential map is
//!   exactly the positive half of the diverging one, so a value has one colour whatever else
//!   shares its picture.
//! - **One scale per set of related pictures** ([`super::picture::Scale::of`] over all of them:
//!   all peels of a body, all levels of a pyramid), always containing zero; a lone picture is a
//!   set of one.
//! - **NaN and infinite texels are magenta**, a colour neither half of the map uses.
//! - **Every picture carries a colour key** with its numeric range (and zero when the map is
//!   diverging), and its title; numbers never print as "-0".
//! - **Small targets are enlarged by whole factors, nearest texel** (no smoothing: a texel is
//!   a block of equal pixels); a strip much longer one way than the picture is stretched each
//!   way so that it is not drawn as a line. Titles wrap inside their panel and key labels that
//!   would touch are left out, so labels never overlap or get cut.
//!
//! Images are not data: byte formats, and float targets that hold colours (a rendered frame),
//! are written as they are, each channel from `[lo, hi]` ([`DumpRange`]) to `[0, 255]`.
//! Single-channel float textures (R32F, depth) go through the colour map above at their own
//! size ([`map_floats`]); [`texture_picture_png`] draws any float texture as panels with keys.
//! Alpha is written opaque. Row 0 (GL's bottom) is written at the bottom of the image.

use super::drawn::{self, Drawn};
use super::picture::{self, Panel, Scale};
use super::{GlError, Texture, TextureFormat};
use std::path::Path;

/// How float values map to bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DumpRange {
    /// The data's own range: for one channel the [`Scale::of`] its values; for colours each
    /// channel from its own finite minimum to maximum.
    Auto,
    /// From `lo` to `hi` (one channel: the colour map's scale, widened to contain zero).
    Fixed(f32, f32),
}

impl DumpRange {
    /// The colour map's scale of one channel's `values`.
    pub fn scale(self, values: &[f32]) -> Scale {
        match self {
            DumpRange::Auto => Scale::of([values]),
            DumpRange::Fixed(lo, hi) => Scale::fixed(lo, hi),
        }
    }
}

/// Write a float `texture` to `path` as a picture of `size` pixels: one panel per channel
/// (named by `channels`, which also says how many are drawn), each with its own scale from
/// `range` and its colour key, as the module doc says.
pub fn texture_picture_png(
    texture: &Texture,
    channels: &[&str],
    range: DumpRange,
    size: (u32, u32),
    path: &Path,
) -> Result<(), GlError> {
    let n = texture.format().components();
    let values = texture.download_f32()?;
    let panels: Vec<Panel> = channels
        .iter()
        .enumerate()
        .take(n)
        .map(|(c, name)| {
            let dims = (texture.width(), texture.height());
            let panel = Panel::channel(*name, &values, n, c, dims, Scale::fixed(0.0, 0.0));
            let scale = range.scale(&panel.values);
            Panel { scale, ..panel }
        })
        .collect();
    picture_png(&panels, size, path)
}

/// Write `panels` as one picture of at least `size` pixels ([`picture::picture`]), grown
/// where a panel would otherwise drop texels ([`picture::whole_texel_size`]); what it shows
/// is recorded ([`drawn::record`]).
pub fn picture_png(panels: &[Panel], size: (u32, u32), path: &Path) -> Result<(), GlError> {
    let size = picture::whole_texel_size(panels, size);
    let (image, _, shown) = picture::picture_drawn(panels, size);
    crate::files::write_image(path, &image::DynamicImage::ImageRgba8(image))
        .map_err(|e| write_error(path, &e))?;
    drawn::record(path, Drawn::Picture(shown));
    Ok(())
}

/// Write rendered `frames` (titles, images top row first) as one picture
/// ([`picture::frames_picture`]) with their colour `legend`, and record what it shows.
pub fn frames_png(
    frames: &[(String, image::RgbaImage)],
    columns: usize,
    scale: u32,
    legend: &[([u8; 4], String)],
    path: &Path,
) -> Result<(), GlError> {
    let (image, shown) = picture::frames_picture(frames, columns, scale, legend);
    crate::files::write_image(path, &image::DynamicImage::ImageRgba8(image))
        .map_err(|e| write_error(path, &e))?;
    drawn::record(path, Drawn::Frames(shown));
    Ok(())
}

/// Write `texture` to `path` as PNG.
pub fn texture_png(texture: &Texture, path: &Path, range: DumpRange) -> Result<(), GlError> {
    let rgba = to_rgba8(texture, range)?;
    // The folder is made by the write (`files::write`), which names a part that is a file.
    rgba_png(&rgba, (texture.width(), texture.height()), path)?;
    let what = format!("a {:?} texture", texture.format());
    let shown = match texture.format() {
        TextureFormat::Rgba8 | TextureFormat::R8 => Drawn::Image { what },
        _ => Drawn::BareFloats { what },
    };
    drawn::record(path, shown);
    Ok(())
}

/// Write `width x height` RGBA bytes, rows from the bottom as GL reads them, to `path` as
/// PNG (top row first, as images are stored).
pub fn rgba_png(rgba: &[u8], (width, height): (u32, u32), path: &Path) -> Result<(), GlError> {
    let flipped: Vec<u8> = rgba
        .chunks_exact(width as usize * 4)
        .rev()
        .flatten()
        .copied()
        .collect();
    crate::files::write_png(path, &flipped, width, height).map_err(|e| write_error(path, &e))?;
    let what = format!("a {width}x{height} RGBA frame");
    drawn::record(path, Drawn::Image { what });
    Ok(())
}

/// A failed write of `path` as [`GlError::Io`] (which says "writing PATH" itself): every
/// cause of `e`, the disk's own reason included, without saying the path twice.
pub(crate) fn write_error(path: &Path, e: &anyhow::Error) -> GlError {
    let text = crate::files::error_text(e);
    let prefix = format!("writing {}: ", path.display());
    let message = text.strip_prefix(&prefix).unwrap_or(&text).to_string();
    io_error(path, message)
}

fn io_error(path: &Path, e: impl std::fmt::Display) -> GlError {
    GlError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// The texture as RGBA bytes, row by row from the bottom, mapped as the module doc says.
pub fn to_rgba8(texture: &Texture, range: DumpRange) -> Result<Vec<u8>, GlError> {
    Ok(match texture.format() {
        TextureFormat::Rgba8 => texture.download_u8()?,
        TextureFormat::R8 => texture
            .download_u8()?
            .into_iter()
            .flat_map(|v| [v, v, v, 255])
            .collect(),
        TextureFormat::Rgba32F | TextureFormat::Rgba16F => {
            map_floats(&texture.download_f32()?, 4, range)
        }
        TextureFormat::Rg32F => {
            let rg = texture.download_f32()?;
            let rgba: Vec<f32> = rg.chunks(2).flat_map(|c| [c[0], c[1], 0.0, 1.0]).collect();
            map_floats(&rgba, 4, range)
        }
        TextureFormat::R32F | TextureFormat::R16F | TextureFormat::Depth32F => {
            map_floats(&texture.download_f32()?, 1, range)
        }
        TextureFormat::Depth24Stencil8 => {
            let depth: Vec<f32> = texture
                .download_u32()?
                .into_iter()
                .map(|v| (v >> 8) as f32 / 16_777_215.0)
                .collect();
            map_floats(&depth, 1, range)
        }
        TextureFormat::Depth32FStencil8 => {
            return Err(GlError::Invalid(
                "dumping a DEPTH32F_STENCIL8 texture is not supported; dump a colour target".into(),
            ))
        }
        TextureFormat::Rgba32Ui => {
            let values: Vec<f32> = texture
                .download_u32()?
                .into_iter()
                .map(|v| v as f32)
                .collect();
            map_floats(&values, 4, range)
        }
    })
}

/// Map `channels`-component floats to RGBA bytes: one channel through the colour map (the
/// module doc), more as colours (each channel to red, green, blue).
pub fn map_floats(values: &[f32], channels: usize, range: DumpRange) -> Vec<u8> {
    if channels == 1 {
        let scale = range.scale(values);
        return values.iter().flat_map(|&v| scale.colour(v)).collect();
    }
    let colour_channels = channels.min(3);
    let bounds: Vec<(f32, f32)> = (0..colour_channels)
        .map(|c| match range {
            DumpRange::Fixed(lo, hi) => (lo, hi),
            DumpRange::Auto => values
                .iter()
                .skip(c)
                .step_by(channels)
                .filter(|v| v.is_finite())
                .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
                    (lo.min(v), hi.max(v))
                }),
        })
        .collect();
    let byte = |v: f32, (lo, hi): (f32, f32)| -> u8 {
        if hi > lo {
            ((v - lo) / (hi - lo) * 255.0).round().clamp(0.0, 255.0) as u8
        } else {
            128
        }
    };
    values
        .chunks_exact(channels)
        .flat_map(|texel| {
            if texel[..colour_channels].iter().any(|v| !v.is_finite()) {
                return picture::NOT_FINITE;
            }
            let mut out = [0, 0, 0, 255];
            for c in 0..colour_channels {
                out[c] = byte(texel[c], bounds[c]);
            }
            out
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_map_per_channel_and_flag_nan() {
        let values = [
            0.0,
            10.0,
            -1.0,
            7.0,
            1.0,
            20.0,
            1.0,
            7.0,
            f32::NAN,
            10.0,
            -1.0,
            0.0,
        ];
        let bytes = map_floats(&values, 4, DumpRange::Auto);
        assert_eq!(&bytes[0..4], &[0, 0, 0, 255]);
        assert_eq!(&bytes[4..8], &[255, 255, 255, 255]);
        assert_eq!(&bytes[8..12], &[255, 0, 255, 255]);
        let one = map_floats(&[0.0, 1.0, f32::INFINITY], 1, DumpRange::Fixed(0.0, 2.0));
        let scale = Scale::fixed(0.0, 2.0);
        assert_eq!(&one[0..4], &picture::NEUTRAL);
        assert_eq!(&one[4..8], &scale.colour(1.0));
        assert_eq!(&one[8..12], &picture::NOT_FINITE);
    }
}
