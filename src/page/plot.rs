//! Line plots as PNG (plotters), for the report's figures, the guide's ladder and the compare
//! page: one or more series of (x, y) points, optional log axes, a legend below the axes
//! (never over the data).
//!
//! Made to be read without the code: every axis carries at least two labelled ticks (a log
//! axis at its decades, or at the data's own x values when there are few: 8, 16 .. 512); the
//! x range is fitted to the data; one colour-blind-safe palette (Okabe and Ito's, without its
//! yellow, which is too close to white) with a marker shape per colour, so neighbouring series
//! differ in both; a value of zero on a log axis is a hollow mark on the axis floor, said in a
//! note; series with the same points are one legend entry ("A = B") instead of one hidden
//! under another; reference lines ([`Series::reference`]) are dashed grey. What was drawn is
//! recorded ([`crate::gl::drawn`]) for the figure test.

use crate::gl::drawn::{self, Drawn, PlotDrawn};
use anyhow::{bail, Context as _};
use plotters::prelude::*;
use std::cell::RefCell;
use std::path::Path;
use std::sync::Once;

/// How a series is drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Line {
    /// Points joined by a solid line.
    #[default]
    Solid,
    /// Points joined by a dashed line, no markers (a model or a baseline beside measured data).
    Dashed,
    /// A horizontal line at the first point's y across the whole x axis: a bound a claim
    /// names (Fig. 4's 5%).
    Reference,
    /// A dashed grey line through the points, no markers: a mark on the axes (Fig. 7's
    /// switch), not data.
    Guide,
}

/// One curve of a plot.
#[derive(Clone, Debug, Default)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// The palette slot (colour and marker); `None`: the series' place among the plot's.
    pub slot: Option<usize>,
    pub line: Line,
}

impl Series {
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            ..Series::default()
        }
    }

    /// A horizontal reference line at `y`.
    pub fn reference(name: impl Into<String>, y: f64) -> Series {
        Series {
            name: name.into(),
            points: vec![(0.0, y)],
            slot: None,
            line: Line::Reference,
        }
    }

    /// A dashed grey line through `points` (a threshold drawn across the data).
    pub fn guide(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
            slot: None,
            line: Line::Guide,
        }
    }

    /// Drawn in palette slot `slot` (series of one object share a colour).
    pub fn slot(self, slot: usize) -> Series {
        Series {
            slot: Some(slot),
            ..self
        }
    }

    /// Drawn dashed, without markers.
    pub fn dashed(self) -> Series {
        Series {
            line: Line::Dashed,
            ..self
        }
    }
}

/// A plot: title, axis labels, log axes, curves.
#[derive(Clone, Debug, Default)]
pub struct Plot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_x: bool,
    pub log_y: bool,
    pub series: Vec<Series>,
}

const FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
/// The size of the axes' part of the image; the legend adds rows below it.
const SIZE: (u32, u32) = (900, 560);
/// The size of tick labels and legend text, the plot's smallest, px.
const LABEL_PX: u32 = 14;
/// Height of one legend row, px.
const LEGEND_ROW: u32 = 22;
/// Legend entries per row.
const LEGEND_COLUMNS: usize = 2;

/// Okabe and Ito's colour-blind-safe palette without its yellow, ordered so that neighbours
/// differ in hue and lightness.
const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
];
/// Reference lines.
const GREY: RGBColor = RGBColor(110, 110, 110);

/// Marker shapes, one per palette colour (a second round of colours takes the next shapes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Marker {
    Circle,
    Square,
    TriangleUp,
    Diamond,
    TriangleDown,
    Cross,
    Plus,
}

const MARKERS: [Marker; 7] = [
    Marker::Circle,
    Marker::Square,
    Marker::TriangleUp,
    Marker::Diamond,
    Marker::TriangleDown,
    Marker::Cross,
    Marker::Plus,
];

/// The colour and marker of palette slot `slot`.
fn style_of(slot: usize) -> (RGBColor, Marker) {
    let n = PALETTE.len();
    (PALETTE[slot % n], MARKERS[(slot + slot / n) % n])
}

