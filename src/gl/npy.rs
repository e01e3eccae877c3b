//! The numbers behind a dumped picture: a float texture as a `.npy` file (numpy's format,
//! float32, the exact values the GPU holds), for people who study the numbers rather than the
//! colours.
//!
//! Layout: shape `[height, width, channels]` (a 1D texture has height 1), rows in GL's order,
//! so row 0 is the texture's bottom row (the PNG's last) and `a[y, x]` is texel `(x, y)`;
//! `matplotlib.pyplot.imshow(a, origin="lower")` shows it the way up the PNG has it.
//! Float formats are written as they are (RGBA32F: 4 channels; R32F, R16F (widened to f32) and
//! DEPTH32F: 1);
//! DEPTH24_STENCIL8 writes its depth as GL reads it, `d / (2^24 - 1)`. Byte and integer
//! formats are not float buffers and have no `.npy`.

use super::{GlError, Texture, TextureFormat};
use std::path::Path;

/// A float texture's shape `[height, width, channels]` and values (rows from the bottom).
pub type Floats = ([usize; 3], Vec<f32>);

/// The shape and values of a float texture, or `None` for a byte or integer format.
pub fn texture_floats(texture: &Texture) -> Result<Option<Floats>, GlError> {
    let (width, height) = (texture.width() as usize, texture.height() as usize);
    let (channels, values) = match texture.format() {
        TextureFormat::Rgba32F
        | TextureFormat::Rg32F
        | TextureFormat::R32F
        | TextureFormat::R16F
        | TextureFormat::Rgba16F
        | TextureFormat::Depth32F => (texture.format().components(), texture.download_f32()?),
        TextureFormat::Depth24Stencil8 => (
            1,
            texture
                .download_u32()?
                .into_iter()
                .map(|v| (v >> 8) as f32 / 16_777_215.0)
                .collect(),
        ),
        TextureFormat::R8
        | TextureFormat::Rgba8
        | TextureFormat::Rgba32Ui
        | TextureFormat::Depth32FStencil8 => return Ok(None),
    };
    Ok(Some(([height, width, channels], values)))
}

/// Writes a float `texture` to `path` as `.npy` (the layout of the module doc) and says
/// whether it did: byte and integer formats write nothing and give `false`.
pub fn texture_npy(texture: &Texture, path: &Path) -> Result<bool, GlError> {
    let Some((shape, values)) = texture_floats(texture)? else {
        return Ok(false);
    };
    crate::files::write_npy(path, &shape, &values)
        .map_err(|e| super::dump::write_error(path, &e))?;
    Ok(true)
}
