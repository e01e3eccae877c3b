//! Insets: an intermediate buffer (any texture the paper code keeps) drawn small in a corner of
//! the frame, or filling it when it is the buffer shown. Float buffers are drawn as
//! `gl::dump` states the mapping ([`crate::gl::picture`]: one panel per channel, zero neutral,
//! a colour key), so the inset looks like the dumped file; each panel is recorded on the
//! canvas for the texel probe, with the CPU reference's values where the demo has one.

use super::{overlay, Canvas};
use crate::gl::dump::DumpRange;
use crate::gl::picture::{self, number, Panel, Placement};
use crate::gl::{GlError, Rect, Texture};

/// A panel drawn into the frame, for the probe: where its texels are (canvas pixels, top-left
/// origin), the values the probe shows (the GPU's) and the reference's, when there is one.
#[derive(Clone, Debug)]
pub struct Probed {
    pub name: String,
    pub placement: Placement,
    pub values: Vec<f32>,
    pub reference: Option<Vec<f32>>,
}

impl Probed {
    /// The readout for canvas pixel (`x`, `y`) (top-left origin), if it is over this panel.
    pub fn readout(&self, x: u32, y: u32) -> Option<Vec<String>> {
        let (tx, ty) = self.placement.texel(x, y)?;
        let i = (ty * self.placement.texels.0 + tx) as usize;
        let gpu = *self.values.get(i)?;
        let name = self.name.split(':').next().unwrap_or_default();
        let mut lines = vec![
            format!("{name} texel ({tx}, {ty})"),
            format!("GPU {}", probe_number(gpu)),
        ];
        if let Some(cpu) = self.reference.as_ref().and_then(|r| r.get(i)) {
            lines.push(format!("CPU {}", probe_number(*cpu)));
        }
        Some(lines)
    }
}

/// A probed value in full: the shortest decimal that reads back as the same f32 (so the
/// probe tells any two values apart), "0" for both zeros, exponent form when very small or
/// large.
fn probe_number(v: f32) -> String {
    if v == 0.0 {
        "0".into()
    } else if !v.is_finite() {
        number(v as f64)
    } else if (1e-4..1e7).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// A panel of a picture, with what its probe shows when that is not the colours' values (the
/// masks of collide's levels are coloured by their set bits) and the CPU reference's values.
pub struct Shown {
    pub panel: Panel,
    pub probe_values: Option<Vec<f32>>,
    pub reference: Option<Vec<f32>>,
}

impl From<Panel> for Shown {
    fn from(panel: Panel) -> Shown {
        Shown {
            panel,
            probe_values: None,
            reference: None,
        }
    }
}

/// Draw `shown` as one picture ([`picture::picture`]: panels with titles and colour keys)
/// filling `rect` of `canvas`, and record each panel for the probe.
pub fn draw_picture(canvas: &Canvas, shown: Vec<Shown>, rect: Rect) -> Result<(), GlError> {
    if rect.w < 8 || rect.h < 8 || shown.is_empty() {
        return Ok(());
    }
    let panels: Vec<Panel> = shown.iter().map(|s| s.panel.clone()).collect();
    let (image, placements) = picture::picture(&panels, (rect.w, rect.h));
    overlay::draw_image(
        canvas,
        &picture::rows_from_bottom(&image),
        rect.w,
        rect.h,
        (rect.x, rect.y),
    )?;
    // The picture's top-left corner in canvas pixels from the top.
    let top = canvas.height() - (rect.y + rect.h);
    for (s, p) in shown.into_iter().zip(placements) {
        canvas.add_probed(Probed {
            name: s.panel.title.clone(),
            placement: Placement {
                x: p.x + rect.x,
                y: p.y + top,
                ..p
            },
            values: s.probe_values.unwrap_or(s.panel.values),
            reference: s.reference,
        });
    }
    Ok(())
}

/// A float `texture` as one panel per named channel, each on its own scale from `range`.
pub fn texture_panels(
    texture: &Texture,
    channels: &[&str],
    range: DumpRange,
) -> Result<Vec<Panel>, GlError> {
    let n = texture.format().components();
    let values = texture.download_f32()?;
    let dims = (texture.width(), texture.height());
    Ok(channels
        .iter()
        .enumerate()
        .take(n)
        .map(|(c, name)| {
            let panel = Panel::channel(*name, &values, n, c, dims, picture::Scale::fixed(0.0, 0.0));
            let scale = range.scale(&panel.values);
            Panel { scale, ..panel }
        })
        .collect())
}

/// Draw an RGBA image (rows from the bottom) scaled into `rect` of `canvas`, framed in grey,
/// keeping its aspect ratio, with `label` in its bottom-left corner. Where its pixels are
/// (canvas pixels, top-left origin), for the probe.
pub fn draw_rgba(
    canvas: &Canvas,
    rgba: &[u8],
    (width, height): (u32, u32),
    rect: Rect,
    label: &str,
) -> Result<Option<Placement>, GlError> {
    if rect.w < 3 || rect.h < 3 || width == 0 || height == 0 {
        return Ok(None);
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
    let placement = Placement {
        x: rect.x + 1,
        y: canvas.height() - (rect.y + fh) + 1,
        w,
        h,
        texels: (width, height),
    };
    if !label.is_empty() {
        overlay::draw_text(
            canvas,
            &[label.to_string()],
            overlay::Corner::At(rect.x, rect.y),
        )?;
    }
    Ok(Some(placement))
}

/// The rectangle of a strip of `count` panels along the bottom right of `canvas` (drawn as one
/// picture): each panel at most a fifth of its width, the strip at most half its height.
pub fn strip_rect(canvas: &Canvas, count: usize) -> Rect {
    let (w, h) = (canvas.width(), canvas.height());
    let cell = (w / 5).min(w / count.max(1) as u32).max(1);
    let width = cell * count as u32;
    let text = if picture::glyph_for(width) > 8 {
        70
    } else {
        40
    };
    let height = (cell + text).min(h / 2);
    Rect::new(w - width, 0, width, height)
}
