//! Insets: an intermediate buffer (any texture the paper code keeps) drawn small in a corner of
//! the frame, or filling it when it is the buffer shown. Float textures are mapped to bytes as
//! `gl::dump` maps them for PNGs, so the inset looks like the dumped file.

use super::{overlay, Canvas};
use crate::gl::dump::{self, DumpRange};
use crate::gl::{GlError, Rect, Texture};

/// Draw `texture` scaled (nearest texel) into `rect` of `canvas`, with `label` under it.
pub fn draw_texture(
    canvas: &Canvas,
    texture: &Texture,
    range: DumpRange,
    rect: Rect,
    label: &str,
) -> Result<(), GlError> {
    let rgba = dump::to_rgba8(texture, range)?;
    draw_rgba(
        canvas,
        &rgba,
        (texture.width(), texture.height()),
        rect,
        label,
    )
}

/// Draw an RGBA image (rows from the bottom) scaled into `rect` of `canvas`, framed in grey,
/// keeping its aspect ratio, with `label` in its bottom-left corner.
pub fn draw_rgba(
    canvas: &Canvas,
    rgba: &[u8],
    (width, height): (u32, u32),
    rect: Rect,
    label: &str,
) -> Result<(), GlError> {
    if rect.w < 3 || rect.h < 3 || width == 0 || height == 0 {
        return Ok(());
    }
    // Fit inside the frame's 1-pixel border, keeping the aspect ratio.
    let (inner_w, inner_h) = (rect.w - 2, rect.h - 2);
    let s = (inner_w as f64 / width as f64).min(inner_h as f64 / height as f64);
    let (w, h) = (
        ((width as f64 * s) as u32).max(1),
        ((height as f64 * s) as u32).max(1),
    );
    let (fw, fh) = (w + 2, h + 2);
    let mut out = vec![0u8; (fw * fh * 4) as usize];
    for y in 0..fh {
        for x in 0..fw {
            let i = ((y * fw + x) * 4) as usize;
            let px = if x == 0 || y == 0 || x == fw - 1 || y == fh - 1 {
                [150, 150, 150, 255]
            } else {
                let sx = ((x - 1) as u64 * width as u64 / w as u64) as u32;
                let sy = ((y - 1) as u64 * height as u64 / h as u64) as u32;
                let j = ((sy * width + sx) * 4) as usize;
                [rgba[j], rgba[j + 1], rgba[j + 2], 255]
            };
            out[i..i + 4].copy_from_slice(&px);
        }
    }
    overlay::draw_image(canvas, &out, fw, fh, (rect.x, rect.y))?;
    if label.is_empty() {
        return Ok(());
    }
    overlay::draw_text(
        canvas,
        &[label.to_string()],
        overlay::Corner::At(rect.x, rect.y),
    )
}

/// `count` inset rectangles along the bottom of `canvas`, each at most a fifth of its width.
pub fn strip(canvas: &Canvas, count: usize) -> Vec<Rect> {
    let side = (canvas.width() / 5)
        .min(canvas.height() / 3)
        .min(if count == 0 {
            0
        } else {
            canvas.width() / count as u32
        });
    (0..count as u32)
        .map(|i| Rect::new(canvas.width() - (i + 1) * side, 0, side, side))
        .collect()
}
