//! The measurements: every paper object at every resolution against Mirtich's analytic
//! method (Fig. 4-5, Table 1), the 50-body buoyancy scene (section 5.3, Fig. 9), and the peels
//! of a buoyant bunny (Fig. 10).

use super::timed::{QUICK_RUNS, SETTLE_STEPS};
use crate::gl::profile::ProfileRow;
use crate::gl::{profile, Context};
use crate::mass::buoyancy::simulation::{Simulation, SubmergedSolver};
use crate::mass::buoyancy::{batch::GpuSolver, race, render::FrameRenderer, scene};
use crate::mass::gpu::GpuMass;
use crate::mass::peel::{PeelOrder, PeelSettings};
use crate::mass::{analytic, models, surface, MassProperties};
use crate::mesh::Mesh;
use crate::report::BenchOptions;
use crate::timing::{wall_ms, Load, Runs, Spread};
use serde::Serialize;
use std::time::Instant;

/// The folder (under the output folder) of Fig. 10's peel dumps.
pub const FIG10_DIR: &str = "fig10_bunny";

/// Everything the section measures.
#[derive(Clone, Debug, Serialize)]
pub struct Paper4Results {
    pub renderer: String,
    pub quick: bool,
    pub objects: Vec<ObjectRun>,
    /// The machine's load when the paper objects' timings ended (Fig. 5's claims).
    pub objects_load: Option<Load>,
    pub buoyancy: BuoyancyRun,
    /// Peels of the buoyant bunny dumped for Fig. 10 (`fig10_bunny/peel<k>_target0.png`).
    pub fig10_peels: usize,
    /// Classic vs compute vs CPU: the 2007 formulation beside today's compute shaders.
    pub then_and_now: crate::report::then_and_now::ThenAndNow,
    /// The same for the buoyancy step's submerged integrals (section 5.2).
    pub then_and_now_buoyancy: super::then_and_now_buoyancy::BuoyancyThenAndNow,
    /// The two orders of peels and sums, side by side on the bunny at 64x64.
    pub peel_orders: Vec<PeelOrderRun>,
    /// The project's speed targets on llvmpipe, as ratios measured in this run.
    pub targets: SpeedTargets,
    /// Where the time goes, per pass: one bunny at 64x64, and buoyancy steps.
    pub profile_bunny_64: Vec<ProfileRow>,
    pub profile_buoyancy: Vec<ProfileRow>,
}

/// One order of peels and sums ([`PeelOrder`]) on the bunny at 64x64.
#[derive(Clone, Debug, Serialize)]
pub struct PeelOrderRun {
    pub order: PeelOrder,
    pub default: bool,
    /// Median wall clock of one call (ms).
    pub wall_ms: f64,
    /// Largest difference of any of the ten integrals from the running sums', relative to
    /// the largest integral.
    pub max_difference: f64,
    /// Peel textures held at once (three RGBA32F targets each).
    pub peel_target_sets: usize,
}

/// The project's speed targets on llvmpipe: ratios of one run, renderer named in the
/// results.
#[derive(Clone, Debug, Serialize)]
pub struct SpeedTargets {
    /// `mass bunny --resolution 64`: GPU wall clock over Mirtich's analytic time.
    pub mass_bunny_64_gpu_over_analytic: f64,
    /// The same passes with the layer count given in advance (no stopping test: no occlusion
    /// query read between two peels), over Mirtich's time: what the test's waits cost.
    #[serde(default)]
    pub mass_bunny_64_without_stopping_test: f64,
    /// Buoyancy, 50 bodies at 32x32 over the first `buoyancy_steps` steps (drop and
    /// plunge included): GPU solver steps/s over the CPU reference solver's.
    pub buoyancy_gpu_over_cpu: f64,
    pub buoyancy_steps: usize,
    pub buoyancy_gpu_steps_per_second: f64,
    pub buoyancy_cpu_steps_per_second: f64,
    /// Target: at least this.
    pub buoyancy_target: f64,
    /// The ratio's rounds: interleaved pairs of steps, a ratio per round, the load.
    pub buoyancy_race: crate::mass::buoyancy::race::Race,
}

