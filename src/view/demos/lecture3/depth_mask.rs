//! Technique 6: the expensive shader run only where the mask is active, by the depth test: the
//! mask, and the picture against the CPU's.

use super::{against, draw_one_of, square, to_f32};
use crate::gl::picture::Scale;
use crate::gl::Context;
use crate::lecture3::depth_mask::{self, cpu_picture, DepthMask, MaskShape};
use crate::view::{Canvas, Demo, ViewState};

pub struct DepthMaskDemo {
    passes: DepthMask,
    mask: Vec<f32>,
    picture: Vec<f32>,
    cpu: Vec<f32>,
    fragments: u64,
    active: u64,
    /// The share of active pixels in hundredths (keys + and -).
    fraction: u32,
}

const SIDE: u32 = 64;
const ITERATIONS: u32 = 32;

impl DepthMaskDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        let mask = depth_mask::mask(MaskShape::Blobs, SIDE, SIDE, 1);
        let passes = DepthMask::new(ctx, &mask, SIDE, SIDE)?;
        let mut demo = DepthMaskDemo {
            passes,
            mask,
            picture: Vec::new(),
            cpu: Vec::new(),
            fragments: 0,
            active: 0,
            fraction: 25,
        };
        demo.run()?;
        Ok(demo)
    }

    fn run(&mut self) -> anyhow::Result<()> {
        let fraction = self.fraction as f32 / 100.0;
        self.fragments = self.passes.run_masked(fraction, ITERATIONS)?;
        self.picture = self.passes.read()?;
        let (cpu, active) = cpu_picture(&self.mask, SIDE, SIDE, fraction, ITERATIONS);
        self.cpu = to_f32(&cpu);
        self.active = active;
        Ok(())
    }
}

impl Demo for DepthMaskDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        let picture = square(
            "depth-masked picture: the expensive function where active, 0 elsewhere",
            &self.picture,
            SIDE,
            Scale::of([self.picture.as_slice(), self.cpu.as_slice()]),
        );
        let mask = square(
            &format!(
                "the mask: active where the key < {} (written into the depth buffer)",
                self.fraction as f32 / 100.0
            ),
            &self.mask,
            SIDE,
            Scale::fixed(0.0, 1.0),
        );
        draw_one_of(canvas, view, [against(picture, &self.cpu), mask.into()])
    }

    fn buffers(&self) -> Vec<String> {
        vec!["masked picture".into(), "mask".into()]
    }

    fn overlay(&self) -> Vec<String> {
        vec![
            format!(
                "lecture 3, depth mask: {}% of {SIDE}x{SIDE} pixels active [+/-]",
                self.fraction
            ),
            format!(
                "the expensive shader ran {} times for {} active pixels",
                self.fragments, self.active
            ),
        ]
    }

    fn timings(&self) -> String {
        String::new()
    }

    fn keys(&self) -> Vec<(&'static str, &'static str)> {
        vec![("+", "more active pixels"), ("-", "fewer active pixels")]
    }

    fn key(&mut self, key: &str) -> anyhow::Result<bool> {
        match key {
            "+" | "=" => self.fraction = (self.fraction + 5).min(100),
            "-" => self.fraction = self.fraction.saturating_sub(5),
            _ => return Ok(false),
        }
        self.run()?;
        Ok(true)
    }
}
