//! The headline ratios across the machines, as PNG: one x position per column of the table
//! (the paper's hardware first), one line of markers per ratio, log y. Each line's
//! marker is its own (filled circle, triangle, cross, open circle, in turn). Colours are the
//! Okabe-Ito palette, told apart with any common colour-vision deficiency.

use super::headline::{then_and_now_text, THEN_AND_NOW};
use super::{Comparison, Group};
use anyhow::Context as _;
use plotters::prelude::*;

/// A figure of the page: its group, file name, caption, PNG bytes.
pub struct Figure {
    /// The index of the group of runs it plots ([`Comparison::groups`]).
    pub group: usize,
    pub file: String,
    pub caption: String,
    pub png: Vec<u8>,
}

/// The files the figures of a group are written to (those of `--quick` runs end in `-quick`).
pub const FILES: [&str; 2] = ["headline_ratios", "then_and_now"];

/// The file of figure `name` ([`FILES`]) of a group.
fn file(name: &str, group: &Group) -> String {
    if group.quick {
        format!("{name}-quick.png")
    } else {
        format!("{name}.png")
    }
}

/// Every file the figures of `c` may be written to.
pub fn files(c: &Comparison) -> Vec<String> {
    c.groups
        .iter()
        .flat_map(|g| FILES.iter().map(move |name| file(name, g)))
        .collect()
}

/// Okabe & Ito's colour-blind-safe palette (black last).
const PALETTE: [RGBColor; 8] = [
    RGBColor(0xE6, 0x9F, 0x00),
    RGBColor(0x56, 0xB4, 0xE9),
    RGBColor(0x00, 0x9E, 0x73),
    RGBColor(0xD5, 0x5E, 0x00),
    RGBColor(0x00, 0x72, 0xB2),
    RGBColor(0xCC, 0x79, 0xA7),
    RGBColor(0xF0, 0xE4, 0x42),
    RGBColor(0x00, 0x00, 0x00),
];

/// The axes' part of the image; the legend adds rows below.
const SIZE: (u32, u32) = (1000, 520);
const LEGEND_ROW: u32 = 24;

/// One line of the chart: a value per x position (`None`: no point there).
pub struct Line {
    pub name: String,
    pub values: Vec<Option<f64>>,
}

/// A chart over named x positions.
pub struct Chart {
    pub title: String,
    pub y_label: String,
    pub x_names: Vec<String>,
    pub lines: Vec<Line>,
}

/// The figures of a comparison, group by group; a figure with no point to draw is left out.
pub fn figures(c: &Comparison) -> anyhow::Result<Vec<Figure>> {
    let mut figures = Vec::new();
    for (i, group) in c.groups.iter().enumerate() {
        figures.extend(group_figures(i, group)?);
    }
    Ok(figures)
}

fn group_figures(index: usize, c: &Group) -> anyhow::Result<Vec<Figure>> {
    let mut figures = Vec::new();
    let mut x_names = vec!["the paper's hardware".to_string()];
    x_names.extend(c.machines.iter().map(|m| m.label.clone()));
    let headline = Chart {
        title: "Headline ratios: the paper's hardware, then each machine".into(),
        y_label: "ratio (log scale; above 1: the paper's method ahead)".into(),
        x_names,
        lines: c
            .headlines
            .iter()
            .filter(|r| !r.ratio.is_empty())
            .map(|r| {
                let mut values = vec![r.paper_ratio];
                values.extend(
                    r.cells
                        .iter()
                        .map(|cell| cell.figure.as_ref().and_then(|f| f.ratio)),
                );
                Line {
                    name: r.ratio.clone(),
                    values,
                }
            })
            .collect(),
    };
    if let Some(png) = headline.png()? {
        figures.push(Figure {
            group: index,
            file: file(FILES[0], c),
            caption: "Each headline ratio on the paper's hardware (where the paper states it) \
                      and on each machine. The tori frame and the buoyancy frame rate are \
                      taken relative to the paper's own figure, so the paper's hardware sits \
                      at 1 for them."
                .into(),
            png,
        });
    }
    let then_and_now = Chart {
        title: "Then and now: compute-shader frame time / classic frame time".into(),
        y_label: "compute / classic (log scale; below 1: compute faster)".into(),
        x_names: c.machines.iter().map(|m| m.label.clone()).collect(),
        lines: THEN_AND_NOW
            .iter()
            .enumerate()
            .map(|(i, (_, name))| Line {
                name: (*name).into(),
                values: c
                    .then_and_now
                    .iter()
                    .map(|row| row.cells[i].ratio)
                    .collect(),
            })
            .collect(),
    };
    if let Some(png) = then_and_now.png()? {
        let missing: Vec<String> = c
            .then_and_now
            .iter()
            .flat_map(|row| {
                row.cells
                    .iter()
                    .zip(THEN_AND_NOW)
                    .filter(|(cell, _)| cell.ratio.is_none())
                    .map(|(cell, (_, name))| {
                        format!("{name} on {}: {}", row.machine, then_and_now_text(cell))
                    })
                    .collect::<Vec<_>>()
            })
            .collect();
        let mut caption = "The frame time of each section's compute formulation (OpenGL 4.3) \
                           over its classic one (the paper's), per machine."
            .to_string();
        if !missing.is_empty() {
            caption += &format!(" No point: {}.", missing.join("; "));
        }
        figures.push(Figure {
            group: index,
            file: file(FILES[1], c),
            caption,
            png,
        });
    }
    Ok(figures)
}