/// A curve as drawn: its legend name (merged names of identical series), style, points.
#[derive(Clone, Debug)]
struct Curve {
    name: String,
    colour: RGBColor,
    marker: Marker,
    line: Line,
    /// Points inside the axes.
    points: Vec<(f64, f64)>,
    /// x of the points whose y is exactly zero on a log y axis.
    zeros: Vec<f64>,
}

impl Curve {
    /// Measured or published data, not a reference or guide line.
    fn is_data(&self) -> bool {
        matches!(self.line, Line::Solid | Line::Dashed)
    }
}

/// The curves of `series`: identical data series merged ("A = B"), styles assigned.
fn curves(series: &[Series], log_x: bool, log_y: bool) -> Vec<Curve> {
    let mut out: Vec<(Curve, Vec<(u64, u64)>)> = Vec::new();
    let mut data_slot = 0;
    for s in series {
        let key: Vec<(u64, u64)> = s
            .points
            .iter()
            .map(|p| (p.0.to_bits(), p.1.to_bits()))
            .collect();
        if matches!(s.line, Line::Solid | Line::Dashed) {
            if let Some((curve, _)) = out
                .iter_mut()
                .find(|(c, k)| c.line == s.line && *k == key && !key.is_empty())
            {
                curve.name = format!("{} = {}", curve.name, s.name);
                continue;
            }
        }
        let slot = s.slot.unwrap_or(data_slot);
        let (colour, marker) = match s.line {
            Line::Reference | Line::Guide => (GREY, Marker::Circle),
            Line::Solid | Line::Dashed => {
                data_slot += 1;
                style_of(slot)
            }
        };
        let reference = s.line == Line::Reference;
        let usable = |&(x, y): &(f64, f64)| {
            let x_ok = reference || (x.is_finite() && (!log_x || x > 0.0));
            x_ok && y.is_finite() && (!log_y || y > 0.0)
        };
        let zeros = if log_y && matches!(s.line, Line::Solid | Line::Dashed) {
            s.points
                .iter()
                .filter(|p| p.1 == 0.0 && p.0.is_finite() && (!log_x || p.0 > 0.0))
                .map(|p| p.0)
                .collect()
        } else {
            Vec::new()
        };
        let curve = Curve {
            name: s.name.clone(),
            colour,
            marker,
            line: s.line,
            points: s.points.iter().copied().filter(usable).collect(),
            zeros,
        };
        out.push((curve, key));
    }
    out.into_iter().map(|(c, _)| c).collect()
}

/// Two data curves closer than this (relative to the larger value) at a point are said to lie
/// on one another there: one hides the other where they are drawn.
const COINCIDENT: f64 = 0.05;

/// A note for each pair of data curves with the same x values that lie within [`COINCIDENT`]
/// of each other at two points or more (identical ones are already one curve), naming those
/// points, so that a reader knows the curve they see there is two.
fn coincident_notes(curves: &[Curve]) -> Vec<String> {
    let data: Vec<&Curve> = curves.iter().filter(|c| c.is_data()).collect();
    let mut notes = Vec::new();
    for (i, a) in data.iter().enumerate() {
        for b in &data[i + 1..] {
            let same_x = a.points.len() == b.points.len()
                && a.points.iter().zip(&b.points).all(|(p, q)| p.0 == q.0);
            if !same_x {
                continue;
            }
            let close: Vec<String> = a
                .points
                .iter()
                .zip(&b.points)
                .filter(|(p, q)| (p.1 - q.1).abs() <= COINCIDENT * p.1.abs().max(q.1.abs()))
                .map(|(p, _)| tick_label(p.0))
                .collect();
            if close.len() >= 2 {
                let at = if close.len() == a.points.len() {
                    "at every point".to_string()
                } else {
                    format!("at x = {}", close.join(", "))
                };
                notes.push(format!(
                    "'{}' and '{}' lie within {:.0}% of each other {at}: one hides the other.",
                    a.name,
                    b.name,
                    100.0 * COINCIDENT
                ));
            }
        }
    }
    notes
}

/// One axis: its range and the values it labels.
#[derive(Clone, Debug, PartialEq)]
struct Axis {
    lo: f64,
    hi: f64,
    ticks: Vec<f64>,
}