/// One paper object at every resolution.
#[derive(Clone, Debug, Serialize)]
pub struct ObjectRun {
    pub object: String,
    pub vertices: usize,
    pub faces: usize,
    pub closed: bool,
    /// Peels at 32x32 with the object turned 90 degrees about x (the paper's views are not
    /// published; a torus seen edge-on has four layers, face-on two).
    pub peels_turned_90_about_x: usize,
    pub analytic: AnalyticReference,
    /// Median wall clock of Mirtich's method (ms).
    pub analytic_ms: f64,
    /// The runs behind `analytic_ms`.
    pub analytic_runs: Spread,
    pub resolutions: Vec<ResolutionRow>,
    /// Where the GPU wall time meets the analytic time (see `break_even`).
    pub break_even: String,
}

/// The exact mass properties (Mirtich, f64) the errors are measured against.
#[derive(Clone, Debug, Serialize)]
pub struct AnalyticReference {
    pub volume: f64,
    pub inertia: [[f64; 3]; 3],
    /// Eigenvalues of `inertia` (about the centre of mass), ascending.
    pub principal_moments: [f64; 3],
}

/// One resolution of one object.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ResolutionRow {
    pub resolution: u32,
    pub peels: usize,
    pub relative_error: RelativeErrors,
    /// Median GPU time of the passes (timer query).
    pub gpu_ms: f64,
    /// Median wall clock of one call.
    pub gpu_wall_ms: f64,
    /// The runs behind `gpu_wall_ms`.
    pub gpu_wall_runs: Spread,
    /// Relative errors of the three principal moments (eigenvalues of the inertia tensor
    /// about the centre of mass), ascending.
    pub principal_relative_error: [f64; 3],
}

/// Fig. 4's four quantities.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct RelativeErrors {
    pub mass: f64,
    #[serde(rename = "Ixx")]
    pub ixx: f64,
    #[serde(rename = "Iyy")]
    pub iyy: f64,
    #[serde(rename = "Izz")]
    pub izz: f64,
}

impl RelativeErrors {
    /// Mass, Ixx, Iyy, Izz in Fig. 4's order.
    pub fn all(&self) -> [f64; 4] {
        [self.mass, self.ixx, self.iyy, self.izz]
    }
}

/// The 50-body scene of section 5.3.
#[derive(Clone, Debug, Serialize)]
pub struct BuoyancyRun {
    pub bodies: usize,
    pub resolution: u32,
    pub steps: usize,
    pub settle_steps: usize,
    pub mean_step_ms: f64,
    pub steps_per_second: f64,
    /// Frames per second: a step and the drawing of the scene ([`BuoyancyRun::frame_size`]:
    /// every body shaded, its gravity and buoyancy arrows, the water), one step per frame
    /// (dt = 1/60 s): what the paper's 16 frames/s compares with.
    pub frames_per_second: f64,
    pub frame_size: (u32, u32),
    /// Share of the frame time in the buoyancy computation (the paper: over 90%).
    pub buoyancy_share: f64,
    /// Steps whose peeling stopped at the peel limit with fragments left, and the limit.
    pub truncated_steps: usize,
    pub max_peels_limit: usize,
    pub max_peels: usize,
    pub mean_peels: f64,
    /// Steps per second of the CPU reference solver, and of the GPU solver beside it, in the
    /// race's interleaved rounds from the drop ([`SpeedTargets::buoyancy_race`]).
    pub cpu_solver_steps_per_second: f64,
    pub race_gpu_steps_per_second: f64,
    /// Frames per second of each of `RATE_PARTS` (3) consecutive parts of the timed frames:
    /// the runs the interactive-rate claim is judged on.
    pub rate_runs: Spread,
    /// The machine's load when the timed steps ended.
    pub load: Option<Load>,
    /// Median of [`BuoyancyRun::batching_runs`] interleaved runs of each.
    pub batched_ms: f64,
    pub one_body_at_a_time_ms: f64,
    pub batching_runs: usize,
    /// Fig. 9: the scene after the run (file in the output folder).
    pub frame: String,
}

// region: workload resolutions
/// The resolutions of Fig. 4-5.
pub fn resolutions(quick: bool) -> Vec<u32> {
    if quick {
        vec![8, 16, 32, 64, 128]
    } else {
        vec![8, 16, 32, 64, 128, 256, 512]
    }
}
// endregion