impl Chart {
    /// The chart as PNG, or `None` when it has no finite positive value to draw.
    pub fn png(&self) -> anyhow::Result<Option<Vec<u8>>> {
        let values: Vec<f64> = self
            .lines
            .iter()
            .flat_map(|l| l.values.iter().flatten().copied())
            .filter(|v| v.is_finite() && *v > 0.0)
            .collect();
        if values.is_empty() {
            return Ok(None);
        }
        let (lo, hi) = values
            .iter()
            .fold((1.0f64, 1.0f64), |(lo, hi), &v| (lo.min(v), hi.max(v)));
        let (lo, hi) = (
            10f64.powf(lo.log10().floor()),
            10f64.powf(hi.log10().ceil().max(lo.log10().floor() + 1.0)),
        );
        crate::page::plot::register_font();
        let size = (SIZE.0, SIZE.1 + LEGEND_ROW * self.lines.len() as u32 + 12);
        let mut pixels = vec![0u8; (size.0 * size.1 * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
            root.fill(&WHITE).map_err(draw_error)?;
            let (axes, legend) = root.split_vertically(SIZE.1);
            self.draw_axes(&axes, lo, hi)?;
            self.draw_legend(&legend)?;
            root.present().map_err(draw_error)?;
        }
        let image = image::RgbImage::from_raw(size.0, size.1, pixels)
            .context("the chart's pixels do not fill its size")?;
        let rgba = image::DynamicImage::ImageRgb8(image).to_rgba8();
        crate::files::encode_png(rgba.as_raw(), size.0, size.1).map(Some)
    }

    fn draw_axes(
        &self,
        area: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
        lo: f64,
        hi: f64,
    ) -> anyhow::Result<()> {
        let n = self.x_names.len();
        let mut chart = ChartBuilder::on(area)
            .caption(&self.title, ("sans-serif", 22))
            .margin(14)
            .margin_right(40)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(-0.5f64..n as f64 - 0.5, (lo..hi).log_scale())
            .map_err(draw_error)?;
        let names = self.x_names.clone();
        let x_label = move |v: &f64| {
            let i = v.round();
            if (v - i).abs() < 1e-6 && i >= 0.0 {
                names.get(i as usize).cloned().unwrap_or_default()
            } else {
                String::new()
            }
        };
        chart
            .configure_mesh()
            .x_desc("machine (a column of the table)")
            .y_desc(self.y_label.as_str())
            .label_style(("sans-serif", 15))
            .x_labels(n + 1)
            .x_label_formatter(&x_label)
            .y_label_formatter(&|v| tick(*v))
            .disable_x_mesh()
            .draw()
            .map_err(draw_error)?;
        // 1: break-even, or the paper's own figure.
        chart
            .draw_series(LineSeries::new(
                [(-0.5, 1.0), (n as f64 - 0.5, 1.0)],
                BLACK.mix(0.4).stroke_width(1),
            ))
            .map_err(draw_error)?;
        for (i, line) in self.lines.iter().enumerate() {
            let colour = PALETTE[i % PALETTE.len()];
            let points: Vec<(f64, f64)> = line
                .values
                .iter()
                .enumerate()
                .filter_map(|(x, v)| {
                    v.filter(|v| v.is_finite() && *v > 0.0)
                        .map(|v| (x as f64, v))
                })
                .collect();
            chart
                .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))
                .map_err(draw_error)?;
            let points = points.into_iter();
            match i % 4 {
                0 => chart.draw_series(points.map(|p| Circle::new(p, 5, colour.filled()))),
                1 => chart.draw_series(points.map(|p| TriangleMarker::new(p, 7, colour.filled()))),
                2 => chart.draw_series(points.map(|p| Cross::new(p, 5, colour.stroke_width(3)))),
                _ => chart.draw_series(points.map(|p| Circle::new(p, 5, colour.stroke_width(2)))),
            }
            .map_err(draw_error)?;
        }
        Ok(())
    }

    fn draw_legend(
        &self,
        area: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    ) -> anyhow::Result<()> {
        for (i, line) in self.lines.iter().enumerate() {
            let colour = PALETTE[i % PALETTE.len()];
            let (x, y) = (90, 8 + i as i32 * LEGEND_ROW as i32 + LEGEND_ROW as i32 / 2);
            area.draw(&PathElement::new(
                vec![(x, y), (x + 30, y)],
                colour.stroke_width(2),
            ))
            .map_err(draw_error)?;
            let at = (x + 15, y);
            match i % 4 {
                0 => area.draw(&Circle::new(at, 5, colour.filled())),
                1 => area.draw(&TriangleMarker::new(at, 7, colour.filled())),
                2 => area.draw(&Cross::new(at, 5, colour.stroke_width(3))),
                _ => area.draw(&Circle::new(at, 5, colour.stroke_width(2))),
            }
            .map_err(draw_error)?;
            area.draw(&Text::new(
                line.name.clone(),
                (x + 40, y - 8),
                ("sans-serif", 15).into_font().color(&BLACK),
            ))
            .map_err(draw_error)?;
        }
        Ok(())
    }
}

/// A short axis label.
fn tick(v: f64) -> String {
    if (1e-3..1e5).contains(&v.abs()) {
        let text = format!("{v:.3}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.0e}")
    }
}

fn draw_error<E: std::error::Error + Send + Sync + 'static>(
    e: DrawingAreaErrorKind<E>,
) -> anyhow::Error {
    anyhow::anyhow!("drawing a chart: {e}")
}