/// A linear axis over `values` (5% margin), ticked at 1, 2 or 5 times a power of ten (whole
/// numbers only when `whole`); plotters places its own ticks on a linear axis, as many as
/// these.
fn linear_axis(values: &[f64], whole: bool) -> Axis {
    let (lo, hi) = min_max(values);
    let (lo, hi) = if hi > lo {
        let pad = (hi - lo) * 0.05;
        (lo - pad, hi + pad)
    } else {
        (lo - 1.0, hi + 1.0)
    };
    let raw = (hi - lo) / 6.0;
    let power = 10f64.powf(raw.log10().floor());
    let mut step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * power)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * power);
    if whole {
        step = step.max(1.0).ceil();
    }
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    let ticks = (first..=last).map(|k| k as f64 * step).collect();
    Axis { lo, hi, ticks }
}

/// A log x axis fitted to `values` (a fifth of a factor beyond each end), ticked at the
/// values themselves when there are 2 to 12 distinct ones, else at 1-2-5 steps.
fn log_x_axis(values: &[f64]) -> Axis {
    let (lo, hi) = min_max(values);
    let (lo, hi) = if hi > lo {
        (lo / 1.2, hi * 1.2)
    } else {
        (lo / 2.0, hi * 2.0)
    };
    let mut distinct: Vec<f64> = values.to_vec();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup();
    let ticks = if (2..=12).contains(&distinct.len()) {
        distinct
    } else {
        log_ticks(lo, hi)
    };
    Axis { lo, hi, ticks }
}

/// A log y axis from the decade below the smallest value to the decade above the largest
/// (one decade lower again when zeros are marked on its floor), labelled at its decades, the
/// lowest and the highest included.
fn log_y_axis(values: &[f64], zeros: bool) -> Axis {
    let (lo, hi) = if values.is_empty() {
        (1e-3, 1.0)
    } else {
        min_max(values)
    };
    // A value within a sixth of a decade of an end gets the next decade, off the frame.
    let mut bottom = (lo.log10() - 0.15).floor();
    let mut top = (hi.log10() + 0.15).ceil().max(bottom + 1.0);
    if zeros {
        bottom -= 1.0;
    }
    // Thinned to every k-th decade, the axis ends at a labelled decade too.
    let every = ((top - bottom) as usize + 1).div_ceil(10).max(1) as f64;
    while (top - bottom) % every != 0.0 {
        top += 1.0;
    }
    let (lo, hi) = (10f64.powf(bottom), 10f64.powf(top));
    Axis {
        lo,
        hi,
        ticks: log_ticks(lo, hi),
    }
}

/// Ticks of a log axis from `lo` to `hi`: every decade (thinned to at most 10), with 2 and 5
/// between when fewer than three decades fall inside.
fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let inside = |v: f64| v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9);
    let (first, last) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let decades: Vec<f64> = (first..=last)
        .map(|k| 10f64.powi(k))
        .filter(|&v| inside(v))
        .collect();
    if decades.len() >= 3 {
        let every = decades.len().div_ceil(10);
        return decades.into_iter().step_by(every).collect();
    }
    (first..=last)
        .flat_map(|k| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(k)))
        .filter(|&v| inside(v))
        .collect()
}

fn min_max(values: &[f64]) -> (f64, f64) {
    values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
}

/// Rows of the legend below the axes for `entries` entries and `notes` notes.
fn legend_rows(entries: usize, notes: usize) -> u32 {
    (entries.div_ceil(LEGEND_COLUMNS) + notes) as u32
}

/// The whole image: the axes and the legend rows below them (with a margin).
fn image_size(entries: usize, notes: usize) -> (u32, u32) {
    let legend = legend_rows(entries, notes);
    let margin = if legend > 0 { 20 } else { 0 };
    (SIZE.0, SIZE.1 + legend * LEGEND_ROW + margin)
}

