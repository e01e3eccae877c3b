//! Technique 1: the max, min and mean pyramids of the shipped height map, every level of one
//! pyramid on one scale, each texel probed against the CPU pyramid.

use crate::gl::picture::{Panel, Scale};
use crate::gl::Context;
use crate::lecture3::height_map::{HeightMap, SHIPPED_SIZE};
use crate::lecture3::pyramid::{cpu_pyramid, Extreme, Level, PyramidBuilder};
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};

pub struct PyramidDemo {
    map: HeightMap,
    /// GPU and CPU levels of the max, the min and the mean pyramid.
    pyramids: [(Vec<Level>, Vec<Level>); 3],
}

const EXTREMES: [Extreme; 3] = [Extreme::Max, Extreme::Min, Extreme::Mean];
const NAMES: [&str; 3] = ["max", "min", "mean"];

impl PyramidDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        let map = HeightMap::generated(SHIPPED_SIZE);
        let builder = PyramidBuilder::new(ctx)?;
        let build = |extreme: Extreme| -> anyhow::Result<(Vec<Level>, Vec<Level>)> {
            let (w, h) = (map.width(), map.height());
            let gpu = builder.from_image(w, h, map.heights(), extreme)?;
            Ok((
                gpu.read_levels()?,
                cpu_pyramid(w, h, map.heights(), extreme),
            ))
        };
        Ok(PyramidDemo {
            pyramids: [
                build(EXTREMES[0])?,
                build(EXTREMES[1])?,
                build(EXTREMES[2])?,
            ],
            map,
        })
    }
}

impl Demo for PyramidDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.0, 0.0, 0.0, 1.0])?;
        let k = view.shown % NAMES.len();
        let (gpu, cpu) = &self.pyramids[k];
        // All levels of one pyramid are one set: one scale.
        let scale = Scale::of(gpu.iter().map(|l| l.values.as_slice()));
        let shown: Vec<Shown> = gpu
            .iter()
            .zip(cpu)
            .enumerate()
            .map(|(i, (g, c))| Shown {
                panel: Panel {
                    title: format!("{} level {i} ({}x{})", NAMES[k], g.width, g.height),
                    values: g.values.clone(),
                    width: g.width,
                    height: g.height,
                    scale,
                },
                probe_values: None,
                reference: Some(c.values.clone()),
            })
            .collect();
        inset::draw_picture(canvas, shown, canvas.below_text())?;
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        NAMES.iter().map(|n| format!("{n} pyramid")).collect()
    }

    fn overlay(&self) -> Vec<String> {
        let agreement: Vec<String> = EXTREMES
            .iter()
            .zip(&self.pyramids)
            .map(|(&extreme, (gpu, cpu))| {
                let error = largest_difference(gpu, cpu);
                match (extreme, error) {
                    (_, None) => format!("{extreme:?}: level sizes DIFFER from the CPU's"),
                    (Extreme::Mean, Some(e)) => format!("mean: within {e:.1e} of the CPU's"),
                    (_, Some(0.0)) => format!("{extreme:?}: the CPU's bit for bit"),
                    (_, Some(e)) => format!("{extreme:?}: DIFFERS from the CPU's by {e:.1e}"),
                }
                .to_lowercase()
            })
            .collect();
        vec![
            format!(
                "lecture 3, image pyramids of the {}x{} height map: {} levels",
                self.map.width(),
                self.map.height(),
                self.pyramids[0].0.len()
            ),
            // Max and min pick a value, so they must equal the CPU's exactly; a mean rounds
            // its sums in a different order.
            format!("GPU against CPU: {}", agreement.join("; ")),
        ]
    }

    fn timings(&self) -> String {
        String::new()
    }
}

/// The largest absolute difference of two pyramids' texels; `None` when their levels differ
/// in number or size.
fn largest_difference(gpu: &[Level], cpu: &[Level]) -> Option<f32> {
    let same_shape = gpu.len() == cpu.len()
        && gpu
            .iter()
            .zip(cpu)
            .all(|(g, c)| (g.width, g.height) == (c.width, c.height));
    same_shape.then(|| {
        gpu.iter()
            .zip(cpu)
            .flat_map(|(g, c)| g.values.iter().zip(&c.values).map(|(a, b)| (a - b).abs()))
            .fold(0.0, f32::max)
    })
}
