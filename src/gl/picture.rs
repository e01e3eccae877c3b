//! Pictures of float buffers as [`super::dump`] states the mapping: the colour map ([`Scale`]),
//! panels with a colour key and their title ([`picture`]), nearest-texel enlargement, and the
//! number format of every label ([`number`], [`fixed`]: never "-0"). CPU only: the same
//! pictures go into PNG files and, through the viewer, onto the screen.

use super::drawn::{FrameDrawn, FramesDrawn, PanelDrawn, PictureDrawn, MAX_TITLE_LINES};
use font8x8::legacy::BASIC_LEGACY;
use image::{Rgba, RgbaImage};

/// How every picture of a float buffer maps values to colours, in a reader's words (the
/// report and the guide print it; [`super::dump`] states it in full).
pub const MAPPING_IN_WORDS: &str = "Pictures of float buffers: each channel is its own panel; \
    zero is always the same dark grey; non-negative values run from that grey through dark red \
    and orange to pale yellow, negative ones through dark blue to pale cyan; related pictures \
    (all peels of a body, all levels of a pyramid) share one scale, which always contains zero; \
    the colour key under each panel gives its range; NaN and infinite texels are magenta; small \
    buffers are enlarged texel by texel, with no smoothing.";

/// The colour of zero in every picture: a dark neutral grey, the background a buffer starts
/// from (most buffers are mostly zero), distinct from the picture's black margin.
pub const NEUTRAL: [u8; 4] = [48, 48, 48, 255];
/// NaN and infinite texels: a colour neither half of the map uses.
pub const NOT_FINITE: [u8; 4] = [255, 0, 255, 255];
/// Around and between panels.
const BACKGROUND: [u8; 4] = [8, 8, 10, 255];
const FRAME: [u8; 4] = [140, 140, 140, 255];
const TEXT: [u8; 4] = [235, 235, 235, 255];

/// Positive values, from zero to the largest magnitude: neutral, dark red, orange, pale yellow
/// (lightness rises with the value, so the picture reads in grey too).
const POSITIVE: [[f32; 3]; 4] = [
    [48.0, 48.0, 48.0],
    [150.0, 30.0, 20.0],
    [240.0, 130.0, 20.0],
    [255.0, 245.0, 170.0],
];
/// Negative values, from zero to the largest magnitude: neutral, dark blue, blue, pale cyan.
const NEGATIVE: [[f32; 3]; 4] = [
    [48.0, 48.0, 48.0],
    [25.0, 55.0, 160.0],
    [40.0, 145.0, 235.0],
    [175.0, 240.0, 255.0],
];

/// The numeric range one colour map covers, shared by a set of related pictures. It always
/// contains zero (zero is the neutral colour); `lo < 0` makes the map diverging.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scale {
    pub lo: f32,
    pub hi: f32,
}

impl Scale {
    /// The scale of every finite value of every slice (one set of related pictures).
    pub fn of<'a>(sets: impl IntoIterator<Item = &'a [f32]>) -> Scale {
        let mut scale = Scale { lo: 0.0, hi: 0.0 };
        for set in sets {
            for &v in set.iter().filter(|v| v.is_finite()) {
                scale.lo = scale.lo.min(v);
                scale.hi = scale.hi.max(v);
            }
        }
        scale
    }

    /// A given range, widened to contain zero.
    pub fn fixed(lo: f32, hi: f32) -> Scale {
        Scale {
            lo: lo.min(0.0),
            hi: hi.max(0.0),
        }
    }

    /// Whether the data has negative values (a diverging map).
    pub fn is_signed(&self) -> bool {
        self.lo < 0.0
    }

    /// The largest magnitude: both halves of a diverging map are scaled by it, so that equal
    /// magnitudes have equal lightness.
    fn magnitude(&self) -> f32 {
        (-self.lo).max(self.hi)
    }

    /// The colour of `v`.
    pub fn colour(&self, v: f32) -> [u8; 4] {
        if !v.is_finite() {
            return NOT_FINITE;
        }
        let m = self.magnitude();
        if v == 0.0 || m <= 0.0 {
            return NEUTRAL;
        }
        let t = (v.abs() / m).clamp(0.0, 1.0);
        let stops = if v > 0.0 { &POSITIVE } else { &NEGATIVE };
        let x = t * (stops.len() - 1) as f32;
        let i = (x.floor() as usize).min(stops.len() - 2);
        let f = x - i as f32;
        let mut out = [0, 0, 0, 255];
        for c in 0..3 {
            let value = stops[i][c] + (stops[i + 1][c] - stops[i][c]) * f;
            out[c] = value.round().clamp(0.0, 255.0) as u8;
        }
        out
    }
}

