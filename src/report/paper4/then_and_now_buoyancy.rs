//! Then and now for section 5.2: the submerged integrals of every body of the buoyancy scene by
//! the paper's n + 2 passes (a tile per body, water depth, peels below it, the water patch,
//! reductions) beside the compute formulation (every body's triangles clipped against the
//! water plane in one dispatch, a sum per body) and the CPU reference solver (clip + Mirtich),
//! on the same poses, interleaved.

use super::super::then_and_now::{StageRow, ThenAndNow};
use super::super::BenchOptions;
use crate::mass::buoyancy::batch::GpuSolver;
use crate::mass::buoyancy::compute::ComputeSolver;
use crate::mass::buoyancy::forces::Submerged;
use crate::mass::buoyancy::scene;
use crate::mass::buoyancy::simulation::{AnalyticSolver, Simulation, SubmergedSolver};
use crate::timing::{Load, Spread};
use serde::Serialize;
use std::time::Instant;

const VERDICT: &str = "What each needs. Classic (OpenGL 3.3): a 32x32 tile per body in one \
    render target framed by the body's bounding box, the water-depth pass, a peel per depth \
    layer below the water with an occlusion query per body, the water-patch pass over the \
    surfaces that face down, and a reduction of the integrand targets; its answer carries the \
    tile's resolution error. Compute (OpenGL 4.3): the posed triangles in one storage buffer, \
    one dispatch that clips each against the water plane and sums eq. 4's four integrands about \
    an origin on the plane (so the water patch adds nothing and is not drawn), one \
    shared-memory reduction to a sum per body; its answer is exact but for fp32 rounding. The \
    forces and the rigid-body step after either are the same code.";

/// The buoyancy then-and-now: the table's content and the runs its timing claim is judged on.
#[derive(Clone, Debug, Default, Serialize)]
pub struct BuoyancyThenAndNow {
    pub table: ThenAndNow,
    pub classic_runs: Spread,
    pub compute_runs: Spread,
    pub cpu_runs: Spread,
    /// The load when the timed runs ended.
    pub load: Option<Load>,
    /// Largest difference of a body's submerged volume from the CPU solver's, as a fraction
    /// of the body's volume: classic, compute.
    pub classic_volume_error: f64,
    pub compute_volume_error: Option<f64>,
}

impl BuoyancyThenAndNow {
    pub fn table(&self, renderer: &str) -> crate::report::Table {
        if self.table.unavailable.is_some() {
            return self.table.table(renderer);
        }
        self.table
            .table_judged(renderer, &self.classic_runs, &self.compute_runs, self.load)
    }
}

/// The worst submerged-volume difference from `exact`, as a fraction of each body's volume.
fn worst_volume_error(sim: &Simulation, got: &[Submerged], exact: &[Submerged]) -> f64 {
    sim.bodies
        .iter()
        .zip(got.iter().zip(exact))
        .map(|(b, (g, e))| (g.volume - e.volume).abs() / sim.shapes[b.shape].unit.volume)
        .fold(0.0, f64::max)
}

/// Wall clock of one `submerged` call (ms) and its answer.
fn timed(
    solver: &mut dyn SubmergedSolver,
    sim: &Simulation,
) -> anyhow::Result<(f64, Vec<Submerged>)> {
    let start = Instant::now();
    let subs = solver
        .submerged(&sim.shapes, &sim.bodies, &sim.water)
        .map_err(anyhow::Error::msg)?;
    Ok((start.elapsed().as_secs_f64() * 1e3, subs))
}

