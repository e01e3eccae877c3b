//! Synthetic training images for the text detector: lines of random characters of the
//! `font8x8` bitmap font, scaled, rotated and blurred, over varied backgrounds (levels,
//! gradients, smooth noise, ruled lines, blocks) with sensor noise, and the ground truth
//! of every pixel.
//!
//! A pixel is text when it lies in the ink bounding box of a rendered character (so the
//! gaps inside a letter count as text, blank space between words does not). Everything
//! comes from one seeded ChaCha8 generator, so a seed gives the same images everywhere.

use super::labelled::LabelledImage;
use font8x8::legacy::BASIC_LEGACY;
use image::GrayImage;
use rand::Rng;

/// Side of the square synthetic images.
pub const SYNTH_SIZE: u32 = 96;

/// One synthetic image of `SYNTH_SIZE` squared.
pub fn labelled_image(rng: &mut impl Rng) -> LabelledImage {
    let n = SYNTH_SIZE as usize;
    let mut canvas = background(rng, n);
    let mut text = vec![false; n * n];
    let lines = rng.gen_range(0..=3);
    for _ in 0..lines {
        draw_text_line(rng, &mut canvas, &mut text, n);
    }
    if rng.gen_bool(0.5) {
        canvas = box_blur(&canvas, n);
    }
    let sigma = rng.gen_range(0.0..0.04);
    let image = GrayImage::from_fn(SYNTH_SIZE, SYNTH_SIZE, |x, y| {
        let v = canvas[y as usize * n + x as usize] + sigma * gaussian(rng);
        image::Luma([(v.clamp(0.0, 1.0) * 255.0).round() as u8])
    });
    LabelledImage { image, text }
}

/// Paper-like backgrounds: a level, a gradient, smooth blotches, maybe ruled lines
/// (the strongest non-text strokes) and flat blocks with hard edges.
fn background(rng: &mut impl Rng, n: usize) -> Vec<f32> {
    let level = rng.gen_range(0.1..0.9f32);
    let (gx, gy) = (rng.gen_range(-0.3..0.3f32), rng.gen_range(-0.3..0.3f32));
    let (cell, amplitude) = (rng.gen_range(6..32), rng.gen_range(0.0..0.25));
    let blotch = smooth_noise(rng, n, cell, amplitude);
    let mut canvas: Vec<f32> = (0..n * n)
        .map(|p| {
            let (x, y) = ((p % n) as f32 / n as f32, (p / n) as f32 / n as f32);
            level + gx * (x - 0.5) + gy * (y - 0.5) + blotch[p]
        })
        .collect();
    if rng.gen_bool(0.5) {
        ruled_lines(rng, &mut canvas, n);
    }
    for _ in 0..rng.gen_range(0..3) {
        block(rng, &mut canvas, n);
    }
    canvas
}

/// Bilinearly interpolated random values on a grid of `cell` pixels.
fn smooth_noise(rng: &mut impl Rng, n: usize, cell: usize, amplitude: f32) -> Vec<f32> {
    let g = n / cell + 2;
    let grid: Vec<f32> = (0..g * g)
        .map(|_| rng.gen_range(-amplitude..=amplitude))
        .collect();
    (0..n * n)
        .map(|p| {
            let (x, y) = ((p % n) as f32 / cell as f32, (p / n) as f32 / cell as f32);
            let (ix, iy) = (x as usize, y as usize);
            let (fx, fy) = (x.fract(), y.fract());
            let at = |i: usize, j: usize| grid[j * g + i];
            let top = at(ix, iy) * (1.0 - fx) + at(ix + 1, iy) * fx;
            let bottom = at(ix, iy + 1) * (1.0 - fx) + at(ix + 1, iy + 1) * fx;
            top * (1.0 - fy) + bottom * fy
        })
        .collect()
}

/// Parallel straight lines at a random angle and spacing, like ruled paper.
fn ruled_lines(rng: &mut impl Rng, canvas: &mut [f32], n: usize) {
    let angle = rng.gen_range(-0.5..0.5f32);
    let spacing = rng.gen_range(10.0..40.0f32);
    let width = rng.gen_range(0.6..2.0f32);
    let shade = rng.gen_range(0.08..0.4f32) * if rng.gen_bool(0.8) { -1.0 } else { 1.0 };
    let offset = rng.gen_range(0.0..spacing);
    let (s, c) = angle.sin_cos();
    for (p, v) in canvas.iter_mut().enumerate() {
        let (x, y) = ((p % n) as f32, (p / n) as f32);
        let across = (-x * s + y * c + offset).rem_euclid(spacing);
        if across < width {
            *v += shade;
        }
    }
}

/// A flat rectangle of another grey: hard straight edges that are not text.
fn block(rng: &mut impl Rng, canvas: &mut [f32], n: usize) {
    let (x0, y0) = (rng.gen_range(0..n), rng.gen_range(0..n));
    let (w, h) = (rng.gen_range(8..n), rng.gen_range(8..n));
    let level = rng.gen_range(0.0..1.0f32);
    for y in y0..(y0 + h).min(n) {
        for x in x0..(x0 + w).min(n) {
            canvas[y * n + x] = level;
        }
    }
}

