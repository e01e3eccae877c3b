//! Text over the frame: the demo's numbers, the help, drawn with the 8x8 bitmap font the crate
//! already has (font8x8), as an RGBA image blended over the canvas.

use super::Canvas;
use crate::gl::{Blend, DrawState, GlError, Rect, Texture, TextureFormat};
use font8x8::legacy::BASIC_LEGACY;

/// Where a block of text goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Corner {
    TopLeft,
    BottomLeft,
    Centre,
    /// The bottom-left pixel of the box.
    At(u32, u32),
    /// The top-left pixel of the box (rows from the bottom), moved inside the canvas.
    Probe(u32, u32),
}

const TEXT: [u8; 4] = [240, 240, 240, 255];
const BACKDROP: [u8; 4] = [0, 0, 0, 170];
const MARGIN: u32 = 4;

/// Draw `lines` in a dark box at `corner` of `canvas`: 8x8 glyphs, doubled on canvases at least
/// 640 pixels wide. Text that would not fit the canvas is drawn in single-size glyphs, then
/// wrapped at spaces, so no line is cut; lines still below the canvas's bottom are left out
/// (the canvas holds fewer than them). Characters outside ASCII show as '?'.
pub fn draw_text(canvas: &Canvas, lines: &[String], corner: Corner) -> Result<(), GlError> {
    if lines.is_empty() {
        return Ok(());
    }
    let (scale, lines) = fit(lines, canvas.width(), canvas.height());
    let glyph = 8 * scale;
    let columns = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0) as u32;
    let width = (columns * glyph + 2 * MARGIN).min(canvas.width());
    let height = (lines.len() as u32 * (glyph + 2 * scale) + 2 * MARGIN).min(canvas.height());
    let image = text_image(&lines, scale, width, height);
    let (x, y) = match corner {
        Corner::TopLeft => (0, canvas.height() - height),
        Corner::BottomLeft => (0, 0),
        Corner::Centre => ((canvas.width() - width) / 2, (canvas.height() - height) / 2),
        Corner::At(x, y) => (
            x.min(canvas.width() - width),
            y.min(canvas.height() - height),
        ),
        Corner::Probe(x, top) => (
            x.min(canvas.width() - width),
            top.saturating_sub(height).min(canvas.height() - height),
        ),
    };
    draw_image(canvas, &image, width, height, (x, y))
}

/// The height in pixels of `lines` drawn by [`draw_text`] on a `width x height` canvas.
pub fn text_height(lines: &[String], width: u32, height: u32) -> u32 {
    let (scale, fitted) = fit(lines, width, height);
    (fitted.len() as u32 * 10 * scale + 2 * MARGIN).min(height)
}

/// The glyph scale and the lines as they fit a `width x height` canvas: doubled glyphs where
/// the canvas is wide enough for them and they fit, else single ones; lines longer than the
/// canvas wrapped; lines past its height left out.
pub fn fit(lines: &[String], width: u32, height: u32) -> (u32, Vec<String>) {
    let wrapped = |scale: u32| -> Vec<String> {
        let columns = (width.saturating_sub(2 * MARGIN) / (8 * scale)).max(1) as usize;
        lines
            .iter()
            .flat_map(|l| crate::gl::picture::wrap(l, columns))
            .collect()
    };
    // Doubled glyphs where the canvas is wide and the wrapped text takes at most half of it.
    let doubled = wrapped(2);
    let (scale, mut out) = if width >= 640 && doubled.len() as u32 * 20 + 2 * MARGIN <= height / 2 {
        (2, doubled)
    } else {
        (1, wrapped(1))
    };
    let rows = (height.saturating_sub(2 * MARGIN) / (10 * scale)).max(1) as usize;
    out.truncate(rows);
    (scale, out)
}

/// How many characters of text fit across a canvas `width` pixels wide (for wrapping).
pub fn columns(width: u32) -> usize {
    let scale = if width >= 640 { 2 } else { 1 };
    (width.saturating_sub(2 * MARGIN) / (8 * scale)).max(1) as usize
}

/// Blend an RGBA image (rows from the bottom) over `canvas` with its bottom-left pixel at `at`.
pub fn draw_image(
    canvas: &Canvas,
    rgba: &[u8],
    width: u32,
    height: u32,
    at: (u32, u32),
) -> Result<(), GlError> {
    let ctx = canvas.context();
    let texture = Texture::new_2d(ctx, width, height, TextureFormat::Rgba8)?;
    texture.upload_u8(rgba)?;
    let mut pass = canvas
        .target()
        .pass(canvas.overlay_program(), "viewer overlay")?;
    pass.state(DrawState {
        blend: Some(Blend::Alpha),
        ..DrawState::default()
    })
    .texture("u_image", &texture)
    .uniform("u_origin", glam::IVec2::new(at.0 as i32, at.1 as i32));
    pass.draw_rect(Rect::new(at.0, at.1, width, height))
}

/// The text as an RGBA image of `width x height`, rows from the bottom.
fn text_image(lines: &[String], scale: u32, width: u32, height: u32) -> Vec<u8> {
    let mut top_down = vec![0u8; (width * height * 4) as usize];
    for px in top_down.chunks_exact_mut(4) {
        px.copy_from_slice(&BACKDROP);
    }
    let line_height = 8 * scale + 2 * scale;
    for (row, line) in lines.iter().enumerate() {
        for (col, c) in line.chars().enumerate() {
            let code = if c.is_ascii() {
                c as usize
            } else {
                '?' as usize
            };
            let bitmap = BASIC_LEGACY[code];
            for (gy, bits) in bitmap.iter().enumerate() {
                for gx in 0..8 {
                    if bits & (1 << gx) == 0 {
                        continue;
                    }
                    for sy in 0..scale {
                        for sx in 0..scale {
                            let x = MARGIN + col as u32 * 8 * scale + gx * scale + sx;
                            let y = MARGIN + row as u32 * line_height + gy as u32 * scale + sy;
                            if x < width && y < height {
                                let i = ((y * width + x) * 4) as usize;
                                top_down[i..i + 4].copy_from_slice(&TEXT);
                            }
                        }
                    }
                }
            }
        }
    }
    let row = width as usize * 4;
    top_down
        .chunks_exact(row)
        .rev()
        .flatten()
        .copied()
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::gl::picture::wrap;

    #[test]
    fn wrapped_lines_fit_and_keep_every_character() {
        let text =
            "glsl/gl/reduce.frag:6: error: syntax error, unexpected ';' averyveryverylongword";
        for columns in [1, 7, 20, 200] {
            let lines = wrap(text, columns);
            assert!(
                lines.iter().all(|l| l.chars().count() <= columns),
                "{lines:?}"
            );
            let joined: String = lines.concat().split_whitespace().collect();
            let want: String = text.split_whitespace().collect();
            assert_eq!(joined, want);
        }
        assert_eq!(wrap("a b c", 3), ["a b", "c"]);
    }
}
