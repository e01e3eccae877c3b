//! Feedback that points at the mistake: a check made texel by texel (or pixel, block, work
//! group, list slot: whatever one cell of the checked grid is) keeps how many values are
//! beyond its tolerance, the first few of them (cell, channel, the GPU's value and the CPU's),
//! and the difference GPU - CPU as a buffer, written as a picture with its colour key beside
//! the pass pictures when the check fails.

use super::{Check, LessonRun, PassBuffer};
use serde::Serialize;

/// How many wrong values a failed check keeps to show.
pub const FIRST_WRONG: usize = 5;

/// One value where the GPU and the CPU disagree by more than the check's tolerance.
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct WrongTexel {
    /// The texel: x from the left, y from the bottom (as GL numbers rows).
    pub x: u32,
    pub y: u32,
    pub channel: usize,
    /// What the GPU wrote there.
    pub gpu: f32,
    /// What the CPU reference computes there.
    pub cpu: f32,
}

/// A grid's size: cells across, cells up, values per cell; and what a cell is.
#[derive(Clone, Copy, Debug)]
pub struct Grid {
    pub width: u32,
    pub height: u32,
    pub channels: usize,
    /// What one cell is, for the feedback's words: "texel" unless [`Grid::of`] says.
    pub unit: &'static str,
}

impl Grid {
    pub fn new(width: u32, height: u32, channels: usize) -> Grid {
        Grid {
            width,
            height,
            channels,
            unit: "texel",
        }
    }

    /// The same grid, its cells called `unit` ("pixel", "block", "work group", "slot").
    pub fn of(self, unit: &'static str) -> Grid {
        Grid { unit, ..self }
    }
}

/// Whether `gpu` misses `cpu` by more than `tolerance` (a value that is not finite always does).
fn wrong(gpu: f32, cpu: f32, tolerance: f64) -> bool {
    let d = (gpu as f64 - cpu as f64).abs();
    !d.is_finite() || d > tolerance
}

/// How many of `grid`'s values `gpu` gets wrong against `cpu` (beyond `tolerance`), and the
/// first [`FIRST_WRONG`] of them, row by row from the bottom.
pub fn wrong_texels(
    grid: Grid,
    gpu: &[f32],
    cpu: &[f32],
    tolerance: f64,
) -> (usize, Vec<WrongTexel>) {
    let mut first = Vec::new();
    let mut count = 0;
    for (k, (&g, &c)) in gpu.iter().zip(cpu).enumerate() {
        if !wrong(g, c, tolerance) {
            continue;
        }
        count += 1;
        if first.len() < FIRST_WRONG {
            let texel = (k / grid.channels) as u32;
            first.push(WrongTexel {
                x: texel % grid.width,
                y: texel / grid.width,
                channel: k % grid.channels,
                gpu: g,
                cpu: c,
            });
        }
    }
    (count, first)
}

impl LessonRun {
    /// Record a comparison made texel by texel: `gpu` and `cpu` hold `grid`'s values, rows
    /// from the bottom. Passes when every value is within `tolerance`; a failure keeps the
    /// count of wrong values, the first [`FIRST_WRONG`] of them, and the difference picture's
    /// buffer.
    pub fn check_texels(
        &mut self,
        what: &str,
        grid: Grid,
        gpu: &[f32],
        cpu: &[f32],
        tolerance: f64,
    ) {
        self.check(what, super::max_difference(gpu, cpu), tolerance);
        let check = self.checks.last_mut().expect("just recorded");
        check.unit = grid.unit;
        let expected = (grid.width * grid.height) as usize * grid.channels;
        if gpu.len() != expected || cpu.len() != expected {
            return;
        }
        let (count, first) = wrong_texels(grid, gpu, cpu, tolerance);
        check.wrong = Some(count);
        check.first_wrong = first;
        // The buffer the learner can look at: the last one a pass recorded with these values.
        check.buffer = self.buffers.iter().rposition(|b| b.values == gpu);
        if count > 0 {
            let difference: Vec<f32> = gpu.iter().zip(cpu).map(|(&g, &c)| g - c).collect();
            check.difference = Some(PassBuffer::floats(
                grid.width,
                grid.height,
                grid.channels,
                difference,
            ));
        }
    }

    /// The file name of check `k`'s difference picture.
    pub fn difference_file(k: usize) -> String {
        format!("check-{k}-difference.png")
    }
}

impl Check {
    /// Its difference GPU - CPU as picture panels, one per channel, each on its own signed
    /// scale (zero, a value where both agree, is the neutral colour).
    pub fn difference_panels(&self) -> Vec<crate::gl::picture::Panel> {
        use crate::gl::picture::{Panel, Scale};
        let Some(d) = &self.difference else {
            return Vec::new();
        };
        (0..d.channels)
            .map(|c| {
                let values: Vec<f32> = d
                    .values
                    .iter()
                    .skip(c)
                    .step_by(d.channels)
                    .copied()
                    .collect();
                let title = if d.channels == 1 {
                    "GPU - CPU".to_string()
                } else {
                    format!("GPU - CPU, channel {c}")
                };
                let scale = Scale::of([values.as_slice()]);
                Panel::channel(title, &d.values, d.channels, c, (d.width, d.height), scale)
            })
            .collect()
    }

    /// The lines that say where a failed check went wrong: how many values, the first few
    /// with both values.
    pub fn where_wrong(&self) -> Vec<String> {
        let Some(count) = self.wrong.filter(|&n| n > 0) else {
            return Vec::new();
        };
        let total = self
            .difference
            .as_ref()
            .map_or(0, |d| d.values.len())
            .max(count);
        let mut lines = vec![format!(
            "{count} of {total} values are off by more than {:.1e}; the first {}:",
            self.tolerance,
            self.first_wrong.len()
        )];
        // A grid of one row (work groups, list slots) numbers its cells; else (x, y).
        let one_row = self.difference.as_ref().is_some_and(|d| d.height == 1);
        for w in &self.first_wrong {
            let at = if one_row && self.unit != "texel" {
                format!("{} {}", self.unit, w.x)
            } else {
                format!("{} ({}, {})", self.unit, w.x, w.y)
            };
            lines.push(format!(
                "{at} channel {}: the GPU wrote {}, the CPU expects {}",
                w.channel, w.gpu, w.cpu
            ));
        }
        lines
    }
}