pub(crate) fn register_font() {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // The font is part of the source; a failure here is a bug caught by the plot test.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

fn err(e: impl std::fmt::Display) -> anyhow::Error {
    anyhow::anyhow!("{e}")
}

/// Everything measured before drawing: the curves, both axes, the notes.
struct Layout {
    curves: Vec<Curve>,
    x: Axis,
    y: Axis,
    whole_x: bool,
    notes: Vec<String>,
}

impl Plot {
    /// Write the plot to `path` (PNG), and record what it shows.
    pub fn write_png(&self, path: &Path) -> anyhow::Result<()> {
        register_font();
        let layout = self.layout()?;
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        }
        // Drawn into a buffer and written with `image`, so plotters needs no PNG encoder of its own.
        let size = image_size(layout.curves.len(), layout.notes.len());
        let mut pixels = vec![0u8; (size.0 * size.1 * 3) as usize];
        let ticks = RefCell::new((Vec::new(), Vec::new()));
        {
            let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
            root.fill(&WHITE)?;
            let (axes, legend) = root.split_vertically(SIZE.1);
            let (x, y) = (&layout.x, &layout.y);
            let (xr, yr) = (x.lo..x.hi, y.lo..y.hi);
            let (xt, yt) = (x.ticks.clone(), y.ticks.clone());
            match (self.log_x, self.log_y) {
                (false, false) => self.draw(&axes, xr, yr, &layout, &ticks),
                (true, false) => self.draw(
                    &axes,
                    xr.log_scale().with_key_points(xt),
                    yr,
                    &layout,
                    &ticks,
                ),
                (false, true) => self.draw(
                    &axes,
                    xr,
                    yr.log_scale().with_key_points(yt),
                    &layout,
                    &ticks,
                ),
                (true, true) => self.draw(
                    &axes,
                    xr.log_scale().with_key_points(xt),
                    yr.log_scale().with_key_points(yt),
                    &layout,
                    &ticks,
                ),
            }
            .with_context(|| format!("drawing {}", path.display()))?;
            draw_legend(&legend, &layout).with_context(|| format!("drawing {}", path.display()))?;
            root.present()
                .with_context(|| format!("drawing {}", path.display()))?;
        }
        let image = image::RgbImage::from_raw(size.0, size.1, pixels)
            .context("the plot's pixels do not fill its size")?;
        crate::files::write_image(path, &image::DynamicImage::ImageRgb8(image))?;
        let (x_ticks, y_ticks) = ticks.into_inner();
        drawn::record(
            path,
            Drawn::Plot(PlotDrawn {
                title: self.title.clone(),
                x_title: self.x_label.clone(),
                y_title: self.y_label.clone(),
                x_ticks,
                y_ticks,
                legend: layout.curves.iter().map(|c| c.name.clone()).collect(),
                curves: layout.curves.iter().filter(|c| c.is_data()).count(),
                notes: layout.notes.clone(),
                text_px: LABEL_PX,
            }),
        );
        Ok(())
    }

    /// The curves, axes and notes of the plot.
    fn layout(&self) -> anyhow::Result<Layout> {
        let curves = curves(&self.series, self.log_x, self.log_y);
        let data = || curves.iter().filter(|c| c.is_data());
        let xs: Vec<f64> = data()
            .flat_map(|c| c.points.iter().map(|p| p.0).chain(c.zeros.iter().copied()))
            .collect();
        let ys: Vec<f64> = curves
            .iter()
            .flat_map(|c| c.points.iter().map(|p| p.1))
            .collect();
        let has_zeros = data().any(|c| !c.zeros.is_empty());
        if xs.is_empty() {
            bail!("plot '{}' has no finite points to draw", self.title);
        }
        let whole_x = !self.log_x && xs.iter().all(|x| x.fract() == 0.0);
        let x = if self.log_x {
            log_x_axis(&xs)
        } else {
            linear_axis(&xs, whole_x)
        };
        let y = if self.log_y {
            log_y_axis(&ys, has_zeros)
        } else {
            linear_axis(&ys, false)
        };
        let mut notes = coincident_notes(&curves);
        if has_zeros {
            notes.push(
                "Hollow marks on the bottom axis: a value of 0 (a log axis has no 0).".to_string(),
            );
        }
        let dropped: usize = self
            .series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|p| !p.0.is_finite() || !p.1.is_finite() || (self.log_y && p.1 < 0.0))
            .count();
        if dropped > 0 {
            notes.push(format!(
                "{dropped} point(s) not drawn: not finite, or negative on a log axis."
            ));
        }
        Ok(Layout {
            curves,
            x,
            y,
            whole_x,
            notes,
        })
    }

    fn draw<X, Y>(
        &self,
        root: &Area,
        x: X,
        y: Y,
        layout: &Layout,
        ticks: &RefCell<(Vec<String>, Vec<String>)>,
    ) -> anyhow::Result<()>
    where
        X: plotters::coord::ranged1d::AsRangedCoord<Value = f64>,
        Y: plotters::coord::ranged1d::AsRangedCoord<Value = f64>,
        X::CoordDescType: plotters::coord::ranged1d::ValueFormatter<f64>,
        Y::CoordDescType: plotters::coord::ranged1d::ValueFormatter<f64>,
    {
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 22))
            .margin(12)
            .margin_right(36)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(x, y)
            .map_err(err)?;
        let whole_x = layout.whole_x;
        let remember = |list: &mut Vec<String>, text: &String| {
            if !text.is_empty() && list.last() != Some(text) {
                list.push(text.clone());
            }
        };
        let x_label = |v: &f64| {
            let text = if whole_x && v.fract() != 0.0 {
                String::new()
            } else {
                tick_label(*v)
            };
            remember(&mut ticks.borrow_mut().0, &text);
            text
        };
        let y_label = |v: &f64| {
            let text = tick_label(*v);
            remember(&mut ticks.borrow_mut().1, &text);
            text
        };
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style(("sans-serif", LABEL_PX))
            .x_labels(layout.x.ticks.len().clamp(2, 10))
            .y_labels(layout.y.ticks.len().clamp(2, 10))
            .x_label_formatter(&x_label)
            .y_label_formatter(&y_label)
            .draw()
            .map_err(err)?;
        let (x0, x1) = (layout.x.lo, layout.x.hi);
        for curve in &layout.curves {
            let colour = curve.colour;
            match curve.line {
                Line::Reference => {
                    let y = curve.points.first().map_or(f64::NAN, |p| p.1);
                    chart
                        .draw_series(DashedLineSeries::new(
                            [(x0, y), (x1, y)],
                            10,
                            6,
                            colour.stroke_width(2),
                        ))
                        .map_err(err)?;
                }
                Line::Dashed | Line::Guide => {
                    chart
                        .draw_series(DashedLineSeries::new(
                            curve.points.clone(),
                            10,
                            6,
                            colour.stroke_width(2),
                        ))
                        .map_err(err)?;
                }
                Line::Solid => {
                    chart
                        .draw_series(LineSeries::new(
                            curve.points.clone(),
                            colour.stroke_width(2),
                        ))
                        .map_err(err)?;
                }
            }
        }
        // Markers in pixels, on top of every line: the shapes tell the series apart where
        // colours do not.
        let floor = layout.y.lo;
        for curve in &layout.curves {
            if curve.line == Line::Solid {
                for p in &curve.points {
                    let at = chart.backend_coord(p);
                    draw_marker(root, at, curve.marker, curve.colour, true)?;
                }
            }
            for &x in &curve.zeros {
                let at = chart.backend_coord(&(x, floor));
                draw_marker(root, at, Marker::Circle, curve.colour, false)?;
            }
        }
        Ok(())
    }
}

