//! Paper 4's section 5 live: bodies floating on still water, the submerged part of each found
//! every step by depth peeling below the water surface (all bodies in one batch of tiles), the
//! peel layers of the batch one key away [Kim et al., Sec. 5].

use super::peels::PeelChoice;
use crate::gl::picture::fixed;
use crate::gl::Context;
use crate::mass::buoyancy::batch::GpuSolver;
use crate::mass::buoyancy::render::{FrameRenderer, Turn};
use crate::mass::buoyancy::scene;
use crate::mass::buoyancy::simulation::Simulation;
use crate::mass::peel::CapturedPeel;
use crate::view::{Canvas, Demo, ViewState};
use std::time::Instant;

pub struct BuoyancyDemo {
    sim: Simulation,
    solver: GpuSolver,
    renderer: FrameRenderer,
    peels: Vec<CapturedPeel>,
    choice: PeelChoice,
    steps: usize,
    step_ms: f64,
}

impl BuoyancyDemo {
    pub fn new(ctx: &Context, bodies: usize, resolution: u32) -> anyhow::Result<Self> {
        if bodies == 0 || bodies > 400 {
            anyhow::bail!("--bodies {bodies}: must be between 1 and 400 in the viewer");
        }
        if !(4..=128).contains(&resolution) {
            anyhow::bail!("--resolution {resolution}: must be between 4 and 128 in the viewer");
        }
        let sim = scene::paper_scene(bodies, 1.0 / 60.0).map_err(anyhow::Error::msg)?;
        // All ten integrands, so that the insets can show every channel of each peel (Fig. 10).
        let solver = GpuSolver::with_integrands(
            ctx,
            &sim.shapes,
            sim.bodies.len(),
            resolution,
            crate::mass::integrands::Integrands::All,
        )?;
        solver.peeler().set_capture(true);
        let renderer = FrameRenderer::new(ctx, &sim.shapes, 16, 16)?;
        Ok(BuoyancyDemo {
            sim,
            solver,
            renderer,
            peels: Vec::new(),
            choice: PeelChoice::default(),
            steps: 0,
            step_ms: 0.0,
        })
    }
}

impl Demo for BuoyancyDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        let start = Instant::now();
        self.sim
            .step(&mut self.solver)
            .map_err(anyhow::Error::msg)?;
        self.step_ms = start.elapsed().as_secs_f64() * 1e3;
        self.peels = self.solver.peeler().take_captured();
        self.steps += 1;
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        if view.shown == 1 {
            return self.choice.draw_full(canvas, &self.peels);
        }
        let turn = Turn {
            yaw: view.yaw,
            pitch: view.pitch,
            zoom: view.zoom,
        };
        self.renderer.draw(&self.sim, canvas.target(), turn)?;
        self.choice.draw_strip(canvas, &self.peels)
    }

    fn buffers(&self) -> Vec<String> {
        vec!["bodies".into(), "peel layers (all bodies' tiles)".into()]
    }

    fn overlay(&self) -> Vec<String> {
        let submerged: f64 = self.sim.bodies.iter().map(|b| b.submerged.volume).sum();
        vec![
            format!(
                "buoyancy: {} bodies, step {}, t = {} s",
                self.sim.bodies.len(),
                self.steps,
                fixed(self.sim.time, 2)
            ),
            format!(
                "peels {}  submerged volume {}",
                self.solver.last_peels,
                fixed(submerged, 3)
            ),
            "arrows: blue gravity at the centre of mass (its length the weight),".into(),
            "yellow buoyancy at the centre of buoyancy (length: force / weight x blue's)".into(),
        ]
    }

    fn timings(&self) -> String {
        format!("step {:.1} ms (peel + reduce + integrate)", self.step_ms)
    }

    fn keys(&self) -> Vec<(&'static str, &'static str)> {
        PeelChoice::KEYS.to_vec()
    }

    fn key(&mut self, key: &str) -> anyhow::Result<bool> {
        Ok(self.choice.key(key, &self.peels))
    }
}