/// `v` with at most 4 significant digits (exponent form outside 1e-3..1e5), "0" for both
/// zeros: the numbers of keys and probes.
pub fn number(v: f64) -> String {
    if !v.is_finite() {
        return if v.is_nan() {
            "NaN"
        } else if v > 0.0 {
            "inf"
        } else {
            "-inf"
        }
        .into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    let s = if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{v:.2e}")
    };
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        "0".into()
    } else {
        s
    }
}

/// `v` with `decimals` decimals, without the sign of a value that rounds to zero ("0.000",
/// never "-0.000").
pub fn fixed(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

/// One channel of a buffer drawn as one panel: values row by row from the bottom (as GL reads
/// them), `width x height`.
#[derive(Clone, Debug)]
pub struct Panel {
    pub title: String,
    pub values: Vec<f32>,
    pub width: u32,
    pub height: u32,
    pub scale: Scale,
}

impl Panel {
    /// Channel `channel` of `channels`-component texels.
    pub fn channel(
        title: impl Into<String>,
        texels: &[f32],
        channels: usize,
        channel: usize,
        (width, height): (u32, u32),
        scale: Scale,
    ) -> Panel {
        Panel {
            title: title.into(),
            values: texels
                .iter()
                .skip(channel)
                .step_by(channels)
                .copied()
                .collect(),
            width,
            height,
            scale,
        }
    }

    /// The texel at (`x`, `y`), `y` from the bottom.
    pub fn at(&self, x: u32, y: u32) -> f32 {
        self.values[(y * self.width + x) as usize]
    }
}

/// Where a panel's texels landed in a picture: the image area, top-left origin, in picture
/// pixels; the texel under a picture pixel is found from it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Placement {
    pub x: u32,
    pub y: u32,
    pub w: u32,
    pub h: u32,
    pub texels: (u32, u32),
}

impl Placement {
    /// The texel (x, y from the bottom) under picture pixel (`px`, `py`) (top-left origin).
    pub fn texel(&self, px: u32, py: u32) -> Option<(u32, u32)> {
        if px < self.x || py < self.y || px >= self.x + self.w || py >= self.y + self.h {
            return None;
        }
        let tx = (px - self.x) as u64 * self.texels.0 as u64 / self.w as u64;
        let from_top = (py - self.y) as u64 * self.texels.1 as u64 / self.h as u64;
        Some((tx as u32, self.texels.1 - 1 - from_top as u32))
    }
}

/// The glyph size (pixels) of text in a picture of `width` pixels: 16 from 640 up, else 8.
pub fn glyph_for(width: u32) -> u32 {
    if width >= 640 {
        16
    } else {
        8
    }
}

/// The width from which a picture's text is 16 pixels high ([`glyph_for`]).
pub const LEGIBLE_WIDTH: u32 = 640;

/// `size` grown by the smallest whole factor that makes it at least [`LEGIBLE_WIDTH`] wide:
/// shown at its own size, the picture's titles and key numbers are then 16 pixels high, and
/// texels enlarged by a whole factor stay whole.
pub fn legible_size((width, height): (u32, u32)) -> (u32, u32) {
    let k = LEGIBLE_WIDTH.div_ceil(width.max(1));
    (width * k, height * k)
}

const MARGIN: u32 = 4;
const BAR: u32 = 8;