/// Draw `marker` centred at pixel `at`, filled or as an outline.
fn draw_marker(
    area: &Area,
    (x, y): (i32, i32),
    marker: Marker,
    colour: RGBColor,
    filled: bool,
) -> anyhow::Result<()> {
    let style = if filled {
        colour.filled()
    } else {
        colour.stroke_width(2)
    };
    let r = 5;
    let outline = |points: Vec<(i32, i32)>| -> anyhow::Result<()> {
        if filled {
            area.draw(&Polygon::new(points, style)).map_err(err)
        } else {
            let mut closed = points.clone();
            closed.push(points[0]);
            area.draw(&PathElement::new(closed, style)).map_err(err)
        }
    };
    match marker {
        Marker::Circle => area.draw(&Circle::new((x, y), r, style)).map_err(err),
        Marker::Square => area
            .draw(&Rectangle::new([(x - 4, y - 4), (x + 4, y + 4)], style))
            .map_err(err),
        Marker::TriangleUp => outline(vec![(x, y - r - 1), (x + r, y + r - 1), (x - r, y + r - 1)]),
        Marker::TriangleDown => {
            outline(vec![(x, y + r + 1), (x + r, y - r + 1), (x - r, y - r + 1)])
        }
        Marker::Diamond => outline(vec![(x, y - r - 1), (x + r, y), (x, y + r + 1), (x - r, y)]),
        Marker::Cross | Marker::Plus => {
            let stroke = colour.stroke_width(3);
            let arms = if marker == Marker::Cross {
                [
                    [(x - r, y - r), (x + r, y + r)],
                    [(x - r, y + r), (x + r, y - r)],
                ]
            } else {
                [[(x - r, y), (x + r, y)], [(x, y - r), (x, y + r)]]
            };
            for arm in arms {
                area.draw(&PathElement::new(arm.to_vec(), stroke))
                    .map_err(err)?;
            }
            Ok(())
        }
    }
}

