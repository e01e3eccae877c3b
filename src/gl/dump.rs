//! Look at it: any texture or framebuffer attachment as a PNG (the tutorial's first debugging
//! tip, and how the report shows intermediate buffers).
//!
//! Mapping, documented once: byte formats are written as they are. Float formats are mapped
//! linearly per colour channel from `[lo, hi]` to `[0, 255]`, where [`DumpRange::Auto`] takes
//! `lo` and `hi` as that channel's smallest and largest finite value (a constant channel shows
//! as mid-grey) and [`DumpRange::Fixed`] takes the given pair for every channel. Single-channel
//! textures (R32F, depth) become grey. Alpha is written opaque, since data in alpha would
//! otherwise hide the picture. NaN and infinite texels are magenta. Row 0 (GL's bottom) is
//! written at the bottom of the image.

use super::{GlError, Texture, TextureFormat};
use std::path::Path;

/// How float values map to bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DumpRange {
    /// Each channel from its own finite minimum to maximum.
    Auto,
    /// Every channel from `lo` to `hi`.
    Fixed(f32, f32),
}

/// Write `texture` to `path` as PNG.
pub fn texture_png(texture: &Texture, path: &Path, range: DumpRange) -> Result<(), GlError> {
    let rgba = to_rgba8(texture, range)?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| io_error(path, e))?;
    }
    rgba_png(&rgba, (texture.width(), texture.height()), path)
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
    crate::files::write_png(path, &flipped, width, height)
        .map_err(|e| io_error(path, format!("{e:#}")))
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
        TextureFormat::Rgba32F => map_floats(&texture.download_f32()?, 4, range),
        TextureFormat::R32F | TextureFormat::Depth32F => {
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

/// Map `channels`-component floats to RGBA bytes.
pub fn map_floats(values: &[f32], channels: usize, range: DumpRange) -> Vec<u8> {
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
                return [255, 0, 255, 255];
            }
            if channels == 1 {
                let g = byte(texel[0], bounds[0]);
                [g, g, g, 255]
            } else {
                let mut out = [0, 0, 0, 255];
                for c in 0..colour_channels {
                    out[c] = byte(texel[c], bounds[c]);
                }
                out
            }
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
        let grey = map_floats(&[0.5, 0.25], 1, DumpRange::Fixed(0.0, 1.0));
        assert_eq!(grey, vec![128, 128, 128, 255, 64, 64, 64, 255]);
    }
}