/// `panels` laid out in a grid that fits `width x height` (the columns chosen to give the
/// panels the largest texels, among the layouts whose titles wrap at most
/// [`MAX_TITLE_LINES`] lines), each with its title above and its colour key (the scale's
/// range, and zero for a diverging map) below; texels enlarged by whole factors, nearest
/// texel, when there is room. The picture, and where each panel's texels are.
pub fn picture(panels: &[Panel], size: (u32, u32)) -> (RgbaImage, Vec<Placement>) {
    let (image, placements, _) = picture_drawn(panels, size);
    (image, placements)
}

/// [`picture`], and what it shows: each panel's title, key and texel scale.
pub fn picture_drawn(
    panels: &[Panel],
    (width, height): (u32, u32),
) -> (RgbaImage, Vec<Placement>, PictureDrawn) {
    let mut image = RgbaImage::from_pixel(width.max(1), height.max(1), Rgba(BACKGROUND));
    let mut placements = Vec::new();
    if panels.is_empty() {
        return (image, placements, PictureDrawn::default());
    }
    let glyph = glyph_for(width);
    let columns = layout(panels, (width, height), glyph).1;
    let rows = (panels.len() as u32).div_ceil(columns);
    let (cw, ch) = (width / columns, height / rows);
    let mut drawn = PictureDrawn {
        text_px: glyph,
        ..PictureDrawn::default()
    };
    for (k, panel) in panels.iter().enumerate() {
        let (col, row) = (k as u32 % columns, k as u32 / columns);
        let (placement, key_glyph) =
            draw_panel(&mut image, panels, k, (col * cw, row * ch), (cw, ch), glyph);
        drawn.text_px = drawn.text_px.min(key_glyph);
        let filled = panel.values.iter().filter(|v| **v != 0.0).count();
        drawn.panels.push(PanelDrawn {
            title: panel.title.clone(),
            title_lines: title_lines(panel, cw, glyph).len(),
            key: key_ends(panel.scale),
            texels: placement.texels,
            pixels: (placement.w, placement.h),
            filled: filled as f32 / panel.values.len().max(1) as f32,
        });
        placements.push(placement);
    }
    (image, placements, drawn)
}

/// The best layout of `panels` in `width x height`: the smallest enlargement of a panel and
/// the columns. Layouts whose titles wrap more than [`MAX_TITLE_LINES`] lines are taken only
/// when every layout's do.
fn layout(panels: &[Panel], (width, height): (u32, u32), glyph: u32) -> (f64, u32) {
    let n = panels.len() as u32;
    let mut best: Option<(bool, f64, u32)> = None;
    for columns in 1..=n {
        let rows = n.div_ceil(columns);
        let (cw, ch) = (width / columns, height / rows);
        let (aw, ah) = image_area(panels, cw, ch, glyph);
        let s = panels
            .iter()
            .map(|p| (aw as f64 / p.width as f64).min(ah as f64 / p.height as f64))
            .fold(f64::INFINITY, f64::min);
        let short = panels
            .iter()
            .all(|p| title_lines(p, cw, glyph).len() <= MAX_TITLE_LINES);
        if best.is_none_or(|(b_short, b, _)| (short, s) > (b_short, b)) {
            best = Some((short, s, columns));
        }
    }
    best.map_or((1.0, 1), |(_, s, c)| (s, c))
}

/// The smallest size at least `size` (grown in proportion) at which every panel gets at
/// least one pixel per texel, so that no texel is dropped; at most 8 times `size`.
pub fn whole_texel_size(panels: &[Panel], size: (u32, u32)) -> (u32, u32) {
    let mut grown = size;
    for _ in 0..8 {
        if panels.is_empty() || layout(panels, grown, glyph_for(grown.0)).0 >= 1.0 {
            return grown;
        }
        grown = (grown.0 + size.0 / 2, grown.1 + size.1 / 2);
    }
    grown
}

/// The two ends of a colour key, as printed.
fn key_ends(scale: Scale) -> (String, String) {
    if scale.hi - scale.lo <= 0.0 {
        ("all 0".into(), "all 0".into())
    } else {
        (number(scale.lo as f64), number(scale.hi as f64))
    }
}

