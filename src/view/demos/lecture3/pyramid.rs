//! Technique 1: the max and min pyramids of the shipped height map, every level on one scale,
//! each texel probed against the CPU pyramid.

use crate::gl::picture::{Panel, Scale};
use crate::gl::Context;
use crate::lecture3::height_map::{HeightMap, SHIPPED_SIZE};
use crate::lecture3::pyramid::{cpu_pyramid, Extreme, Level, PyramidBuilder};
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};

pub struct PyramidDemo {
    map: HeightMap,
    /// GPU and CPU levels of the max and the min pyramid.
    pyramids: [(Vec<Level>, Vec<Level>); 2],
}

const NAMES: [&str; 2] = ["max", "min"];

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
            pyramids: [build(Extreme::Max)?, build(Extreme::Min)?],
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
        let k = view.shown % 2;
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
        vec!["max pyramid".into(), "min pyramid".into()]
    }

    fn overlay(&self) -> Vec<String> {
        let equal = self
            .pyramids
            .iter()
            .all(|(g, c)| g.len() == c.len() && g.iter().zip(c).all(|(a, b)| a.values == b.values));
        vec![
            format!(
                "lecture 3, image pyramid of the {}x{} height map: {} levels",
                self.map.width(),
                self.map.height(),
                self.pyramids[0].0.len()
            ),
            format!(
                "GPU max and min pyramids {} the CPU's bit for bit",
                if equal { "equal" } else { "DIFFER from" }
            ),
        ]
    }

    fn timings(&self) -> String {
        String::new()
    }
}