pub fn measure(opts: &BenchOptions) -> anyhow::Result<Paper4Results> {
    let bar = opts.progress.add(indicatif::ProgressBar::new(
        models::PAPER_OBJECTS.len() as u64
    ));
    bar.set_message("mass properties, paper objects");
    crate::timing::mark("paper4: start");
    let mut objects = Vec::new();
    for name in models::PAPER_OBJECTS {
        objects.push(measure_object(
            opts.gl,
            name,
            &resolutions(opts.quick),
            opts.runs(QUICK_RUNS),
        )?);
        bar.inc(1);
        crate::timing::mark(&format!("paper4: object {name}"));
    }
    bar.finish_and_clear();
    let objects_load = Load::now();
    // region: workload buoyancy
    // Timed steps of the buoyancy scene after it settles: 2 s of the scene at 60 steps/s,
    // three parts of 40 steps for the rate's runs.
    let steps = if opts.quick { 20 } else { 120 };
    // endregion
    let bunny = models::paper_object("bunny").expect("bunny");
    let peel_orders = peel_orders(opts.gl, &bunny, opts.runs(QUICK_RUNS))?;
    let profile_bunny_64 = profile_bunny(opts.gl, &bunny)?;
    crate::timing::mark("paper4: peel orders, bunny profile");
    let setup = race_setup(opts.quick);
    let mut scene = measure_scene(opts, steps, &setup)?;
    crate::timing::mark("paper4: buoyancy scene");
    let targets = speed_targets(opts, &objects, setup, &scene)?;
    crate::timing::mark("paper4: race");
    // The CPU solver's rate is the race's: it runs that solver on the same scene already.
    scene.run.cpu_solver_steps_per_second = targets.buoyancy_cpu_steps_per_second;
    scene.run.race_gpu_steps_per_second = targets.buoyancy_gpu_steps_per_second;
    let fig10_peels = buoyant_bunny_peels(opts)?;
    let then_and_now = super::then_and_now::measure(opts)?;
    crate::timing::mark("paper4: fig10, then and now");
    let then_and_now_buoyancy =
        super::then_and_now_buoyancy::measure(opts, (!opts.quick).then_some(scene.settled))?;
    crate::timing::mark("paper4: then and now, buoyancy");
    Ok(Paper4Results {
        renderer: opts.gl.info().renderer_line(),
        quick: opts.quick,
        objects,
        objects_load,
        buoyancy: scene.run,
        fig10_peels,
        then_and_now,
        then_and_now_buoyancy,
        peel_orders,
        targets,
        profile_bunny_64,
        profile_buoyancy: scene.profile,
    })
}

/// Both orders of peels and sums on `mesh` at 64x64: time and agreement.
fn peel_orders(ctx: &Context, mesh: &Mesh, runs: Runs) -> anyhow::Result<Vec<PeelOrderRun>> {
    let mut out = Vec::new();
    let mut reference = None;
    for order in [PeelOrder::RunningSums, PeelOrder::KeepLayers] {
        let settings = PeelSettings {
            order,
            ..PeelSettings::default()
        };
        let gpu = GpuMass::with_settings(ctx, 64, settings)?;
        let first = gpu.integrate(mesh, None, None)?;
        let wall_ms = median_ms(runs, || {
            let start = Instant::now();
            gpu.integrate(mesh, None, None)?;
            Ok(start.elapsed().as_secs_f64() * 1e3)
        })?;
        let values = first.integrals.to_array();
        let reference = reference.get_or_insert(values);
        let scale = reference.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let max_difference = values
            .iter()
            .zip(reference.iter())
            .map(|(a, b)| (a - b).abs() / scale)
            .fold(0.0, f64::max);
        out.push(PeelOrderRun {
            order,
            default: order == PeelOrder::default(),
            wall_ms,
            max_difference,
            peel_target_sets: match order {
                PeelOrder::RunningSums => 3,
                PeelOrder::KeepLayers => first.peels + 2,
            },
        });
    }
    Ok(out)
}