/// Random printable characters (and spaces) along a rotated baseline, scaled by 1.5-4.5
/// with nearest-pixel sampling so strokes are 1-9 pixels wide.
fn draw_text_line(rng: &mut impl Rng, canvas: &mut [f32], text: &mut [bool], n: usize) {
    let scale = rng.gen_range(1.5..4.5f32);
    let angle = rng.gen_range(-0.4..0.4f32);
    let length = rng.gen_range(2..14usize);
    let chars: Vec<u8> = (0..length)
        .map(|_| {
            if rng.gen_bool(0.12) {
                b' '
            } else {
                rng.gen_range(33..127u8)
            }
        })
        .collect();
    let origin = (
        rng.gen_range(-20.0..n as f32 - 10.0),
        rng.gen_range(-5.0..n as f32 - 10.0),
    );
    let contrast = rng.gen_range(0.2..0.8f32) * if rng.gen_bool(0.75) { -1.0 } else { 1.0 };
    let (s, c) = angle.sin_cos();
    let boxes: Vec<Option<[u32; 4]>> = chars.iter().map(|&ch| ink_box(ch)).collect();
    for (p, value) in canvas.iter_mut().enumerate() {
        let (dx, dy) = ((p % n) as f32 - origin.0, (p / n) as f32 - origin.1);
        let (u, v) = ((dx * c + dy * s) / scale, (-dx * s + dy * c) / scale);
        if !(0.0..8.0 * length as f32).contains(&u) || !(0.0..8.0).contains(&v) {
            continue;
        }
        let (cell, gx, gy) = ((u / 8.0) as usize, (u as u32) % 8, v as u32);
        let Some([x0, y0, x1, y1]) = boxes[cell] else {
            continue;
        };
        if (x0..=x1).contains(&gx) && (y0..=y1).contains(&gy) {
            text[p] = true;
        }
        if glyph_bit(chars[cell], gx, gy) {
            *value += contrast;
        }
    }
}

/// The font's pixel (x, y) of a character: rows are bytes, bit 0 is the leftmost pixel.
fn glyph_bit(ch: u8, x: u32, y: u32) -> bool {
    BASIC_LEGACY[usize::from(ch)][y as usize] >> x & 1 == 1
}

/// [x0, y0, x1, y1] of a character's ink, None for a blank glyph.
fn ink_box(ch: u8) -> Option<[u32; 4]> {
    let ink: Vec<(u32, u32)> = (0..8)
        .flat_map(|y| (0..8).map(move |x| (x, y)))
        .filter(|&(x, y)| glyph_bit(ch, x, y))
        .collect();
    let x0 = ink.iter().map(|p| p.0).min()?;
    let x1 = ink.iter().map(|p| p.0).max()?;
    let y0 = ink.iter().map(|p| p.1).min()?;
    let y1 = ink.iter().map(|p| p.1).max()?;
    Some([x0, y0, x1, y1])
}

/// 3 x 3 box blur (edges clamped): the softness of a camera.
fn box_blur(canvas: &[f32], n: usize) -> Vec<f32> {
    (0..n * n)
        .map(|p| {
            let (x, y) = ((p % n) as i64, (p / n) as i64);
            let mut sum = 0.0;
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let sx = (x + dx).clamp(0, n as i64 - 1) as usize;
                    let sy = (y + dy).clamp(0, n as i64 - 1) as usize;
                    sum += canvas[sy * n + sx];
                }
            }
            sum / 9.0
        })
        .collect()
}

/// A standard normal sample (Box-Muller), from the seeded generator.
fn gaussian(rng: &mut impl Rng) -> f32 {
    let u1: f32 = rng.gen_range(f32::EPSILON..1.0);
    let u2: f32 = rng.gen_range(0.0..1.0);
    (-2.0 * u1.ln()).sqrt() * (std::f32::consts::TAU * u2).cos()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn a_seed_gives_the_same_image() {
        let a = labelled_image(&mut ChaCha8Rng::seed_from_u64(3));
        let b = labelled_image(&mut ChaCha8Rng::seed_from_u64(3));
        assert_eq!(a.image, b.image);
        assert_eq!(a.text, b.text);
    }

    #[test]
    fn glyphs_match_the_font() {
        // 'T' is a bar across the top and a stem; '.' has a small box; ' ' has none
        assert!(glyph_bit(b'T', 0, 0) && glyph_bit(b'T', 2, 3) && !glyph_bit(b'T', 0, 3));
        assert_eq!(ink_box(b' '), None);
        let [x0, y0, x1, y1] = ink_box(b'.').unwrap();
        assert!(x1 - x0 <= 2 && y1 - y0 <= 2);
    }

    #[test]
    fn text_pixels_appear_in_a_fair_share_of_images() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let fractions: Vec<f64> = (0..20)
            .map(|_| {
                let img = labelled_image(&mut rng);
                img.text.iter().filter(|&&t| t).count() as f64 / img.text.len() as f64
            })
            .collect();
        let with_text = fractions.iter().filter(|&&f| f > 0.01).count();
        assert!((5..20).contains(&with_text), "{fractions:?}");
        assert!(fractions.iter().all(|&f| f < 0.9));
    }
}
