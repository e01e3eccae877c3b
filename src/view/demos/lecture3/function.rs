//! Technique 4: paper 3's sigmoid in a 1D lookup texture: the table's texels against the
//! function, and a pass summing looked-up values per pixel against the CPU's sums of the
//! table's exact interpolation.

use super::to_f32;
use crate::gl::picture::{fixed, Panel, Scale};
use crate::gl::Context;
use crate::lecture3::function_texture::{
    sample_x, Evaluation, Function, FunctionPasses, FunctionTable,
};
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};

pub struct FunctionDemo {
    table: FunctionTable,
    /// The GPU texels of the table, and the function at the same points.
    texels: Vec<f32>,
    exact: Vec<f32>,
    /// The lookup pass's sums per pixel, and the CPU's.
    sums: Vec<f32>,
    cpu_sums: Vec<f32>,
}

const TEXELS: u32 = 32;
const SIDE: u32 = 32;
const PER_PIXEL: u32 = 16;

impl FunctionDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        let function = Function::Sigmoid;
        let table = FunctionTable::new(ctx, function, TEXELS)?;
        let texels = table.texture.download_f32()?;
        let (lo, hi) = function.domain();
        let exact = (0..TEXELS)
            .map(|i| function.exact(lo + (hi - lo) * i as f64 / (TEXELS - 1) as f64) as f32)
            .collect();
        let passes = FunctionPasses::new(ctx, SIDE, SIDE)?;
        passes.run(Evaluation::Lookup(&table), PER_PIXEL)?;
        let sums = passes.read()?;
        let total = passes.total(PER_PIXEL);
        // Pixel p sums samples p K .. p K + K - 1 (rows from the bottom).
        let cpu_sums: Vec<f64> = (0..(SIDE * SIDE) as u64)
            .map(|p| {
                (0..PER_PIXEL as u64)
                    .map(|j| table.interpolate(sample_x(function, p * PER_PIXEL as u64 + j, total)))
                    .sum()
            })
            .collect();
        Ok(FunctionDemo {
            table,
            texels,
            exact,
            sums,
            cpu_sums: to_f32(&cpu_sums),
        })
    }
}

impl Demo for FunctionDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.0, 0.0, 0.0, 1.0])?;
        let shown = if view.shown.is_multiple_of(2) {
            Shown {
                panel: Panel {
                    title: format!(
                        "the 1D table: texel i = {}(x_i), {TEXELS} texels over [-8, 8]",
                        self.table.function.name()
                    ),
                    values: self.texels.clone(),
                    width: TEXELS,
                    height: 1,
                    scale: Scale::fixed(0.0, 1.0),
                },
                probe_values: None,
                reference: Some(self.exact.clone()),
            }
        } else {
            Shown {
                panel: Panel {
                    title: format!("each pixel: the sum of {PER_PIXEL} looked-up values"),
                    values: self.sums.clone(),
                    width: SIDE,
                    height: SIDE,
                    scale: Scale::of([self.sums.as_slice()]),
                },
                probe_values: None,
                reference: Some(self.cpu_sums.clone()),
            }
        };
        inset::draw_picture(canvas, vec![shown], canvas.below_text())?;
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        vec!["lookup table".into(), "looked-up sums".into()]
    }

    fn overlay(&self) -> Vec<String> {
        let worst = self
            .sums
            .iter()
            .zip(&self.cpu_sums)
            .map(|(a, b)| (a - b).abs() as f64)
            .fold(0.0, f64::max);
        vec![
            format!(
                "lecture 3, function texture: {} in {TEXELS} texels",
                self.table.function.name()
            ),
            format!(
                "max |GPU sum - CPU sum| {} over {} pixels",
                fixed(worst, 6),
                SIDE * SIDE
            ),
        ]
    }

    fn timings(&self) -> String {
        String::new()
    }
}