/// Rendered frames (`(title, image)`, top row first) in a grid of `columns`, each enlarged by
/// the whole factor `scale` (nearest pixel) under its title, and below them the `legend`: a
/// swatch and its meaning per line. The picture, and what it shows.
pub fn frames_picture(
    frames: &[(String, RgbaImage)],
    columns: usize,
    scale: u32,
    legend: &[([u8; 4], String)],
) -> (RgbaImage, FramesDrawn) {
    let columns = columns.clamp(1, frames.len().max(1)) as u32;
    let rows = (frames.len() as u32).div_ceil(columns);
    let scale = scale.max(1);
    let cell_w = frames.iter().map(|f| f.1.width()).max().unwrap_or(1) * scale + 2 * MARGIN + 2;
    let width = (columns * cell_w).max(480);
    // Titles and legend in the large font: read on a page, 8-pixel text is too small.
    let glyph = 16;
    let line = |text: &str| wrap(text, ((cell_w - 2 * MARGIN) / glyph).max(1) as usize);
    let title_rows = frames
        .iter()
        .map(|f| line(&f.0).len() as u32)
        .max()
        .unwrap_or(1);
    let cell_h = frames.iter().map(|f| f.1.height()).max().unwrap_or(1) * scale
        + title_rows * (glyph + 2)
        + 2 * MARGIN
        + 2;
    let legend_lines: Vec<Vec<String>> = legend
        .iter()
        .map(|(_, text)| wrap(text, ((width - 3 * glyph) / glyph).max(1) as usize))
        .collect();
    let legend_h = legend_lines.iter().map(|l| l.len() as u32).sum::<u32>() * (glyph + 2);
    let height = rows * cell_h + legend_h + MARGIN * 2;
    let mut image = RgbaImage::from_pixel(width, height, Rgba(BACKGROUND));
    let mut drawn = FramesDrawn {
        text_px: glyph,
        ..FramesDrawn::default()
    };
    for (k, (title, frame)) in frames.iter().enumerate() {
        let (x0, y0) = ((k as u32 % columns) * cell_w, (k as u32 / columns) * cell_h);
        let lines = line(title);
        for (i, text) in lines.iter().enumerate() {
            draw_text(
                &mut image,
                x0 + MARGIN,
                y0 + MARGIN + i as u32 * (glyph + 2),
                text,
                glyph,
            );
        }
        let (ix, iy) = (x0 + MARGIN + 1, y0 + MARGIN + title_rows * (glyph + 2) + 1);
        let (w, h) = (frame.width() * scale, frame.height() * scale);
        fill(&mut image, (ix - 1, iy - 1), (w + 2, h + 2), FRAME);
        for py in 0..h {
            for px in 0..w {
                put(
                    &mut image,
                    ix + px,
                    iy + py,
                    frame.get_pixel(px / scale, py / scale).0,
                );
            }
        }
        drawn.frames.push(FrameDrawn {
            title: title.clone(),
            title_lines: lines.len(),
            pixels: (frame.width(), frame.height()),
            shown: (w, h),
        });
    }
    let mut y = rows * cell_h + MARGIN;
    for ((colour, text), lines) in legend.iter().zip(&legend_lines) {
        fill(&mut image, (MARGIN, y), (glyph, glyph), *colour);
        for text in lines {
            draw_text(&mut image, MARGIN + 2 * glyph, y, text, glyph);
            y += glyph + 2;
        }
        drawn.legend.push(text.clone());
    }
    (image, drawn)
}

/// The lines of a panel's title in a cell `cw` wide.
fn title_lines(panel: &Panel, cw: u32, glyph: u32) -> Vec<String> {
    let columns = (cw.saturating_sub(2 * MARGIN) / glyph).max(1) as usize;
    wrap(&panel.title, columns)
}

