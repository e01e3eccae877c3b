//! Technique 7: a histogram by additive blending, one point per value: the values, and the
//! bins against the CPU's counts.

use super::{against, draw_one_of, square};
use crate::gl::picture::{Panel, Scale};
use crate::gl::Context;
use crate::lecture3::blend_histogram::{cpu_histogram, Bins, Histogram, Method, Values};
use crate::lecture3::random_texture::HybridTaus;
use crate::view::{Canvas, Demo, ViewState};

pub struct HistogramDemo {
    values: Vec<f32>,
    bins: Vec<f32>,
    cpu: Vec<f32>,
    outside: usize,
}

const SIDE: u32 = 64;
const BINS: u32 = 32;

impl HistogramDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        // Skewed values (the cube of uniform ones), as `lecture3 histogram` counts.
        let mut g = HybridTaus::seeded(3, 0);
        let values: Vec<f32> = (0..SIDE * SIDE).map(|_| g.next_f32().powi(3)).collect();
        let bins = Bins::new(0.0, 1.0, BINS, ctx.info().limits.max_texture_size)?;
        let histogram = Histogram::new(ctx, bins)?;
        histogram.draw(&Values::new(ctx, &values, None)?, Method::Blend)?;
        let counts = histogram.read()?;
        let (cpu, outside) = cpu_histogram(&values, None, &bins);
        Ok(HistogramDemo {
            values,
            bins: counts,
            cpu: cpu.iter().map(|&c| c as f32).collect(),
            outside,
        })
    }
}

impl Demo for HistogramDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        let bins = Panel {
            title: format!("the {BINS} bins over [0, 1): texel = count (blended points)"),
            values: self.bins.clone(),
            width: BINS,
            height: 1,
            scale: Scale::of([self.bins.as_slice()]),
        };
        let values = square(
            &format!("the {} values counted (one point each)", self.values.len()),
            &self.values,
            SIDE,
            Scale::fixed(0.0, 1.0),
        );
        draw_one_of(canvas, view, [against(bins, &self.cpu), values.into()])
    }

    fn buffers(&self) -> Vec<String> {
        vec!["bins".into(), "values".into()]
    }

    fn overlay(&self) -> Vec<String> {
        vec![
            format!(
                "lecture 3, blend histogram: {} values in {BINS} bins ({} outside)",
                self.values.len(),
                self.outside
            ),
            format!(
                "blended counts {} the CPU's",
                if self.bins == self.cpu {
                    "equal"
                } else {
                    "DIFFER from"
                }
            ),
        ]
    }

    fn timings(&self) -> String {
        String::new()
    }
}