/// Where one bunny at 64x64 spends its time, per pass.
fn profile_bunny(ctx: &Context, bunny: &Mesh) -> anyhow::Result<Vec<ProfileRow>> {
    let gpu = GpuMass::new(ctx, 64)?;
    gpu.integrate(bunny, None, None)?;
    profile::start(ctx);
    gpu.integrate(bunny, None, None)?;
    Ok(profile::finish(ctx).map(|t| t.rows).unwrap_or_default())
}

/// The race of the speed targets: the first steps of the 50-body scene (drop and plunge
/// included), the two solvers in interleaved pairs, in rounds.
fn race_setup(quick: bool) -> race::RaceSetup {
    let (steps, rounds) = if quick { (30, 1) } else { (120, 3) };
    race::RaceSetup {
        bodies: 50,
        resolution: 32,
        steps,
        rounds,
        dt: 1.0 / 60.0,
        extra_damping: false,
    }
}

/// The speed targets' ratios: the bunny at 64x64 against Mirtich (from the Fig. 5 rows), and the
/// first steps of the 50-body scene (drop and plunge included), the two solvers in
/// interleaved pairs ([`race`]): the first round is the scene's own run from the drop
/// ([`measure_scene`]), the others are run here.
fn speed_targets(
    opts: &BenchOptions,
    objects: &[ObjectRun],
    setup: race::RaceSetup,
    scene: &SceneRuns,
) -> anyhow::Result<SpeedTargets> {
    let bunny = objects
        .iter()
        .find(|o| o.object == "bunny")
        .expect("the bunny is a paper object");
    let at64 = bunny
        .resolutions
        .iter()
        .find(|r| r.resolution == 64)
        .map(|r| r.gpu_wall_ms / bunny.analytic_ms)
        .ok_or_else(|| anyhow::anyhow!("paper 4: no 64x64 run of the bunny"))?;
    let without_test = without_stopping_test(opts, 64)? / bunny.analytic_ms;
    let steps = setup.steps;
    let race = race::run_after(
        opts.gl,
        setup,
        PeelSettings::default(),
        vec![scene.race_round],
        scene.race_load,
    )
    .map_err(anyhow::Error::msg)?;
    Ok(SpeedTargets {
        mass_bunny_64_gpu_over_analytic: at64,
        mass_bunny_64_without_stopping_test: without_test,
        buoyancy_gpu_over_cpu: race.gpu_over_cpu.median,
        buoyancy_steps: steps,
        buoyancy_gpu_steps_per_second: race.gpu_steps_per_second,
        buoyancy_cpu_steps_per_second: race.cpu_steps_per_second,
        buoyancy_target: 1.0,
        buoyancy_race: race,
    })
}

/// Median wall clock (ms) of the bunny at `resolution` with the layer count of a first run
/// given in advance: the same passes without the stopping test's occlusion queries.
fn without_stopping_test(opts: &BenchOptions, resolution: u32) -> anyhow::Result<f64> {
    let bunny = models::paper_object("bunny").expect("bunny");
    let gpu = GpuMass::new(opts.gl, resolution)?;
    let first = gpu.integrate(&bunny, None, None)?;
    gpu.set_known_layers(Some(first.peels));
    median_ms(opts.runs(QUICK_RUNS), || {
        let start = Instant::now();
        gpu.integrate(&bunny, None, None)?;
        Ok(start.elapsed().as_secs_f64() * 1e3)
    })
}

/// Median of the timings (ms) of `work`, run as `runs` says.
fn median_ms(runs: Runs, mut work: impl FnMut() -> anyhow::Result<f64>) -> anyhow::Result<f64> {
    Ok(Spread::of(&runs.run(|_| work())?).median)
}