/// The legend in its own strip below the axes: a line sample, marker and name per curve in
/// [`LEGEND_COLUMNS`] columns, then the notes one per row.
fn draw_legend(area: &Area, layout: &Layout) -> anyhow::Result<()> {
    let column_width = (SIZE.0 as i32 - 100) / LEGEND_COLUMNS as i32;
    let font = ("sans-serif", LABEL_PX).into_font().color(&BLACK);
    let row = LEGEND_ROW as i32;
    for (i, curve) in layout.curves.iter().enumerate() {
        let x = 80 + (i % LEGEND_COLUMNS) as i32 * column_width;
        let y = 6 + (i / LEGEND_COLUMNS) as i32 * row + row / 2;
        let style = curve.colour.stroke_width(2);
        if curve.line == Line::Solid {
            area.draw(&PathElement::new(vec![(x, y), (x + 28, y)], style))
                .map_err(err)?;
            draw_marker(area, (x + 14, y), curve.marker, curve.colour, true)?;
        } else {
            for dash in [(x, x + 10), (x + 16, x + 26)] {
                area.draw(&PathElement::new(vec![(dash.0, y), (dash.1, y)], style))
                    .map_err(err)?;
            }
        }
        area.draw(&Text::new(
            curve.name.clone(),
            (x + 36, y - 8),
            font.clone(),
        ))
        .map_err(err)?;
    }
    let first = legend_rows(layout.curves.len(), 0) as i32;
    for (k, note) in layout.notes.iter().enumerate() {
        let y = 6 + (first + k as i32) * row + row / 2;
        area.draw(&Text::new(note.clone(), (80, y - 8), font.clone()))
            .map_err(err)?;
    }
    Ok(())
}

