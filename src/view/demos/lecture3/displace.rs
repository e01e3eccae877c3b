//! Technique 2: pyramidal displacement mapping with the camera orbiting the box: the frame,
//! each pixel's distance to its hit against the exact CPU tracer, the traversal's steps, and
//! the bound pyramid against the CPU's. Keys: `p` switches the minification prefilter on and
//! off (the exact tracer then follows the same rule), `+` / `-` move the camera nearer or
//! farther.

use super::{against, cleared, gpu_beside_cpu, square};
use crate::gl::picture::{Panel, Scale};
use crate::gl::Context;
use crate::lecture3::displacement::bounds::cpu_bound_pyramid;
use crate::lecture3::displacement::{
    exact, prefilter, Camera, DisplacementRenderer, FrameTarget, Method, Pixel, Surface,
};
use crate::lecture3::height_map::{HeightMap, SHIPPED_SIZE};
use crate::lecture3::pyramid::{Extreme, Level};
use crate::view::inset::{self, Probed};
use crate::view::{Canvas, Demo, ViewState};

pub struct DisplaceDemo {
    renderer: DisplacementRenderer,
    target: FrameTarget,
    frame: usize,
    colour: Vec<u8>,
    /// Distance from the eye to the hit (0: no hit), GPU and exact CPU tracer.
    tau: Vec<f32>,
    exact_tau: Vec<f32>,
    iterations: Vec<f32>,
    bounds: Vec<Level>,
    cpu_bounds: Vec<Level>,
    /// The minification prefilter on.
    prefilter: bool,
    /// The camera's distance from the box centre.
    distance: f32,
}

/// Image side (pixels): small, the exact tracer runs every frame.
const SIDE: u32 = 96;
/// The box's depth and the camera's distance and elevation, as the report's orbit.
const DEPTH: f32 = 0.3;
const DISTANCE: f32 = 3.2;
const ELEVATION: f32 = 30.0;
/// The nearest and farthest camera (`+` and `-`).
const MIN_DISTANCE: f32 = 1.5;
const MAX_DISTANCE: f32 = 40.0;
/// Degrees the camera turns per frame.
const TURN: f32 = 6.0;

impl DisplaceDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        let map = HeightMap::generated(SHIPPED_SIZE);
        let renderer = DisplacementRenderer::new(ctx, Surface::new(map, DEPTH)?)?;
        let target = renderer.target(SIDE, SIDE)?;
        let bounds = renderer.bounds().read_levels()?;
        let cpu_bounds = cpu_bound_pyramid(&renderer.surface().map, Extreme::Max);
        Ok(DisplaceDemo {
            renderer,
            target,
            frame: 0,
            colour: Vec::new(),
            tau: Vec::new(),
            exact_tau: Vec::new(),
            iterations: Vec::new(),
            bounds,
            cpu_bounds,
            prefilter: false,
            distance: DISTANCE,
        })
    }

    fn camera(&self) -> Camera {
        Camera::orbit(
            self.renderer.surface().centre(),
            self.distance,
            225.0 + TURN * self.frame as f32,
            ELEVATION,
            SIDE,
            SIDE,
        )
    }
}

impl Demo for DisplaceDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        self.frame += 1;
        let camera = self.camera();
        let method = if self.prefilter {
            Method::Prefiltered
        } else {
            Method::Pyramid
        };
        self.renderer.render(&self.target, &camera, method)?;
        let frame = self.renderer.read(&self.target)?;
        frame.check_finished()?;
        self.colour = frame.colour.clone();
        let pixels = frame.pixels();
        self.tau = pixels
            .iter()
            .map(|p| match p {
                Pixel::Hit { tau, .. } => *tau as f32,
                _ => 0.0,
            })
            .collect();
        self.iterations = pixels
            .iter()
            .map(|p| match p {
                Pixel::Hit { iterations, .. } => *iterations as f32,
                _ => 0.0,
            })
            .collect();
        let surface = self.renderer.surface();
        let exact = if self.prefilter {
            prefilter::trace_image(surface, &camera)
        } else {
            exact::trace_image(surface, &camera, 0.0)
        };
        self.exact_tau = exact
            .iter()
            .map(|h| h.as_ref().map_or(0.0, |h| h.tau as f32))
            .collect();
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        if !cleared(canvas, self.frame)? {
            return Ok(());
        }
        let area = canvas.below_text();
        match view.shown % 4 {
            0 => {
                let placed = inset::draw_rgba(canvas, &self.colour, (SIDE, SIDE), area, "")?;
                if let Some(placement) = placed {
                    canvas.add_probed(Probed {
                        name: "distance to the hit".into(),
                        placement,
                        values: self.tau.clone(),
                        reference: Some(self.exact_tau.clone()),
                    });
                }
            }
            1 => {
                let shown = gpu_beside_cpu(
                    SIDE,
                    ("GPU distance to the hit (0: none)", &self.tau),
                    ("exact CPU tracer's distance", &self.exact_tau),
                );
                inset::draw_picture(canvas, shown, area)?;
            }
            2 => {
                let scale = Scale::of([self.iterations.as_slice()]);
                let steps = square("traversal steps per pixel", &self.iterations, SIDE, scale);
                inset::draw_picture(canvas, vec![steps.into()], area)?;
            }
            _ => {
                let scale = Scale::of(self.bounds.iter().map(|l| l.values.as_slice()));
                let shown = self
                    .bounds
                    .iter()
                    .zip(&self.cpu_bounds)
                    .enumerate()
                    .map(|(i, (g, c))| {
                        let level = Panel {
                            title: format!("bound level {i} ({}x{})", g.width, g.height),
                            values: g.values.clone(),
                            width: g.width,
                            height: g.height,
                            scale,
                        };
                        against(level, &c.values)
                    })
                    .collect();
                inset::draw_picture(canvas, shown, area)?;
            }
        }
        Ok(())
    }

    fn buffers(&self) -> Vec<String> {
        vec![
            "frame".into(),
            "distance to the hit".into(),
            "traversal steps".into(),
            "max bound pyramid".into(),
        ]
    }

    fn overlay(&self) -> Vec<String> {
        let hits = self.tau.iter().filter(|&&t| t > 0.0).count();
        let missed = self
            .tau
            .iter()
            .zip(&self.exact_tau)
            .filter(|(g, c)| (**g > 0.0) != (**c > 0.0))
            .count();
        vec![
            format!(
                "lecture 3, pyramidal displacement mapping: {SIDE}x{SIDE}, azimuth {} deg, \
                 distance {:.1}, prefilter {}",
                (225.0 + TURN * self.frame as f32) % 360.0,
                self.distance,
                if self.prefilter { "on" } else { "off" }
            ),
            format!("{hits} pixels hit; hit or miss unlike the exact tracer: {missed}"),
        ]
    }

    fn timings(&self) -> String {
        String::new()
    }

    fn keys(&self) -> Vec<(&'static str, &'static str)> {
        vec![
            ("p", "minification prefilter on / off"),
            ("+", "camera nearer"),
            ("-", "camera farther"),
        ]
    }

    fn key(&mut self, key: &str) -> anyhow::Result<bool> {
        match key {
            "p" => self.prefilter = !self.prefilter,
            "+" | "=" => self.distance = (self.distance / 1.5).max(MIN_DISTANCE),
            "-" => self.distance = (self.distance * 1.5).min(MAX_DISTANCE),
            _ => return Ok(false),
        }
        Ok(true)
    }
}