/// Fig. 4 and 5 for one object at every resolution.
fn measure_object(
    ctx: &Context,
    name: &str,
    resolutions: &[u32],
    runs: Runs,
) -> anyhow::Result<ObjectRun> {
    let mesh = models::paper_object(name).expect("a paper object");
    let exact = MassProperties::from_integrals(&analytic::volume_integrals(&mesh), 1.0);
    // Mirtich's method takes a millisecond or less: five runs at least.
    let analytic_runs = Runs {
        min: runs.min.max(5),
        max: runs.max.max(5),
        ..runs
    };
    let analytic_spread = wall_ms(analytic_runs, || analytic::volume_integrals(&mesh));
    let analytic_ms = analytic_spread.median;
    let mut rows = Vec::new();
    for &n in resolutions {
        let gpu = GpuMass::new(ctx, n)?;
        let first = gpu.integrate(&mesh, None, None)?;
        let got = MassProperties::from_integrals(&first.integrals, 1.0);
        let [mass, ixx, iyy, izz] = got.relative_errors(&exact);
        let (gp, wp) = (got.principal_moments(), exact.principal_moments());
        let principal_relative_error = std::array::from_fn(|k| ((gp[k] - wp[k]) / wp[k]).abs());
        let mut timer = Vec::new();
        let wall = Spread::of(&runs.run(|_| -> anyhow::Result<f64> {
            let start = Instant::now();
            let r = gpu.integrate(&mesh, None, None)?;
            timer.push(r.gpu_ms);
            Ok(start.elapsed().as_secs_f64() * 1e3)
        })?);
        rows.push(ResolutionRow {
            resolution: n,
            peels: first.peels,
            relative_error: RelativeErrors {
                mass,
                ixx,
                iyy,
                izz,
            },
            gpu_ms: Spread::of(&timer).median,
            gpu_wall_ms: wall.median,
            gpu_wall_runs: wall,
            principal_relative_error,
        });
    }
    let turn = glam::Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
    let turned = Mesh::new(
        mesh.positions.iter().map(|p| turn * *p).collect(),
        mesh.triangles.clone(),
    );
    let turned_peels = GpuMass::new(ctx, 32)?.integrate(&turned, None, None)?.peels;
    Ok(ObjectRun {
        object: name.to_string(),
        vertices: mesh.positions.len(),
        faces: mesh.triangles.len(),
        closed: surface::check(&mesh).is_closed(),
        peels_turned_90_about_x: turned_peels,
        analytic: AnalyticReference {
            volume: exact.volume,
            inertia: exact.inertia_rows(),
            principal_moments: exact.principal_moments().to_array(),
        },
        analytic_ms,
        analytic_runs: analytic_spread,
        break_even: break_even(analytic_ms, &rows),
        resolutions: rows,
    })
}

/// The resolution at which the GPU wall time equals the analytic time (log-log interpolation
/// between measured resolutions), as text.
fn break_even(analytic_ms: f64, rows: &[ResolutionRow]) -> String {
    let t = analytic_ms;
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.resolution as f64, r.gpu_wall_ms))
        .collect();
    if pts.first().is_some_and(|p| p.1 >= t) {
        return format!(
            "GPU slower at every resolution (from {}x{})",
            pts[0].0, pts[0].0
        );
    }
    for w in pts.windows(2) {
        let ((n0, t0), (n1, t1)) = (w[0], w[1]);
        if t0 < t && t1 >= t {
            let f = (t.ln() - t0.ln()) / (t1.ln() - t0.ln());
            let n = (n0.ln() + f * (n1.ln() - n0.ln())).exp();
            return format!("{n:.0}x{n:.0}");
        }
    }
    let last = pts.last().map(|p| p.0).unwrap_or(0.0);
    format!("GPU faster at every resolution (up to {last}x{last})")
}

/// The 50-body scene, run once with the GPU solver from the drop: its timed frames (after
/// the settling steps; each a step and the scene drawn), the per-pass profile and the
/// batching gain come from this run; the CPU solver's rate from the race
/// ([`speed_targets`]), which runs that solver on the same scene.
struct SceneRuns {
    run: BuoyancyRun,
    profile: Vec<ProfileRow>,
    /// The scene when the settling steps ended (the then-and-now table's poses).
    settled: Simulation,
    /// The race's first round ([`race::Beside`]): the first steps of this run, the CPU
    /// solver beside them; and the load when it began.
    race_round: race::Round,
    race_load: Option<Load>,
}

/// Every step of one run: wall clock of the step, of its buoyancy half and of the whole
/// frame (the step and, when drawn, the scene's drawing) (ms), peels.
#[derive(Default)]
struct StepTimes {
    step_ms: Vec<f64>,
    buoyancy_ms: Vec<f64>,
    frame_ms: Vec<f64>,
    peels: Vec<usize>,
}