/// The scene after the drop (its bodies in the water, the plane cutting most), then the
/// three solvers on the same poses, in turn, as the report's runs policy says. `settled` is
/// the 50-body scene after the frame-rate run's settling steps, where it has one (not
/// simulated twice); without it (`--quick`: 10 bodies) the scene settles here.
pub fn measure(
    opts: &BenchOptions,
    settled: Option<Simulation>,
) -> anyhow::Result<BuoyancyThenAndNow> {
    let ctx = opts.gl;
    let runs = opts.runs(super::timed::QUICK_RUNS);
    let (sim, settle) = match settled {
        Some(sim) => (sim, super::timed::SETTLE_STEPS),
        None => {
            let (bodies, settle) = (10, 30);
            let mut sim = scene::paper_scene(bodies, 1.0 / 60.0).map_err(anyhow::Error::msg)?;
            for _ in 0..settle {
                sim.step(&mut AnalyticSolver).map_err(anyhow::Error::msg)?;
            }
            (sim, settle)
        }
    };
    let bodies = sim.bodies.len();
    let mut classic = GpuSolver::new(ctx, &sim.shapes, bodies, 32)?;
    let mut compute = if ctx.has_compute() {
        Some(ComputeSolver::new(ctx)?)
    } else {
        None
    };
    let triangles: usize = sim
        .bodies
        .iter()
        .map(|b| sim.shapes[b.shape].mesh.triangles.len())
        .sum();
    // Untimed first runs (programs compiled, buffers allocated); their answers are compared.
    let (_, exact) = timed(&mut AnalyticSolver, &sim)?;
    let (_, then) = timed(&mut classic, &sim)?;
    let now = match compute.as_mut() {
        Some(c) => Some(timed(c, &sim)?.1),
        None => None,
    };
    let peels = classic.last_peels;
    let (mut classic_ms, mut compute_ms, mut cpu_ms) = (Vec::new(), Vec::new(), Vec::new());
    runs.run(|_| -> anyhow::Result<()> {
        classic_ms.push(timed(&mut classic, &sim)?.0);
        if let Some(c) = compute.as_mut() {
            compute_ms.push(timed(c, &sim)?.0);
        }
        cpu_ms.push(timed(&mut AnalyticSolver, &sim)?.0);
        Ok(())
    })?;
    let load = Load::now();
    let (classic_runs, compute_runs, cpu_runs) = (
        Spread::of(&classic_ms),
        Spread::of(&compute_ms),
        Spread::of(&cpu_ms),
    );
    let classic_volume_error = worst_volume_error(&sim, &then, &exact);
    let compute_volume_error = now.as_ref().map(|n| worst_volume_error(&sim, n, &exact));
    let cut = exact
        .iter()
        .zip(&sim.bodies)
        .filter(|(e, b)| e.volume > 0.0 && e.volume < sim.shapes[b.shape].unit.volume)
        .count();
    let workload = format!(
        "the submerged integrals of the {bodies} bodies of section 5.3 ({triangles} triangles, \
         {cut} cut by the water plane) after {settle} steps from the drop, classic at 32x32 per \
         body ({peels} peels), {}, each solver's whole call (posing, upload, passes, \
         read-back) by wall clock; worst submerged volume against the CPU solver, as a fraction \
         of the body's volume: classic {classic_volume_error:.1e}{}",
        runs.in_words(),
        compute_volume_error.map_or(String::new(), |e| format!(", compute {e:.1e}"))
    );
    let stage = "one step's submerged parts of every body (classic: n + 2 passes in tiles; \
                 compute: one clipping dispatch and reduction; CPU: clip + Mirtich)";
    let some = |s: &Spread| (s.runs > 0).then_some(s.median);
    let stages = vec![StageRow::new(
        stage,
        some(&classic_runs),
        some(&compute_runs),
        some(&cpu_runs),
    )];
    let table = match ctx.require_compute("the compute formulation") {
        Err(e) => ThenAndNow {
            stages,
            ..ThenAndNow::unavailable(workload, e.to_string(), VERDICT)
        },
        _ => ThenAndNow {
            workload,
            unavailable: None,
            stages,
            // Classic within its resolution error (the 32x32 water line), compute within fp32.
            same_answer: Some(
                classic_volume_error < 0.03 && compute_volume_error.is_some_and(|e| e < 1e-4),
            ),
            verdict: VERDICT.into(),
        },
    };
    Ok(BuoyancyThenAndNow {
        table,
        classic_runs,
        compute_runs,
        cpu_runs,
        load,
        classic_volume_error,
        compute_volume_error,
    })
}
