//! Line plots as PNG (plotters), for the papers' figures: one or more series of (x, y)
//! points, optional log axes, a legend below the axes (never over the data). An axis whose
//! values are all whole numbers (frames, counts) is labelled at whole numbers only.

use anyhow::{bail, Context as _};
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// One curve of a plot.
#[derive(Clone, Debug, Default)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

impl Series {
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series {
            name: name.into(),
            points,
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
/// Height of one legend row, px.
const LEGEND_ROW: u32 = 22;
/// Legend entries per row.
const LEGEND_COLUMNS: usize = 2;

/// Rows of the legend below the axes for `series` curves.
fn legend_rows(series: usize) -> u32 {
    series.div_ceil(LEGEND_COLUMNS) as u32
}

/// The whole image: the axes and the legend rows below them (with a margin).
fn image_size(series: usize) -> (u32, u32) {
    let legend = legend_rows(series);
    let margin = if legend > 0 { 12 } else { 0 };
    (SIZE.0, SIZE.1 + legend * LEGEND_ROW + margin)
}

pub(crate) fn register_font() {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // The font is part of the source; a failure here is a bug caught by the plot test.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

impl Plot {
    /// Write the plot to `path` (PNG).
    pub fn write_png(&self, path: &Path) -> anyhow::Result<()> {
        register_font();
        let points: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .filter(|&(x, y)| self.usable(x, y))
            .collect();
        if points.is_empty() {
            bail!("plot '{}' has no finite points to draw", self.title);
        }
        let range = |values: Vec<f64>, log: bool| {
            let (lo, hi) = values
                .iter()
                .fold((f64::MAX, f64::MIN), |(lo, hi), &v| (lo.min(v), hi.max(v)));
            if log {
                let (lo, hi) = (
                    lo.log10().floor(),
                    hi.log10().ceil().max(lo.log10().floor() + 1.0),
                );
                (10f64.powf(lo), 10f64.powf(hi))
            } else if hi > lo {
                let pad = (hi - lo) * 0.05;
                (lo - pad, hi + pad)
            } else {
                (lo - 1.0, hi + 1.0)
            }
        };
        let x = range(points.iter().map(|p| p.0).collect(), self.log_x);
        let y = range(points.iter().map(|p| p.1).collect(), self.log_y);
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        }
        // Drawn into a buffer and written with `image`, so plotters needs no PNG encoder of its own.
        let size = image_size(self.series.len());
        let whole_x = !self.log_x && points.iter().all(|p| p.0.fract() == 0.0);
        let mut pixels = vec![0u8; (size.0 * size.1 * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
            root.fill(&WHITE)?;
            let (axes, legend) = root.split_vertically(SIZE.1);
            match (self.log_x, self.log_y) {
                (false, false) => self.draw(&axes, x.0..x.1, y.0..y.1, whole_x),
                (true, false) => self.draw(&axes, (x.0..x.1).log_scale(), y.0..y.1, false),
                (false, true) => self.draw(&axes, x.0..x.1, (y.0..y.1).log_scale(), whole_x),
                (true, true) => {
                    self.draw(&axes, (x.0..x.1).log_scale(), (y.0..y.1).log_scale(), false)
                }
            }
            .with_context(|| format!("drawing {}", path.display()))?;
            self.draw_legend(&legend)
                .with_context(|| format!("drawing {}", path.display()))?;
            root.present()
                .with_context(|| format!("drawing {}", path.display()))?;
        }
        let image = image::RgbImage::from_raw(size.0, size.1, pixels)
            .context("the plot's pixels do not fill its size")?;
        crate::files::write_image(path, &image::DynamicImage::ImageRgb8(image))
    }

    /// The legend in its own strip below the axes: a line and name per curve, in
    /// [`LEGEND_COLUMNS`] columns.
    fn draw_legend(
        &self,
        area: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
    ) -> anyhow::Result<()> {
        let column_width = (SIZE.0 as i32 - 100) / LEGEND_COLUMNS as i32;
        for (i, series) in self.series.iter().enumerate() {
            let colour = Palette99::pick(i).to_rgba();
            let x = 80 + (i % LEGEND_COLUMNS) as i32 * column_width;
            let y = 6 + (i / LEGEND_COLUMNS) as i32 * LEGEND_ROW as i32 + LEGEND_ROW as i32 / 2;
            area.draw(&PathElement::new(
                vec![(x, y), (x + 24, y)],
                colour.stroke_width(2),
            ))
            .map_err(|e| anyhow::anyhow!("{e}"))?;
            area.draw(&Circle::new((x + 12, y), 3, colour.filled()))
                .map_err(|e| anyhow::anyhow!("{e}"))?;
            area.draw(&Text::new(
                series.name.clone(),
                (x + 32, y - 8),
                ("sans-serif", 14).into_font().color(&BLACK),
            ))
            .map_err(|e| anyhow::anyhow!("{e}"))?;
        }
        Ok(())
    }

    fn usable(&self, x: f64, y: f64) -> bool {
        x.is_finite() && y.is_finite() && (!self.log_x || x > 0.0) && (!self.log_y || y > 0.0)
    }

    fn draw<X, Y>(
        &self,
        root: &DrawingArea<BitMapBackend, plotters::coord::Shift>,
        x: X,
        y: Y,
        whole_x: bool,
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
            .map_err(|e| anyhow::anyhow!("{e}"))?;
        let x_ticks = if whole_x {
            self.x_span()
                .map_or(10, |span| (span as usize + 1).clamp(2, 10))
        } else {
            10
        };
        let x_label = |v: &f64| {
            if whole_x && v.fract() != 0.0 {
                String::new()
            } else {
                tick_label(*v)
            }
        };
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style(("sans-serif", 14))
            .x_labels(x_ticks)
            .x_label_formatter(&x_label)
            .y_label_formatter(&|v| tick_label(*v))
            .draw()
            .map_err(|e| anyhow::anyhow!("{e}"))?;
        for (i, series) in self.series.iter().enumerate() {
            let colour = Palette99::pick(i).to_rgba();
            let points: Vec<(f64, f64)> = series
                .points
                .iter()
                .copied()
                .filter(|&(x, y)| self.usable(x, y))
                .collect();
            chart
                .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))
                .map_err(|e| anyhow::anyhow!("{e}"))?;
            chart
                .draw_series(
                    points
                        .into_iter()
                        .map(|p| Circle::new(p, 3, colour.filled())),
                )
                .map_err(|e| anyhow::anyhow!("{e}"))?;
        }
        Ok(())
    }

    /// The largest x minus the smallest, over the drawable points.
    fn x_span(&self) -> Option<f64> {
        let xs = self
            .series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|&&(x, y)| self.usable(x, y))
            .map(|p| p.0);
        let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
        (hi >= lo).then_some(hi - lo)
    }
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
    fn whole_number_axes_span_and_legend_rows() {
        let plot = Plot {
            series: vec![Series::new("frames", vec![(1.0, 3.0), (2.0, 4.0)])],
            ..Plot::default()
        };
        assert_eq!(plot.x_span(), Some(1.0));
        assert_eq!(legend_rows(0), 0);
        assert_eq!(legend_rows(3), 2);
        assert_eq!(image_size(0), SIZE);
    }

    #[test]
    fn writes_a_png_with_log_axes() {
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
                Series::new("b", vec![(1.0, 2.0), (100.0, 0.0)]), // 0 is dropped on a log axis
            ],
        };
        plot.write_png(&path).unwrap();
        let image = image::open(&path).unwrap().to_rgb8();
        assert_eq!(image.dimensions(), image_size(2));
        // The legend is below the axes: its rows hold the curves' colours, and the axes'
        // part holds no legend box (the old legend drew a black frame inside the axes).
        let colour = Palette99::pick(0).to_rgba().rgb();
        let legend_has_colour = (SIZE.1..image.height()).any(|y| {
            (0..image.width()).any(|x| image.get_pixel(x, y).0 == [colour.0, colour.1, colour.2])
        });
        assert!(legend_has_colour, "no legend below the axes");
        std::fs::remove_dir_all(dir).ok();
        let empty = Plot {
            title: "empty".into(),
            ..Plot::default()
        };
        assert!(empty.write_png(&path).is_err());
    }
}