/// The room for a panel's texels in a `cw x ch` cell.
fn image_area(panels: &[Panel], cw: u32, ch: u32, glyph: u32) -> (u32, u32) {
    let title = panels
        .iter()
        .map(|p| title_lines(p, cw, glyph).len() as u32)
        .max()
        .unwrap_or(1)
        * (glyph + 2);
    let key = BAR + 2 * (glyph + 2) + MARGIN;
    (
        cw.saturating_sub(2 * MARGIN + 2),
        ch.saturating_sub(title + key + 2 * MARGIN + 2),
    )
}

/// Draw panel `k` of `panels` in its cell; the titles of all panels take the same rows, so
/// that the images of a row of panels line up. Where its texels landed, and the glyph size of
/// its key's numbers.
fn draw_panel(
    image: &mut RgbaImage,
    panels: &[Panel],
    k: usize,
    (x0, y0): (u32, u32),
    (cw, ch): (u32, u32),
    glyph: u32,
) -> (Placement, u32) {
    let panel = &panels[k];
    let rows = panels
        .iter()
        .map(|p| title_lines(p, cw, glyph).len() as u32)
        .max()
        .unwrap_or(1);
    for (i, line) in title_lines(panel, cw, glyph).iter().enumerate() {
        draw_text(
            image,
            x0 + MARGIN,
            y0 + MARGIN + i as u32 * (glyph + 2),
            line,
            glyph,
        );
    }
    let y = y0 + MARGIN + rows * (glyph + 2);
    let (aw, ah) = image_area(panels, cw, ch, glyph);
    let (sx, sy) = stretch(
        aw as f64 / panel.width as f64,
        ah as f64 / panel.height as f64,
        (panel.width, panel.height),
    );
    let (w, h) = (
        ((panel.width as f64 * sx) as u32).max(1),
        ((panel.height as f64 * sy) as u32).max(1),
    );
    let (ix, iy) = (x0 + MARGIN + 1, y + 1);
    fill(image, (ix - 1, iy - 1), (w + 2, h + 2), FRAME);
    let placement = Placement {
        x: ix,
        y: iy,
        w,
        h,
        texels: (panel.width, panel.height),
    };
    for py in 0..h {
        for px in 0..w {
            let (tx, ty) = placement.texel(ix + px, iy + py).expect("inside");
            put(
                image,
                ix + px,
                iy + py,
                panel.scale.colour(panel.at(tx, ty)),
            );
        }
    }
    let key_y = iy + h + 1 + MARGIN;
    let key_w = cw.saturating_sub(2 * MARGIN).max(1);
    let key_glyph = draw_key(image, panel.scale, (x0 + MARGIN, key_y), key_w, glyph);
    (placement, key_glyph)
}

/// The enlargement of each axis from the room's (`sx`, `sy`): one factor for both (square
/// texels), whole when it is at least 1 so that every texel is a block of equal pixels; but a
/// target more than 4 times longer one way than the other (a strip) in a room of another shape
/// is stretched each way (rectangular texels) so that it is not drawn as a line.
fn stretch(sx: f64, sy: f64, (width, height): (u32, u32)) -> (f64, f64) {
    let whole = |s: f64| if s >= 1.0 { s.floor() } else { s };
    let strip = width.max(height) > 4 * width.min(height);
    if strip && sx.max(sy) > 4.0 * sx.min(sy) {
        (whole(sx), whole(sy))
    } else {
        let s = whole(sx.min(sy));
        (s, s)
    }
}

