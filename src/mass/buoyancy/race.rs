//! The GPU solver against the CPU reference solver on the scene of section 5.3, as a ratio
//! of steps per second taken in interleaved pairs: every round runs both solvers from the
//! drop, each on its own copy of the scene, one step of one then the same step of the
//! other, so that a change of load on a shared machine hits both alike. Each round gives
//! one ratio; the rounds give its spread.

use super::batch::GpuSolver;
use super::scene;
use super::simulation::{AnalyticSolver, Simulation, SubmergedSolver};
use crate::gl::Context;
use crate::mass::peel::PeelSettings;
use crate::timing::{Load, Spread};
use serde::Serialize;
use std::time::Instant;

/// What to race.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct RaceSetup {
    pub bodies: usize,
    pub resolution: u32,
    /// Steps of each round, from the drop.
    pub steps: usize,
    pub rounds: usize,
    pub dt: f64,
    /// The linear drag and rotational damping the paper does not model.
    pub extra_damping: bool,
}

/// The ratios of a race.
#[derive(Clone, Debug, Serialize)]
pub struct Race {
    pub setup: RaceSetup,
    /// GPU solver steps/s over the CPU solver's, one per round.
    pub gpu_over_cpu: Spread,
    /// Steps per second over all rounds.
    pub gpu_steps_per_second: f64,
    pub cpu_steps_per_second: f64,
    /// The load average before the first round and after the last.
    pub load_before: Option<Load>,
    pub load_after: Option<Load>,
}

/// A fresh copy of the scene of `setup`.
fn fresh(setup: &RaceSetup) -> Result<Simulation, String> {
    let mut sim = scene::paper_scene(setup.bodies, setup.dt)?;
    if setup.extra_damping {
        sim.water = sim.water.with_extra_damping();
    }
    Ok(sim)
}

/// One step of `sim` with `solver`, timed (ms).
fn timed_step(sim: &mut Simulation, solver: &mut dyn SubmergedSolver) -> Result<f64, String> {
    let start = Instant::now();
    sim.step(solver)?;
    Ok(start.elapsed().as_secs_f64() * 1e3)
}

/// Runs the race: `setup.rounds` rounds of `setup.steps` interleaved steps of each solver.
/// The GPU solver is made (and its programs compiled) once, before the first round.
pub fn run(ctx: &Context, setup: RaceSetup, settings: PeelSettings) -> Result<Race, String> {
    run_after(ctx, setup, settings, Vec::new(), Load::now())
}

/// The GPU and the CPU solver's time (ms) over one round's steps.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Round {
    pub gpu_ms: f64,
    pub cpu_ms: f64,
}

/// A round run beside another run of the GPU solver from the drop (the report's scene,
/// which steps that solver anyway): after each of its first `setup.steps` steps, timed by
/// the caller as [`Simulation::step`] times it, the CPU solver takes the same step on its
/// own copy of the scene, timed here. The caller's solver must have made one step before
/// (compiled and allocated), as [`run`]'s does.
pub struct Beside {
    sim: Simulation,
    steps_left: usize,
    round: Round,
}

impl Beside {
    pub fn new(setup: &RaceSetup) -> Result<Beside, String> {
        Ok(Beside {
            sim: fresh(setup)?,
            steps_left: setup.steps,
            round: Round::default(),
        })
    }

    /// After the caller's GPU step, which took `gpu_ms`: the CPU solver's same step, while
    /// the round lasts.
    pub fn step(&mut self, gpu_ms: f64) -> Result<(), String> {
        if self.steps_left == 0 {
            return Ok(());
        }
        self.steps_left -= 1;
        self.round.gpu_ms += gpu_ms;
        self.round.cpu_ms += timed_step(&mut self.sim, &mut AnalyticSolver)?;
        Ok(())
    }

    /// The round, once every step of it was taken.
    pub fn round(&self) -> Option<Round> {
        (self.steps_left == 0).then_some(self.round)
    }
}

/// The race of `setup` whose first rounds were run already (`done`, beside another run:
/// [`Beside`]), from the load `load_before` of the first: the rounds left are run here.
pub fn run_after(
    ctx: &Context,
    setup: RaceSetup,
    settings: PeelSettings,
    done: Vec<Round>,
    load_before: Option<Load>,
) -> Result<Race, String> {
    if setup.rounds == 0 || setup.steps == 0 {
        return Err("a race needs at least one round of one step".into());
    }
    let mut rounds = done;
    if rounds.len() < setup.rounds {
        let shapes = fresh(&setup)?.shapes;
        let mut gpu = GpuSolver::new(ctx, &shapes, setup.bodies, setup.resolution)
            .map_err(|e| e.to_string())?;
        gpu.set_settings(settings).map_err(|e| e.to_string())?;
        // One step to compile and allocate, untimed.
        fresh(&setup)?.step(&mut gpu)?;
        while rounds.len() < setup.rounds {
            let (mut on_gpu, mut on_cpu) = (fresh(&setup)?, fresh(&setup)?);
            let mut round = Round::default();
            for _ in 0..setup.steps {
                round.gpu_ms += timed_step(&mut on_gpu, &mut gpu)?;
                round.cpu_ms += timed_step(&mut on_cpu, &mut AnalyticSolver)?;
            }
            rounds.push(round);
        }
    }
    let ratios: Vec<f64> = rounds.iter().map(|r| r.cpu_ms / r.gpu_ms).collect();
    let steps = (rounds.len() * setup.steps) as f64;
    let (gpu_total, cpu_total) = rounds
        .iter()
        .fold((0.0, 0.0), |(g, c), r| (g + r.gpu_ms, c + r.cpu_ms));
    Ok(Race {
        setup,
        gpu_over_cpu: Spread::of(&ratios),
        gpu_steps_per_second: 1e3 * steps / gpu_total,
        cpu_steps_per_second: 1e3 * steps / cpu_total,
        load_before,
        load_after: Load::now(),
    })
}

impl Race {
    /// "GPU/CPU steps per second 0.93x (median of 3 rounds, 0.90-0.95), 31.2 vs 33.5
    /// steps/s, load average 1.2 -> 1.4 on 2 cores".
    pub fn in_words(&self) -> String {
        let load = |l: Option<Load>| l.map_or("?".into(), |l| format!("{:.2}", l.one_minute));
        let cores = self.load_after.or(self.load_before).map_or(0, |l| l.cores);
        let r = &self.gpu_over_cpu;
        format!(
            "GPU/CPU steps per second {:.2}x (median of {} rounds of {} steps, {:.2}-{:.2}), \
             {:.1} vs {:.1} steps/s; load average {} -> {} on {cores} cores",
            r.median,
            r.runs,
            self.setup.steps,
            r.min,
            r.max,
            self.gpu_steps_per_second,
            self.cpu_steps_per_second,
            load(self.load_before),
            load(self.load_after),
        )
    }
}