/// `total` steps of the paper scene with `solver` (`peels` reads its last step's peels),
/// each followed by a drawing of the scene by `draw` when given (one step per frame), then
/// by the CPU solver's same step in the race's round `beside` while it lasts (untimed here).
fn run_scene<S: SubmergedSolver>(
    sim: &mut Simulation,
    solver: &mut S,
    total: usize,
    peels: impl Fn(&S) -> usize,
    draw: Option<&FrameRenderer>,
    beside: &mut race::Beside,
    bar: &indicatif::ProgressBar,
) -> anyhow::Result<StepTimes> {
    let mut times = StepTimes::default();
    for _ in 0..total {
        let start = Instant::now();
        let subs = solver
            .submerged(&sim.shapes, &sim.bodies, &sim.water)
            .map_err(anyhow::Error::msg)?;
        times.buoyancy_ms.push(start.elapsed().as_secs_f64() * 1e3);
        sim.apply(&subs);
        times.step_ms.push(start.elapsed().as_secs_f64() * 1e3);
        if let Some(renderer) = draw {
            renderer.draw_frame(sim)?;
        }
        times.frame_ms.push(start.elapsed().as_secs_f64() * 1e3);
        times.peels.push(peels(solver));
        let step_ms = *times.step_ms.last().expect("pushed above");
        beside.step(step_ms).map_err(anyhow::Error::msg)?;
        bar.inc(1);
    }
    Ok(times)
}

/// The size of the frames drawn in the timed run (the CLI's `--png-every` frames).
pub const FRAME_SIZE: (u32, u32) = (640, 400);

/// The buoyancy scene: mean step time, the buoyancy share, peels, against the CPU solver;
/// the race's first round (`setup`) runs beside its first steps.
fn measure_scene(
    opts: &BenchOptions,
    steps: usize,
    setup: &race::RaceSetup,
) -> anyhow::Result<SceneRuns> {
    let ctx = opts.gl;
    // The bodies start in the air; time them once they are in the water (after 1 s, past
    // the first plunge), as the paper's average over its interactive run would.
    let settle = SETTLE_STEPS;
    let total = settle + steps;
    let bar = opts.progress.add(indicatif::ProgressBar::new(total as u64));
    bar.set_message("buoyancy, 50 bodies");
    let mut sim = scene::paper_scene(50, 1.0 / 60.0).map_err(anyhow::Error::msg)?;
    let mut solver = GpuSolver::new(ctx, &sim.shapes, sim.bodies.len(), 32)?;
    let renderer = FrameRenderer::new(ctx, &sim.shapes, FRAME_SIZE.0, FRAME_SIZE.1)?;
    // One step of another copy compiles and allocates, untimed (as the race's solver does),
    // so that the race's round timed beside this run counts steps only.
    scene::paper_scene(50, 1.0 / 60.0)
        .map_err(anyhow::Error::msg)?
        .step(&mut solver)
        .map_err(anyhow::Error::msg)?;
    let race_load = Load::now();
    let mut beside = race::Beside::new(setup).map_err(anyhow::Error::msg)?;
    // The settling steps are not timed as frames, so not drawn either; one drawing warms the
    // renderer.
    let s = |s: &GpuSolver| s.last_peels;
    run_scene(&mut sim, &mut solver, settle, s, None, &mut beside, &bar)?;
    let settled = sim.clone();
    renderer.draw_frame(&sim)?;
    let gpu = run_scene(
        &mut sim,
        &mut solver,
        steps,
        s,
        Some(&renderer),
        &mut beside,
        &bar,
    )?;
    let race_round = beside.round().ok_or_else(|| {
        anyhow::anyhow!(
            "paper 4: the race's round of {} steps is longer than the scene's run of {}",
            setup.steps,
            settle + steps
        )
    })?;
    let load = Load::now();
    bar.finish_and_clear();
    // Ten more steps, profiled per pass, of the bodies now in the water.
    profile::start(ctx);
    for _ in 0..10 {
        sim.step(&mut solver).map_err(anyhow::Error::msg)?;
    }
    let profile = profile::finish(ctx).map(|t| t.rows).unwrap_or_default();
    let timed = |v: &[f64]| v.iter().sum::<f64>();
    let total_ms = timed(&gpu.step_ms);
    let frames_ms = timed(&gpu.frame_ms);
    let batching = batching_gain(ctx, &sim, &mut solver, opts.runs(5))?;
    let frame = "buoyancy_frame.png";
    FrameRenderer::new(ctx, &sim.shapes, 800, 500)?.write_png(&sim, &opts.out_dir.join(frame))?;
    let peels = &gpu.peels;
    let run = BuoyancyRun {
        bodies: sim.bodies.len(),
        resolution: 32,
        steps,
        settle_steps: settle,
        mean_step_ms: total_ms / steps as f64,
        steps_per_second: 1e3 * steps as f64 / total_ms,
        frames_per_second: 1e3 * steps as f64 / frames_ms,
        frame_size: FRAME_SIZE,
        buoyancy_share: timed(&gpu.buoyancy_ms) / frames_ms,
        truncated_steps: solver.truncated_steps,
        max_peels_limit: PeelSettings::default().max_peels,
        max_peels: peels.iter().copied().max().unwrap_or(0),
        mean_peels: peels.iter().sum::<usize>() as f64 / steps as f64,
        // Set from the race by the caller.
        cpu_solver_steps_per_second: 0.0,
        race_gpu_steps_per_second: 0.0,
        rate_runs: rate_runs(&gpu.frame_ms),
        load,
        batched_ms: batching.batched.median,
        one_body_at_a_time_ms: batching.one_at_a_time.median,
        batching_runs: batching.batched.runs,
        frame: frame.into(),
    };
    Ok(SceneRuns {
        run,
        profile,
        settled,
        race_round,
        race_load,
    })
}