/// The colour key: a bar from the scale's low to high end, the two numbers under its ends and
/// zero under its place when the map is diverging (left out where it would touch the others).
/// The glyph size its numbers took.
fn draw_key(
    image: &mut RgbaImage,
    scale: Scale,
    (x, y): (u32, u32),
    width: u32,
    glyph: u32,
) -> u32 {
    let span = scale.hi - scale.lo;
    for px in 0..width {
        let v = if span > 0.0 {
            scale.lo + span * (px as f32 + 0.5) / width as f32
        } else {
            0.0
        };
        for py in 0..BAR {
            put(image, x + px, y + py, scale.colour(v));
        }
    }
    let label_y = y + BAR + 2;
    if span <= 0.0 {
        return draw_fitted(image, x, label_y, width, "all 0", glyph);
    }
    let lo = number(scale.lo as f64);
    let hi = number(scale.hi as f64);
    let len = |s: &str| s.chars().count() as u32 * glyph;
    if len(&lo) + len(&hi) + glyph > width {
        // Too narrow for both ends on one line: the range on two lines.
        let first = draw_fitted(image, x, label_y, width, &lo, glyph);
        let second = draw_fitted(
            image,
            x,
            label_y + glyph + 2,
            width,
            &format!("to {hi}"),
            glyph,
        );
        return first.min(second);
    }
    draw_text(image, x, label_y, &lo, glyph);
    draw_text(image, x + width - len(&hi), label_y, &hi, glyph);
    if scale.is_signed() && scale.hi > 0.0 {
        let zero_x = x + ((-scale.lo / span) * width as f32) as u32;
        let left = zero_x.saturating_sub(glyph / 2);
        if left >= x + len(&lo) + glyph / 2 && left + glyph + glyph / 2 <= x + width - len(&hi) {
            draw_text(image, left, label_y, "0", glyph);
        }
    }
    glyph
}

/// Text that must fit `width`: in smaller glyphs, then cut to the characters that fit (the
/// last resort of a key narrower than its numbers). The glyph size it took.
fn draw_fitted(image: &mut RgbaImage, x: u32, y: u32, width: u32, text: &str, glyph: u32) -> u32 {
    let n = text.chars().count() as u32;
    let glyph = if n * glyph > width { 8 } else { glyph };
    let fit = (width / glyph) as usize;
    draw_text(
        image,
        x,
        y,
        &text.chars().take(fit).collect::<String>(),
        glyph,
    );
    glyph
}

