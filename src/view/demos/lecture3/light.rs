//! Technique 3: indirect light from virtual point lights, gathered per pixel by a quadtree
//! search of their hierarchy: the shaded room, the gathered irradiance (the probe shows the
//! CPU's search of the same hierarchy beside it), and the nodes each pixel visited; the overlay
//! gives the error against the brute-force sum. Keys + and - change the criterion theta, m the
//! use (indirect light, subsurface scattering, environment light), n normal-aware clustering.

use crate::gl::picture::{fixed, Panel, Scale};
use crate::gl::{Context, Rect};
use crate::lecture3::light_hierarchy::clusters::ClusterLevel;
use crate::lecture3::light_hierarchy::light::{brute_force_with, tree_gather_with, Receiver};
use crate::lecture3::light_hierarchy::normal_cone::MIN_COHERENCE;
use crate::lecture3::light_hierarchy::shade::Terms;
use crate::lecture3::light_hierarchy::uses::{base_exposure, default_scene};
use crate::lecture3::light_hierarchy::{Gather, IndirectLighting, LightUse};
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};

pub struct LightDemo {
    lighting: IndirectLighting,
    /// The receivers and the hierarchy, read back (the CPU references use them).
    receivers: Vec<Option<Receiver>>,
    levels: Vec<ClusterLevel>,
    /// Theta in tenths (keys + and -).
    theta: u32,
    /// Normal-aware clustering (key n; indirect light only).
    normal_aware: bool,
    /// The CPU's tree search with the same criterion (0 where no receiver).
    cpu_tree: Vec<[f32; 3]>,
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
        let mut demo = LightDemo::with_use(ctx, LightUse::Indirect)?;
        demo.run()?;
        Ok(demo)
    }

    /// The lighting of `light_use` on its default scene, its brute force on the CPU.
    fn with_use(ctx: &Context, light_use: LightUse) -> anyhow::Result<Self> {
        let lighting =
            IndirectLighting::for_use(ctx, light_use, default_scene(&light_use), VPLS, SIDE, SIDE)?;
        lighting.build_lights()?;
        lighting.draw_receivers()?;
        let receivers = lighting.gbuffer.receivers()?;
        let levels = lighting.clusters.read_atlas_levels()?;
        let kernel = light_use.kernel();
        let brute = receivers
            .iter()
            .map(|r| {
                r.map_or([0.0; 3], |r| {
                    brute_force_with(&r, &levels[0], &kernel)
                        .as_vec3()
                        .to_array()
                })
            })
            .collect();
        Ok(LightDemo {
            lighting,
            receivers,
            levels,
            theta: 5,
            normal_aware: false,
            cpu_tree: Vec::new(),
            shaded: Vec::new(),
            gathered: Vec::new(),
            brute,
        })
    }

    fn gather(&self) -> anyhow::Result<Gather> {
        let coherence = if self.normal_aware {
            MIN_COHERENCE
        } else {
            0.0
        };
        Ok(Gather::normal_aware(self.theta as f32 / 10.0, coherence)?)
    }

    fn run(&mut self) -> anyhow::Result<()> {
        let gather = self.gather()?;
        self.lighting.gather(gather)?;
        self.gathered = self.lighting.gathers.read()?;
        let criterion = gather.criterion().expect("a tree gather");
        let kernel = self.lighting.light_use.kernel();
        self.cpu_tree = self
            .receivers
            .iter()
            .map(|r| {
                r.map_or([0.0; 3], |r| {
                    tree_gather_with(&r, &self.levels, criterion, &kernel)
                        .irradiance
                        .as_vec3()
                        .to_array()
                })
            })
            .collect();
        let light_use = self.lighting.light_use;
        let terms = match light_use {
            LightUse::Indirect => Terms::Both,
            _ => Terms::Indirect,
        };
        self.lighting.shade(terms, base_exposure(&light_use))?;
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
        let cpu = |c: usize| -> Vec<f32> { self.cpu_tree.iter().map(|b| b[c]).collect() };
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
                let refs: Vec<Vec<f32>> = (0..3).map(cpu).collect();
                let scale = Scale::of(values.iter().chain(&refs).map(|v| v.as_slice()));
                let shown = ["red", "green", "blue"]
                    .iter()
                    .zip(values.into_iter().zip(refs))
                    .map(|(name, (v, r))| Shown {
                        panel: Panel {
                            title: format!("{name} (GPU tree; probe: CPU tree)"),
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
            "shaded picture".into(),
            "gathered light".into(),
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
        let light_use = self.lighting.light_use;
        vec![
            format!(
                "lecture 3, light hierarchy, {} [m]: {VPLS}x{VPLS} {}, theta {} [+/-], {} [n]",
                light_use.name(),
                light_use.lights_name(),
                fixed(self.theta as f64 / 10.0, 1),
                if self.normal_aware {
                    "normal-aware clustering"
                } else {
                    "fixed merge"
                }
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
        vec![
            ("+", "theta up 0.1"),
            ("-", "theta down 0.1"),
            ("m", "next use: indirect, sss, environment"),
            ("n", "normal-aware clustering on/off"),
        ]
    }

    fn key(&mut self, key: &str) -> anyhow::Result<bool> {
        match key {
            "+" | "=" => self.theta = (self.theta + 1).min(15),
            "-" => self.theta = self.theta.saturating_sub(1),
            "n" => self.normal_aware = !self.normal_aware,
            "m" => {
                let next = match self.lighting.light_use {
                    LightUse::Indirect => LightUse::subsurface(),
                    LightUse::Subsurface(_) => LightUse::environment(),
                    LightUse::Environment(_) => LightUse::Indirect,
                };
                let ctx = self.lighting.gbuffer.position().context().clone();
                let (theta, normal_aware) = (self.theta, self.normal_aware);
                *self = LightDemo::with_use(&ctx, next)?;
                self.theta = theta;
                self.normal_aware = normal_aware;
            }
            _ => return Ok(false),
        }
        self.run()?;
        Ok(true)
    }
}