/// How many consecutive parts of the timed steps count as runs of the interactive rate.
pub const RATE_PARTS: usize = 3;

/// Steps per second of each of [`RATE_PARTS`] consecutive parts of `step_ms`.
pub(crate) fn rate_runs(step_ms: &[f64]) -> Spread {
    let part = step_ms.len().div_ceil(RATE_PARTS).max(1);
    let rates: Vec<f64> = step_ms
        .chunks(part)
        .map(|c| 1e3 * c.len() as f64 / c.iter().sum::<f64>())
        .collect();
    Spread::of(&rates)
}

/// Wall clock of the submerged parts of one state, both ways (ms).
struct BatchingGain {
    batched: Spread,
    one_at_a_time: Spread,
}

/// The submerged parts of the scene's current state, all bodies as tiles of one target
/// versus one body per round of passes (what batching saves), as often as `runs` says.
fn batching_gain(
    ctx: &Context,
    sim: &Simulation,
    batched: &mut GpuSolver,
    runs: Runs,
) -> anyhow::Result<BatchingGain> {
    let mut single = GpuSolver::new(ctx, &sim.shapes, 1, 32)?;
    // Interleaved, so that a change of load on a shared machine hits both alike.
    let pairs = runs.run(|_| -> anyhow::Result<(f64, f64)> {
        let start = Instant::now();
        batched
            .submerged(&sim.shapes, &sim.bodies, &sim.water)
            .map_err(anyhow::Error::msg)?;
        let batched_ms = start.elapsed().as_secs_f64() * 1e3;
        let start = Instant::now();
        for body in &sim.bodies {
            single
                .submerged(&sim.shapes, std::slice::from_ref(body), &sim.water)
                .map_err(anyhow::Error::msg)?;
        }
        Ok((batched_ms, start.elapsed().as_secs_f64() * 1e3))
    })?;
    let (batched, single): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
    Ok(BatchingGain {
        batched: Spread::of(&batched),
        one_at_a_time: Spread::of(&single),
    })
}

/// Fig. 10: the integrands of each peel of a buoyant bunny (the part below the water when the
/// water line passes through its centre of mass), dumped at 128x128; returns the peel count.
fn buoyant_bunny_peels(opts: &BenchOptions) -> anyhow::Result<usize> {
    let bunny = models::paper_object("bunny").expect("bunny");
    let centre =
        MassProperties::from_integrals(&analytic::volume_integrals(&bunny), 1.0).center_of_mass;
    let dump_dir = opts.out_dir.join(FIG10_DIR);
    Ok(GpuMass::new(opts.gl, 128)?
        .integrate(&bunny, Some(centre.z), Some(&dump_dir))?
        .peels)
}