/// Split `text` into lines of at most `columns` characters, at spaces where it can.
pub fn wrap(text: &str, columns: usize) -> Vec<String> {
    let columns = columns.max(1);
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let mut word = word.to_string();
        while word.chars().count() > columns {
            if !line.is_empty() {
                lines.push(std::mem::take(&mut line));
            }
            let head: String = word.chars().take(columns).collect();
            word = word.chars().skip(columns).collect();
            lines.push(head);
        }
        let needed = line.chars().count() + usize::from(!line.is_empty()) + word.chars().count();
        if needed > columns && !line.is_empty() {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(&word);
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

/// Draw `text` with its top-left corner at (`x`, `y`) in `glyph`-pixel 8x8 font glyphs.
pub fn draw_text(image: &mut RgbaImage, x: u32, y: u32, text: &str, glyph: u32) {
    let scale = (glyph / 8).max(1);
    for (col, c) in text.chars().enumerate() {
        let code = if c.is_ascii() {
            c as usize
        } else {
            '?' as usize
        };
        for (gy, bits) in BASIC_LEGACY[code].iter().enumerate() {
            for gx in 0..8u32 {
                if bits & (1 << gx) == 0 {
                    continue;
                }
                let px = x + col as u32 * 8 * scale + gx * scale;
                let py = y + gy as u32 * scale;
                fill(image, (px, py), (scale, scale), TEXT);
            }
        }
    }
}

fn fill(image: &mut RgbaImage, (x, y): (u32, u32), (w, h): (u32, u32), colour: [u8; 4]) {
    for py in y..y + h {
        for px in x..x + w {
            put(image, px, py, colour);
        }
    }
}

fn put(image: &mut RgbaImage, x: u32, y: u32, colour: [u8; 4]) {
    if x < image.width() && y < image.height() {
        image.put_pixel(x, y, Rgba(colour));
    }
}

/// An image (top row first) as RGBA bytes with rows from the bottom, as GL and the viewer's
/// overlay take them.
pub fn rows_from_bottom(image: &RgbaImage) -> Vec<u8> {
    image
        .as_raw()
        .chunks_exact(image.width() as usize * 4)
        .rev()
        .flatten()
        .copied()
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legible_sizes_grow_by_whole_factors_to_the_large_font() {
        assert_eq!(legible_size((256, 100)), (768, 300));
        assert_eq!(legible_size((640, 10)), (640, 10));
        assert_eq!(legible_size((900, 10)), (900, 10));
        assert_eq!(glyph_for(legible_size((1, 1)).0), 16);
    }

    fn panel(values: Vec<f32>, w: u32, h: u32) -> Panel {
        let scale = Scale::of([values.as_slice()]);
        Panel {
            title: "t".into(),
            values,
            width: w,
            height: h,
            scale,
        }
    }

    #[test]
    fn zero_is_neutral_in_every_scale_and_sign_picks_the_half() {
        for scale in [
            Scale::fixed(0.0, 1.0),
            Scale::fixed(-3.0, 0.5),
            Scale::of([[1e-6f32, 2e-6].as_slice()]),
        ] {
            assert_eq!(scale.colour(0.0), NEUTRAL);
            assert_eq!(scale.colour(-0.0), NEUTRAL);
            assert_eq!(scale.colour(f32::NAN), NOT_FINITE);
        }
        let s = Scale::fixed(-2.0, 2.0);
        let (pos, neg) = (s.colour(2.0), s.colour(-2.0));
        assert!(pos[0] > pos[2], "positive warm: {pos:?}");
        assert!(neg[2] > neg[0], "negative cool: {neg:?}");
    }

    #[test]
    fn numbers_never_print_negative_zero() {
        assert_eq!(fixed(-0.0001, 3), "0.000");
        assert_eq!(fixed(-0.0, 2), "0.00");
        assert_eq!(fixed(-0.5, 1), "-0.5");
        assert_eq!(number(-0.0), "0");
        assert_eq!(number(-1e-9), "-1.00e-9");
        assert_eq!(number(12.5), "12.5");
        assert_eq!(number(0.1234567), "0.1235");
        assert_eq!(number(65535.0), "65535");
    }

    #[test]
    fn small_targets_are_enlarged_by_whole_factors_nearest_texel() {
        let p = panel(vec![1.0, 2.0, 3.0, 4.0], 2, 2);
        let (image, places) = picture(std::slice::from_ref(&p), (200, 200));
        let place = places[0];
        assert_eq!(place.w % 2, 0);
        assert_eq!(place.w, place.h);
        let factor = place.w / 2;
        assert!(factor > 1, "a 2x2 target is enlarged");
        for py in 0..place.h {
            for px in 0..place.w {
                let (tx, ty) = (px / factor, 1 - py / factor);
                let want = p.scale.colour(p.at(tx, ty));
                assert_eq!(image.get_pixel(place.x + px, place.y + py).0, want);
                assert_eq!(place.texel(place.x + px, place.y + py), Some((tx, ty)));
            }
        }
    }

    #[test]
    fn the_key_spans_the_scale_of_the_data() {
        let p = panel(vec![-1.0, 0.0, 0.0, 4.0], 2, 2);
        assert_eq!(p.scale, Scale { lo: -1.0, hi: 4.0 });
        let (image, places) = picture(std::slice::from_ref(&p), (160, 200));
        // The bar's first and last pixels are the colours of the range's ends (at half a
        // pixel in), so the key's range is the data's.
        let y = places[0].y + places[0].h + 1 + MARGIN;
        let x0 = MARGIN;
        let x1 = 160 - MARGIN - 1;
        let first = image.get_pixel(x0, y).0;
        let last = image.get_pixel(x1, y).0;
        let width = 160 - 2 * MARGIN;
        let step = 5.0 / width as f32;
        assert_eq!(first, p.scale.colour(-1.0 + step / 2.0));
        assert_eq!(last, p.scale.colour(4.0 - step / 2.0));
    }

    #[test]
    fn titles_wrap_inside_their_cell() {
        let lines = wrap("P1' (reduced) 8x8 masks of P0", 10);
        assert!(lines.iter().all(|l| l.chars().count() <= 10), "{lines:?}");
        assert_eq!(lines.join(" "), "P1' (reduced) 8x8 masks of P0");
    }
}