/// A short axis label: 0.001 .. 99999 in plain digits (trailing zeros dropped), else 1e6.
fn tick_label(v: f64) -> String {
    let magnitude = v.abs();
    if v == 0.0 {
        "0".into()
    } else if !(1e-3..1e5).contains(&magnitude) {
        format!("{v:.0e}")
    } else {
        let text = format!("{v:.3}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_label(0.0), "0");
        assert_eq!(tick_label(0.09999999), "0.1");
        assert_eq!(tick_label(100.0), "100");
        assert_eq!(tick_label(2.5), "2.5");
        assert_eq!(tick_label(1e6), "1e6");
        assert_eq!(tick_label(1e-5), "1e-5");
    }

    #[test]
    fn axes_have_two_ticks_and_fit_the_data() {
        // Fig. 4's resolutions: ticked at the data, the range just beyond it.
        let xs = [8.0, 16.0, 32.0, 64.0, 128.0, 256.0, 512.0];
        let x = log_x_axis(&xs);
        assert_eq!(x.ticks, xs.to_vec());
        assert!(x.lo > 5.0 && x.hi < 700.0, "{x:?}");
        // Less than a decade of y: 2 and 5 fill in, the floor decade is a tick.
        let y = log_y_axis(&[2e-7, 6e-7], false);
        assert_eq!(y.lo, 1e-7);
        assert!(y.ticks.len() >= 3 && y.ticks[0] == 1e-7, "{y:?}");
        // Many decades are thinned, the lowest kept.
        let wide = log_ticks(1e-16, 1.0);
        assert!(wide.len() <= 10 && wide[0] == 1e-16, "{wide:?}");
        let lin = linear_axis(&[3.0, 3.0], true);
        assert!(lin.ticks.len() >= 2, "{lin:?}");
        assert!(linear_axis(&[0.0, 0.37], false).ticks.len() >= 2);
    }

    #[test]
    fn identical_series_share_one_legend_entry_and_colours_differ() {
        let a = vec![(1.0, 2.0), (2.0, 3.0)];
        let curves = curves(
            &[
                Series::new("classic", a.clone()),
                Series::new("compute", a),
                Series::new("other", vec![(1.0, 1.0)]),
                Series::reference("5%", 0.05),
            ],
            false,
            false,
        );
        let names: Vec<&str> = curves.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["classic = compute", "other", "5%"]);
        assert_ne!(curves[0].colour, curves[1].colour);
        assert_ne!(curves[0].marker, curves[1].marker);
        // No colour of the palette is near white (the plot's background).
        for c in PALETTE {
            let light = 0.2126 * c.0 as f64 + 0.7152 * c.1 as f64 + 0.0722 * c.2 as f64;
            assert!(light < 200.0, "{c:?}");
        }
    }

    #[test]
    fn curves_that_lie_on_one_another_are_said_once() {
        let curves = curves(
            &[
                Series::new("VS, here", vec![(1.0, 100.0), (16.0, 50.0)]),
                Series::new("VS 1/draw, here", vec![(1.0, 103.0), (16.0, 49.0)]),
                Series::new("2-pass, here", vec![(1.0, 60.0), (16.0, 49.5)]),
            ],
            true,
            true,
        );
        let notes = coincident_notes(&curves);
        assert_eq!(notes.len(), 1, "{notes:?}");
        assert!(notes[0].starts_with("'VS, here' and 'VS 1/draw, here' lie within 5%"));
        assert!(notes[0].contains("at every point"), "{notes:?}");
        // Close at two of three points: those are named.
        let partly = super::curves(
            &[
                Series::new("a", vec![(1.0, 100.0), (16.0, 50.0), (64.0, 10.0)]),
                Series::new("b", vec![(1.0, 200.0), (16.0, 51.0), (64.0, 10.2)]),
            ],
            true,
            true,
        );
        assert_eq!(
            coincident_notes(&partly),
            ["'a' and 'b' lie within 5% of each other at x = 16, 64: one hides the other."]
        );
    }

    #[test]
    fn writes_a_png_with_log_axes_zero_marks_and_records_it() {
        let dir = std::env::temp_dir().join(format!("classic-gpgpu-plot-{}", std::process::id()));
        let path = dir.join("plot.png");
        let plot = Plot {
            title: "test".into(),
            x_label: "n".into(),
            y_label: "ms".into(),
            log_x: true,
            log_y: true,
            series: vec![
                Series::new("a", vec![(1.0, 1.0), (10.0, 5.0), (100.0, 80.0)]),
                Series::new("b", vec![(1.0, 2.0), (100.0, 0.0)]), // 0: a hollow mark
            ],
        };
        plot.write_png(&path).unwrap();
        let image = image::open(&path).unwrap().to_rgb8();
        assert_eq!(image.dimensions(), image_size(2, 1));
        // The legend is below the axes: its rows hold the curves' colours.
        let colour = PALETTE[0];
        let legend_has_colour = (SIZE.1..image.height()).any(|y| {
            (0..image.width()).any(|x| image.get_pixel(x, y).0 == [colour.0, colour.1, colour.2])
        });
        assert!(legend_has_colour, "no legend below the axes");
        let Some(Drawn::Plot(shown)) = drawn::recorded(&path) else {
            panic!("the plot was not recorded");
        };
        assert_eq!(shown.legend, ["a", "b"]);
        assert_eq!(shown.notes.len(), 1, "{:?}", shown.notes);
        assert!(
            shown.x_ticks.len() >= 2 && shown.y_ticks.len() >= 2,
            "{shown:?}"
        );
        assert!(Drawn::Plot(shown).problems().is_empty());
        std::fs::remove_dir_all(dir).ok();
        let empty = Plot {
            title: "empty".into(),
            ..Plot::default()
        };
        assert!(empty.write_png(&path).is_err());
    }
}
