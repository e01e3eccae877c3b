//! Technique 3: indirect light from virtual point lights, gathered per pixel by a quadtree
//! search of their hierarchy: the shaded room, the gathered irradiance against the CPU's
//! brute-force sum over every VPL, and the nodes each pixel visited. Keys + and - change the
//! criterion theta.

use crate::gl::picture::{fixed, Panel, Scale};
use crate::gl::{Context, Rect};
use crate::lecture3::light_hierarchy::gather::MIN_DISTANCE;
use crate::lecture3::light_hierarchy::light::brute_force;
use crate::lecture3::light_hierarchy::shade::Terms;
use crate::lecture3::light_hierarchy::{Gather, IndirectLighting, Scene};
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};

pub struct LightDemo {
    lighting: IndirectLighting,
    /// Theta in tenths (keys + and -).
    theta: u32,
    /// The shaded picture (RGBA8, rows from the bottom).
    shaded: Vec<u8>,
    /// Per pixel: the tree gather's irradiance (r, g, b) and nodes visited.
    gathered: Vec<[f32; 4]>,
    /// The CPU brute-force irradiance (0 where no receiver).
    brute: Vec<[f32; 3]>,
}

const SIDE: u32 = 64;
const VPLS: u32 = 16;

impl LightDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        let lighting = IndirectLighting::new(ctx, Scene::room(), VPLS, SIDE, SIDE)?;
        lighting.build_lights()?;
        lighting.draw_receivers()?;
        let receivers = lighting.gbuffer.receivers()?;
        let levels = lighting.clusters.read_atlas_levels()?;
        let brute = receivers
            .iter()
            .map(|r| {
                r.map_or([0.0; 3], |r| {
                    let e = brute_force(&r, &levels[0], MIN_DISTANCE as f64);
                    [e.x as f32, e.y as f32, e.z as f32]
                })
            })
            .collect();
        let mut demo = LightDemo {
            lighting,
            theta: 5,
            shaded: Vec::new(),
            gathered: Vec::new(),
            brute,
        };
        demo.run()?;
        Ok(demo)
    }

    fn run(&mut self) -> anyhow::Result<()> {
        self.lighting
            .gather(Gather::tree(self.theta as f32 / 10.0)?)?;
        self.gathered = self.lighting.gathers.read()?;
        self.lighting.shade(Terms::Both, 1.5)?;
        self.shaded = self
            .lighting
            .shade
            .target
            .read_u8(0, Rect::sized(SIDE, SIDE))?;
        Ok(())
    }
}

impl Demo for LightDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.0, 0.0, 0.0, 1.0])?;
        let area = canvas.below_text();
        let channel = |c: usize| -> Vec<f32> { self.gathered.iter().map(|g| g[c]).collect() };
        let brute = |c: usize| -> Vec<f32> { self.brute.iter().map(|b| b[c]).collect() };
        match view.shown % 3 {
            0 => {
                let mut rgba = self.shaded.clone();
                for px in rgba.chunks_exact_mut(4) {
                    px[3] = 255;
                }
                inset::draw_rgba(canvas, &rgba, (SIDE, SIDE), area, "")?;
            }
            1 => {
                let values: Vec<Vec<f32>> = (0..3).map(channel).collect();
                let refs: Vec<Vec<f32>> = (0..3).map(brute).collect();
                let scale = Scale::of(values.iter().chain(&refs).map(|v| v.as_slice()));
                let shown = ["red", "green", "blue"]
                    .iter()
                    .zip(values.into_iter().zip(refs))
                    .map(|(name, (v, r))| Shown {
                        panel: Panel {
                            title: format!("irradiance {name} (tree; probe: CPU brute force)"),
                            values: v,
                            width: SIDE,
                            height: SIDE,
                            scale,
                        },
                        probe_values: None,
                        reference: Some(r),
                    })
                    .collect();
                inset::draw_picture(canvas, shown, area)?;
            }
            _ => {
                let nodes = channel(3);
                let shown = Panel {
                    title: "quadtree nodes each pixel visited".into(),
                    scale: Scale::of([nodes.as_slice()]),
                    values: nodes,
                    width: SIDE,
                    height: SIDE,
                };
                inset::draw_picture(canvas, vec![shown.into()], area)?;
            }
        }
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        vec![
            "shaded room".into(),
            "gathered irradiance".into(),
            "nodes visited".into(),
        ]
    }

    fn overlay(&self) -> Vec<String> {
        let (mut err, mut norm) = (0.0f64, 0.0f64);
        for (g, b) in self.gathered.iter().zip(&self.brute) {
            for c in 0..3 {
                err += (g[c] as f64 - b[c] as f64).powi(2);
                norm += (b[c] as f64).powi(2);
            }
        }
        let nodes: f64 = self.gathered.iter().map(|g| g[3] as f64).sum::<f64>()
            / self.gathered.len().max(1) as f64;
        vec![
            format!(
                "lecture 3, light hierarchy: {} VPLs, theta {} [+/-]",
                VPLS * VPLS,
                fixed(self.theta as f64 / 10.0, 1)
            ),
            format!(
                "relative RMS error against the CPU brute force {}, {} nodes per pixel",
                fixed((err / norm.max(1e-30)).sqrt(), 4),
                fixed(nodes, 1)
            ),
        ]
    }

    fn timings(&self) -> String {
        String::new()
    }

    fn keys(&self) -> Vec<(&'static str, &'static str)> {
        vec![("+", "theta up 0.1"), ("-", "theta down 0.1")]
    }

    fn key(&mut self, key: &str) -> anyhow::Result<bool> {
        match key {
            "+" | "=" => self.theta = (self.theta + 1).min(15),
            "-" => self.theta = self.theta.saturating_sub(1),
            _ => return Ok(false),
        }
        self.run()?;
        Ok(true)
    }
}
