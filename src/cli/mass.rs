//! The `mass` and `buoyancy` commands.

use anyhow::{bail, Context as _};
use classic_gpgpu::gl::{profile, Context};
use classic_gpgpu::mass::assemble::MassProperties;
use classic_gpgpu::mass::buoyancy::compute::ComputeSolver;
use classic_gpgpu::mass::buoyancy::simulation::{self, SubmergedSolver};
use classic_gpgpu::mass::buoyancy::{batch::GpuSolver, render, scene};
use classic_gpgpu::mass::compute::ComputeMass;
use classic_gpgpu::mass::framing::Framing;
use classic_gpgpu::mass::gpu::{GpuMass, GpuResult};
use classic_gpgpu::mass::integrands::Integrands;
use classic_gpgpu::mass::peel::{PeelOrder, PeelSettings, DEFAULT_MAX_PEELS};
use classic_gpgpu::mass::{analytic, clip, models, surface};
use classic_gpgpu::page::folder::Staged;
use classic_gpgpu::timing::{Load, Runs, Spread};
use classic_gpgpu::values::{Count, Real, SMALLEST};
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;

/// Mass properties of a model on the GPU [paper 4, sections 2-4], beside Mirtich's
/// analytic method.
#[derive(clap::Args, Debug)]
pub struct MassArgs {
    /// An OBJ file, or one of the paper's objects: cube, sphere, teapot, torus, knot, bunny, pipe.
    pub model: String,
    /// Framebuffer resolution N (N x N); the paper found 32 enough for 5%.
    #[arg(long, default_value_t = 32, value_parser = RESOLUTION.of::<u32>())]
    pub resolution: u32,
    /// Density ρ; mass and inertia scale with it.
    #[arg(long, default_value_t = 1.0, value_parser = DENSITY.of::<f64>())]
    pub density: f64,
    /// Only the part below the horizontal plane z = Z (section 5.2, the submerged part).
    #[arg(long, value_name = "Z", value_parser = HEIGHT.of::<f64>())]
    pub below: Option<f64>,
    /// Write the colour-encoded integrand buffers of each peel here as PNG (Fig. 10), and
    /// each one's exact float values beside it as .npy (numpy, float32, shape [height, width,
    /// 4]; row 0 is the buffer's bottom row, GL's order, so the PNG's top row is the array's
    /// last).
    /// A folder holding files `mass --dump` did not write is refused without --force; a
    /// rerun replaces the files of the earlier dump (its deeper peels too).
    #[arg(long, value_name = "DIR")]
    pub dump: Option<PathBuf>,
    /// Write the --dump files into a folder that holds other files (they are never removed
    /// or replaced).
    #[arg(long, requires = "dump")]
    pub force: bool,
    /// The paper's peeling passes (classic) or one compute pass over the triangles with a
    /// shared-memory reduction (compute, OpenGL 4.3; with --below each triangle is clipped to
    /// the plane in the pass; no --dump).
    #[arg(long, value_enum, default_value_t)]
    pub formulation: super::Formulation,
    #[command(flatten)]
    pub peeling: PeelArgs,
    /// Print a per-pass table (GPU time by timestamp queries, wall time, waits) of one more
    /// run (in the JSON with --json).
    #[arg(long)]
    pub profile: bool,
}

/// How the depth peeling of section 3.2 runs.
#[derive(clap::Args, Debug)]
pub struct PeelArgs {
    /// Stop peeling after this many layers; a warning says when fragments were left.
    #[arg(long, default_value_t = DEFAULT_MAX_PEELS, value_parser = MAX_PEELS.of::<usize>())]
    pub max_peels: usize,
    /// running-sums (default): add each peel into running sums as it is drawn, one
    /// reduction at the end (memory and passes do not grow with the peels). keep-layers:
    /// the paper's order, keep the n peel textures and reduce each (the default with
    /// --period: the period's GPU could not blend 32-bit float targets).
    #[arg(long, value_enum)]
    pub order: Option<Order>,
    #[command(flatten)]
    pub period: super::period::PeriodArg,
}

/// [`PeelOrder`] for clap.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Order {
    RunningSums,
    KeepLayers,
}

impl PeelArgs {
    fn settings(&self) -> anyhow::Result<PeelSettings> {
        if self.max_peels == 0 || self.max_peels > 4096 {
            bail!("--max-peels {}: must be between 1 and 4096", self.max_peels);
        }
        Ok(PeelSettings {
            max_peels: self.max_peels,
            order: match self.order {
                Some(Order::RunningSums) => PeelOrder::RunningSums,
                Some(Order::KeepLayers) => PeelOrder::KeepLayers,
                // The period's way: n layers kept and each reduced, no float blending.
                None if self.period.period => PeelOrder::KeepLayers,
                None => PeelOrder::RunningSums,
            },
        })
    }
}

/// The warning for a peel that stopped at the limit.
fn truncation_warning(max_peels: usize) -> String {
    format!(
        "peeling stopped at the limit of {max_peels} layers with fragments left: the result \
         misses the deeper layers; raise --max-peels"
    )
}

/// The largest framebuffer side the commands accept: ten RGBA32F targets of 2048² are
/// 640 MiB, and the paper stops at 512.
const MAX_RESOLUTION: u32 = 2048;

/// `--resolution` of `mass`, `buoyancy` and their `view` demos (the renderer's texture size
/// is checked too, when it runs).
pub const RESOLUTION: Count = Count::new(
    "a resolution",
    4,
    MAX_RESOLUTION as u64,
    "ten RGBA32F targets of 2048 x 2048 are 640 MiB, and the paper stops at 512",
);

/// `--density`: any positive, finite density (the mass and inertia it gives are checked
/// against fp64's range when computed, with the model's volume).
const DENSITY: Real = Real::new(
    "a density",
    SMALLEST,
    f64::MAX,
    "positive and finite; the mass it gives is checked when computed",
);

/// `--below Z`: a height of the plane, finite.
const HEIGHT: Real = Real::new("a height", -f64::MAX, f64::MAX, "any finite height");

/// `--max-peels`: the depth complexity the peeling follows at most.
const MAX_PEELS: Count = Count::new(
    "a number of peels",
    1,
    4096,
    "each peel is a pass over the model; 4096 layers is more than any model here has",
);

/// `--bodies` of `buoyancy` (and its `view` demo).
pub const BODIES: Count = Count::new(
    "a number of bodies",
    1,
    10_000,
    "each body is a tile of the shared render target and a rigid body stepped each step",
);

/// `--steps` of `buoyancy`: 16 bytes are kept a step, and a step is at least a pass.
const STEPS: Count = Count::in_memory("a number of steps", 1, 16, "step's record").at_most(
    10_000_000,
    "ten million steps take hours at a millisecond a step",
);

/// `--race R`: rounds of --steps steps, each solver in turn.
const ROUNDS: Count = Count::new(
    "a number of rounds",
    1,
    1000,
    "each round runs --steps steps on both solvers",
);

/// `--dt`: the time step of the rigid-body solver.
const DT: Real = Real::new(
    "a time step in seconds",
    1e-9,
    0.1,
    "the paper steps 1/60 s; beyond a tenth the explicit step is not trusted",
);

/// K of `--png-every K DIR`: a frame every K steps.
const PNG_EVERY: Count = Count::new(
    "a step interval K",
    1,
    10_000_000,
    "at most the most steps, ten million",
);

fn check_resolution(ctx: &Context, resolution: u32) -> anyhow::Result<()> {
    let max = ctx.info().limits.max_texture_size.min(MAX_RESOLUTION);
    if resolution < 4 || resolution > max {
        bail!("--resolution {resolution}: must be between 4 and {max}");
    }
    Ok(())
}

/// Every body's tile (`resolution` rounded up to a power of two, for the reduction) in one
/// render target no larger than the context allows (the renderer's, or the period GPU's).
fn check_tiles_fit(ctx: &Context, bodies: usize, resolution: u32) -> anyhow::Result<()> {
    let max = ctx.max_texture_size() as u64;
    let tile = resolution.next_power_of_two() as u64;
    let per_side = max / tile;
    if (bodies as u64) > per_side * per_side {
        let whose = match ctx.period() {
            Some(gpu) => format!("the {}'s (period limit max_texture_size)", gpu.name),
            None => "the renderer's".to_string(),
        };
        bail!(
            "--bodies {bodies} at --resolution {resolution}: every body's {tile}x{tile} tile must \
             fit one render target of at most {max}x{max} texels ({whose}), which holds \
             {} tiles; use fewer --bodies or a lower --resolution",
            per_side * per_side
        );
    }
    Ok(())
}

/// `classic-gpgpu mass`.
pub fn run_mass(args: &MassArgs, ctx: &Context, json_out: bool) -> anyhow::Result<()> {
    args.peeling.period.apply(ctx, 4);
    check_resolution(ctx, args.resolution)?;
    if !(args.density.is_finite() && args.density > 0.0) {
        bail!("--density {}: must be a positive number", args.density);
    }
    if args.below.is_some_and(|z| !z.is_finite()) {
        bail!("--below: must be a finite height");
    }
    if args.formulation == super::Formulation::Compute && args.peeling.order.is_some() {
        bail!(
            "--order orders the depth peels of the classic formulation; the compute formulation \
             does not peel (it sums the integrals over the triangles in one pass): leave out \
             --order or --formulation compute"
        );
    }
    let dump = match &args.dump {
        Some(dir) if args.formulation == super::Formulation::Classic => {
            Some(Staged::begin("--dump", "mass --dump", dir, args.force)?)
        }
        _ => None,
    };
    let mesh = models::load(&args.model).map_err(anyhow::Error::msg)?;
    let report = surface::check(&mesh);
    Framing::fit(&mesh, args.resolution)
        .map_err(|e| anyhow::anyhow!("model '{}': {e}", args.model))?;

    let model = || format!("model '{}'", args.model);
    let (result, timings, profile) = match args.formulation {
        super::Formulation::Classic => {
            let settings = args.peeling.settings()?;
            let gpu = GpuMass::with_settings(ctx, args.resolution, settings)
                .context("setting up the GPU passes")?;
            // The first run compiles llvmpipe's shader variants and allocates on the driver
            // side: untimed (it also writes the dumps), then the report's runs policy.
            let result = gpu
                .integrate(&mesh, args.below, dump.as_ref().map(Staged::path))
                .with_context(model)?;
            if let Some(dump) = dump {
                dump.finish()?;
            }
            let (gpu_runs, wall) =
                timed_runs(|| Ok(gpu.integrate(&mesh, args.below, None)?.gpu_ms))
                    .with_context(model)?;
            let profile = if args.profile {
                profile::start(ctx);
                gpu.integrate(&mesh, args.below, None)?;
                profile::finish(ctx)
            } else {
                None
            };
            let waits = stop_test_waits(ctx, profile.as_ref(), || {
                gpu.integrate(&mesh, args.below, None).map(|_| ())
            })?;
            let known =
                known_layer_runs(&gpu, &mesh, args.below, &result, ctx).with_context(model)?;
            let floor = no_arithmetic_runs(ctx, &gpu, settings, &mesh, args.below, &result)
                .with_context(model)?;
            (
                result,
                (gpu_runs, wall, waits, Some(known), Some(floor)),
                profile,
            )
        }
        super::Formulation::Compute => {
            let (result, (gpu, wall)) = compute_mass(args, ctx, &mesh).with_context(model)?;
            (result, (gpu, wall, None, None, None), None)
        }
    };
    let exact = match args.below {
        Some(z) => analytic::volume_integrals(&clip::below_plane(&mesh, z as f32)),
        None => analytic::volume_integrals(&mesh),
    };
    // Mirtich's method takes a millisecond or less: five runs at least, as the report.
    let analytic_runs = Runs {
        min: 5,
        max: 5.max(Runs::PAPER.max),
        ..Runs::PAPER
    };
    let analytic = Spread::of(&analytic_runs.run(|_| -> anyhow::Result<f64> {
        let start = Instant::now();
        match args.below {
            Some(z) => analytic::volume_integrals(&clip::below_plane(&mesh, z as f32)),
            None => analytic::volume_integrals(&mesh),
        };
        Ok(start.elapsed().as_secs_f64() * 1e3)
    })?);
    let timings = Timings {
        gpu: timings.0,
        gpu_wall: timings.1,
        analytic,
        load: Load::now(),
        stop_test: timings.2,
        known_layers: timings.3,
        no_arithmetic: timings.4,
    };

    let got = MassProperties::from_integrals(&result.integrals, args.density);
    let want = MassProperties::from_integrals(&exact, args.density);
    let finite = |p: &MassProperties| {
        [p.volume, p.mass].iter().all(|v| v.is_finite())
            && p.center_of_mass.is_finite()
            && p.inertia.is_finite()
    };
    if !finite(&got) || !finite(&want) {
        bail!(
            "--density {:e}: model '{}' (volume {:e}) has a mass or inertia beyond the largest \
             number a double holds at this density; give a smaller --density",
            args.density,
            args.model,
            want.volume
        );
    }
    check_underflow(
        args,
        &[
            (&got, MassProperties::from_integrals(&result.integrals, 1.0)),
            (&want, MassProperties::from_integrals(&exact, 1.0)),
        ],
    )?;
    let mut warnings = Vec::new();
    if result.truncated {
        warnings.push(truncation_warning(result.settings.max_peels));
    }
    if !report.is_closed() {
        warnings.push(format!(
            "the mesh is not a closed surface ({}): the GPU result assumes the holes are small; the analytic result is unreliable",
            report.problems()
        ));
    }
    let overlaps = classic_gpgpu::mass::pieces::overlapping_pieces(&mesh, 10);
    if let Some(&(a, b)) = overlaps.first() {
        warnings.push(format!(
            "pieces {a} and {b} of the mesh overlap ({} overlapping pairs found): every result \
             here (GPU and analytic alike, as eq. 4 sums what each piece bounds) is the sum of \
             the pieces, with the space they share counted twice, not the solid they make \
             together; merge the pieces into one closed surface for that",
            overlaps.len()
        ));
    }
    if args.below.is_some() && want.volume == 0.0 {
        warnings.push("nothing of the model lies below the plane".into());
    }
    if got.volume < 0.0 || want.volume < 0.0 {
        warnings.push(
            "the volume is negative: the mesh is inside out (its triangles run clockwise seen from outside); flip them".into(),
        );
    }
    for w in &warnings {
        eprintln!("warning: model '{}': {w}", args.model);
    }
    let output = MassOutput {
        formulation: args.formulation.name(),
        model: &args.model,
        vertices: mesh.positions.len(),
        triangles: mesh.triangles.len(),
        closed: report.is_closed(),
        overlapping_pieces: overlaps,
        renderer: ctx.info().renderer_line(),
        density: args.density,
        below: args.below,
        result: &result,
        got,
        want,
        timings,
        warnings,
        profile,
    };
    if json_out {
        println!("{}", serde_json::to_string_pretty(&output.json())?);
    } else {
        print!("{}", output.text());
    }
    Ok(())
}

/// A table value: fixed point with 6 decimals in 1e-3..1e7, scientific outside (1e38 would
/// otherwise print as 39 digits).
fn number(v: f64) -> String {
    if v == 0.0 || (1e-3..1e7).contains(&v.abs()) {
        classic_gpgpu::gl::picture::fixed(v, 6)
    } else {
        format!("{v:.6e}")
    }
}

/// Refuses a result that underflowed: a mass, or a diagonal moment of inertia, that is zero
/// or subnormal at this density although it is a normal number at density 1 (the model is not
/// empty: only the density made it vanish), as a result beyond a double is refused above.
fn check_underflow(
    args: &MassArgs,
    results: &[(&MassProperties, MassProperties)],
) -> anyhow::Result<()> {
    let lost = |scaled: f64, unscaled: f64| unscaled.is_normal() && !scaled.is_normal();
    let diagonal =
        |p: &MassProperties| [p.inertia.x_axis.x, p.inertia.y_axis.y, p.inertia.z_axis.z];
    for (p, unit) in results {
        let underflows = lost(p.mass, unit.mass)
            || diagonal(p)
                .iter()
                .zip(diagonal(unit))
                .any(|(&m, one)| lost(m, one));
        if underflows {
            bail!(
                "--density {:e}: model '{}' (volume {:e}) has a mass or moment of inertia below \
                 the smallest normal number a double holds at this density (it would print as \
                 0); give a larger --density",
                args.density,
                args.model,
                p.volume
            );
        }
    }
    Ok(())
}

/// `mass --formulation compute`: the integrals summed over triangles in one compute pass.
fn compute_mass(
    args: &MassArgs,
    ctx: &Context,
    mesh: &classic_gpgpu::mesh::Mesh,
) -> anyhow::Result<(GpuResult, (Spread, Spread))> {
    if args.dump.is_some() || args.profile {
        bail!(
            "--dump and --profile need the classic formulation (the compute formulation \
             integrates the bodies in one dispatch: no integrand images, no passes to profile)"
        );
    }
    let compute = ComputeMass::new(ctx).context("setting up the compute pass")?;
    let integrate = || match args.below {
        Some(level) => compute.integrate_below(&[mesh], level),
        None => compute.integrate(&[mesh]),
    };
    let result = integrate()?;
    let timings = timed_runs(|| Ok(integrate()?.gpu_ms))?;
    let framing = Framing::fit(mesh, args.resolution).map_err(anyhow::Error::msg)?;
    Ok((
        GpuResult {
            integrals: result.integrals[0],
            peels: 0,
            truncated: false,
            settings: PeelSettings::default(),
            layers: Vec::new(),
            framing,
            gpu_ms: result.gpu_ms,
        },
        timings,
    ))
}

/// The classic passes again with the layer count of the first run given in advance (no
/// stopping test: no occlusion query is read between two peels), timed as the command's
/// runs: what the passes cost without the test's waits. The result must be the first run's.
fn known_layer_runs(
    gpu: &GpuMass,
    mesh: &classic_gpgpu::mesh::Mesh,
    below: Option<f64>,
    first: &GpuResult,
    ctx: &Context,
) -> anyhow::Result<KnownLayers> {
    gpu.set_known_layers(Some(first.peels));
    let check = gpu.integrate(mesh, below, None);
    let runs = check.and_then(|check| {
        // The same passes in the same order: the same sums but for fp32 rounding.
        let (a, b) = (check.integrals.to_array(), first.integrals.to_array());
        let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let close = a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-6 * scale);
        let same = check.peels == first.peels && close;
        let runs = timed_runs(|| Ok(gpu.integrate(mesh, below, None)?.gpu_ms));
        profile::start_wall_only(ctx);
        let profiled = gpu.integrate(mesh, below, None);
        let table = profile::finish(ctx);
        profiled?;
        Ok((same, runs.map(|r| (r, table))))
    });
    gpu.set_known_layers(None);
    let (same, runs) = runs?;
    anyhow::ensure!(
        same,
        "the passes with the layer count given ({}) did not give the first run's integrals",
        first.peels
    );
    let ((_, runs), table) = runs?;
    Ok(KnownLayers {
        runs,
        wall_ms: table.as_ref().map_or(0.0, |t| t.wall_ms),
        passes: table.as_ref().map(by_pass).unwrap_or_default(),
    })
}

/// How far above the floor of its passes (the same passes with no arithmetic) the command
/// counts its passes as at the floor.
const AT_THE_FLOOR: f64 = 1.3;

/// The passes of `first` with the layer count given in advance, timed (wall clock) in turns
/// with the same passes with the integrands' arithmetic taken out ([`Integrands::Constant`]:
/// the listing's targets written with constants), so that a change of load hits both alike:
/// how far the passes are from their floor on the renderer.
fn no_arithmetic_runs(
    ctx: &Context,
    gpu: &GpuMass,
    settings: PeelSettings,
    mesh: &classic_gpgpu::mesh::Mesh,
    below: Option<f64>,
    first: &GpuResult,
) -> anyhow::Result<NoArithmetic> {
    let mut floor = GpuMass::with_integrands(ctx, first.framing.resolution, Integrands::Constant)
        .context("setting up the passes without the integrands")?;
    floor.set_settings(settings)?;
    floor.set_known_layers(Some(first.peels));
    let untimed = floor.integrate(mesh, below, None)?;
    anyhow::ensure!(
        untimed.peels == first.peels,
        "the passes without the integrands peeled {} layers where the first run peeled {}",
        untimed.peels,
        first.peels
    );
    gpu.set_known_layers(Some(first.peels));
    let wall = |g: &GpuMass| -> anyhow::Result<f64> {
        let start = Instant::now();
        g.integrate(mesh, below, None)?;
        Ok(start.elapsed().as_secs_f64() * 1e3)
    };
    let pairs =
        Runs::PAPER.run(|_| -> anyhow::Result<(f64, f64)> { Ok((wall(gpu)?, wall(&floor)?)) });
    gpu.set_known_layers(None);
    let (with, without): (Vec<f64>, Vec<f64>) = pairs?.into_iter().unzip();
    Ok(NoArithmetic {
        passes: Spread::of(&with),
        floor: Spread::of(&without),
    })
}

/// The passes (with the layer count given in advance) and the same passes with no
/// arithmetic, timed in turns (wall clock).
#[derive(Clone, Debug, serde::Serialize)]
struct NoArithmetic {
    passes: Spread,
    floor: Spread,
}

/// `integrate` (returning its GPU ms) timed as the report times it ([`Runs::PAPER`]: 3
/// runs, up to 5 within a second), after the caller's untimed first run: (GPU ms, wall ms).
fn timed_runs(
    mut integrate: impl FnMut() -> anyhow::Result<f64>,
) -> anyhow::Result<(Spread, Spread)> {
    let mut gpu = Vec::new();
    let wall = Runs::PAPER.run(|_| -> anyhow::Result<f64> {
        let start = Instant::now();
        gpu.push(integrate()?);
        Ok(start.elapsed().as_secs_f64() * 1e3)
    })?;
    Ok((Spread::of(&gpu), Spread::of(&wall)))
}

/// The line that sets the passes' runs (`passes`, wall clock) against the same passes with
/// no arithmetic taken in turns with them (`floor`): within [`AT_THE_FLOOR`] of it, the
/// passes themselves are the time.
fn no_arithmetic_text(peels: usize, passes: &Spread, floor: &Spread) -> String {
    let ratio = passes.median / floor.median.max(f64::MIN_POSITIVE);
    let verdict = if ratio <= AT_THE_FLOOR {
        format!(
            "within {AT_THE_FLOOR}x of them: the integrands' arithmetic is not the time; the \
             peeling passes are (the body drawn once per layer, the peel and water tests of \
             every fragment, three float targets and their accumulation)"
        )
    } else {
        format!(
            "the integrands' arithmetic is {:.0}% of the passes' time",
            100.0 * (1.0 - 1.0 / ratio)
        )
    };
    format!(
        "no arithmetic   the same {peels} peels with the listing's integrands replaced by \
         constants (the same draws, tests, targets and sums: these passes' floor on this \
         renderer), in turns with the passes above: {} against {}; the passes with the \
         integrands take {ratio:.2}x them: {verdict}\n",
        runs_text(floor),
        runs_text(passes)
    )
}

/// "9.812 ms (median of 5 runs, 9.501-10.420)".
fn runs_text(s: &Spread) -> String {
    format!(
        "{:.3} ms (median of {} runs, {:.3}-{:.3})",
        s.median, s.runs, s.min, s.max
    )
}

/// The CLI's timings: medians and spreads of the runs, and the load average they ran at.
struct Timings {
    gpu: Spread,
    gpu_wall: Spread,
    analytic: Spread,
    load: Option<Load>,
    /// Where the classic path's wall time goes beyond the passes themselves.
    stop_test: Option<StopTestWaits>,
    /// The same passes with the layer count given in advance (classic only).
    known_layers: Option<KnownLayers>,
    /// Those passes in turns with the same passes with the integrands' arithmetic taken out:
    /// their floor on this renderer (classic only).
    no_arithmetic: Option<NoArithmetic>,
}

/// The waits of one run for the occlusion-query results that decide whether another layer
/// exists (the paper's stopping test): each drains the renderer before the next peel is
/// issued; the renderer rasterizes the queued passes meanwhile, so the waits are not all
/// lost time: [`KnownLayers`] times the same passes without them.
#[derive(Clone, Debug, serde::Serialize)]
struct StopTestWaits {
    waits: u64,
    wait_ms: f64,
    wall_ms: f64,
    /// The run's wall time by pass ([`by_pass`]).
    passes: Vec<(String, f64)>,
}

/// The outermost rows of a profile (the passes and waits of one run, in order) with their
/// wall time (ms), "mass: " taken off their names.
fn by_pass(table: &profile::ProfileTable) -> Vec<(String, f64)> {
    table
        .rows
        .iter()
        .filter(|r| r.depth == 0)
        .map(|r| {
            let name = r.name.strip_prefix("mass: ").unwrap_or(&r.name);
            (name.to_string(), r.wall_ms)
        })
        .collect()
}

/// "upload 0.34, one peel 4.50, ... ms".
fn by_pass_text(passes: &[(String, f64)]) -> String {
    let parts: Vec<String> = passes
        .iter()
        .map(|(name, ms)| format!("{name} {ms:.2}"))
        .collect();
    format!("{} ms", parts.join(", "))
}

/// The passes with the layer count given in advance: their runs, and one more run by pass.
#[derive(Clone, Debug, serde::Serialize)]
struct KnownLayers {
    runs: Spread,
    wall_ms: f64,
    passes: Vec<(String, f64)>,
}

/// [`StopTestWaits`] from `profiled` (the `--profile` run) or from one more run of `run`
/// profiled for wall time and waits only.
fn stop_test_waits(
    ctx: &Context,
    profiled: Option<&profile::ProfileTable>,
    run: impl FnOnce() -> Result<(), classic_gpgpu::gl::GlError>,
) -> anyhow::Result<Option<StopTestWaits>> {
    let own;
    let table = match profiled {
        Some(t) => t,
        None => {
            profile::start_wall_only(ctx);
            let done = run();
            let table = profile::finish(ctx);
            done?;
            match table {
                Some(t) => {
                    own = t;
                    &own
                }
                None => return Ok(None),
            }
        }
    };
    let rows = table.rows.iter().filter(|r| r.name == "wait: query result");
    let (waits, wait_ms) = rows.fold((0, 0.0), |(n, ms), r| (n + r.calls, ms + r.wall_ms));
    Ok(Some(StopTestWaits {
        waits,
        wait_ms,
        wall_ms: table.wall_ms,
        passes: by_pass(table),
    }))
}

/// The profile table under a heading.
fn profile_text(table: &profile::ProfileTable, what: &str) -> String {
    format!("profile of {what}\n{table}\n")
}

struct MassOutput<'a> {
    formulation: &'static str,
    model: &'a str,
    vertices: usize,
    triangles: usize,
    closed: bool,
    /// Pairs of pieces that overlap (their shared volume is summed twice analytically).
    overlapping_pieces: Vec<(usize, usize)>,
    renderer: String,
    density: f64,
    below: Option<f64>,
    result: &'a GpuResult,
    got: MassProperties,
    want: MassProperties,
    timings: Timings,
    warnings: Vec<String>,
    /// `--profile`: the table of the profiled run.
    profile: Option<profile::ProfileTable>,
}

impl MassOutput<'_> {
    /// The paper's peeling ran (not the compute formulation), so its settings mean something.
    fn classic(&self) -> bool {
        self.formulation == super::Formulation::Classic.name()
    }

    fn json(&self) -> serde_json::Value {
        let f = &self.result.framing;
        json!({
            "formulation": self.formulation,
            "model": self.model,
            "vertices": self.vertices,
            "triangles": self.triangles,
            "closed": self.closed,
            "renderer": self.renderer,
            "resolution": f.resolution,
            "density": self.density,
            "below": self.below,
            "peels": self.result.peels,
            "peeling": self.classic().then(|| json!({
                "max_peels": self.result.settings.max_peels,
                "order": self.result.settings.order,
                "truncated": self.result.truncated,
            })),
            "volume": self.got.volume,
            "mass": self.got.mass,
            "center_of_mass": self.got.center_of_mass.to_array(),
            "inertia": self.got.inertia_rows(),
            "principal_moments": self.got.principal_moments().to_array(),
            "analytic": {
                "volume": self.want.volume,
                "mass": self.want.mass,
                "center_of_mass": self.want.center_of_mass.to_array(),
                "inertia": self.want.inertia_rows(),
                "principal_moments": self.want.principal_moments().to_array(),
                "reliable": self.closed && self.overlapping_pieces.is_empty(),
                "computes": if self.overlapping_pieces.is_empty() {
                    "the solid's integrals"
                } else {
                    "the sum of the pieces' integrals: overlapping space counted once per piece"
                },
                "overlapping_pieces": self.overlapping_pieces,
            },
            "framing": {
                "center": f.center.to_array(),
                "half_width": f.half_width,
                "half_depth": f.half_depth,
                "pixel_size": f.pixel_size(),
            },
            "timings_ms": {
                "gpu": self.timings.gpu.median,
                "gpu_wall": self.timings.gpu_wall.median,
                "analytic": self.timings.analytic.median,
                "runs": {
                    "gpu": self.timings.gpu,
                    "gpu_wall": self.timings.gpu_wall,
                    "analytic": self.timings.analytic,
                },
                "load": self.timings.load,
                "stop_test_waits": self.timings.stop_test,
                "known_layers": self.timings.known_layers,
                "no_arithmetic": self.timings.no_arithmetic,
            },
            "warnings": self.warnings,
            "profile": self.profile,
        })
    }

    fn text(&self) -> String {
        let f = &self.result.framing;
        let c = f.center;
        let mut s = format!(
            "model           {} ({} vertices, {} triangles, {})\nrenderer        {}\n",
            self.model,
            self.vertices,
            self.triangles,
            if self.closed { "closed" } else { "OPEN" },
            self.renderer
        );
        s += &format!(
            "framing         {n}x{n} pixels of {:.4e}, window centred on ({}, {}), half-width {:.4}, depth {} +- {:.4}\n",
            f.pixel_size(),
            classic_gpgpu::gl::picture::fixed(c.x, 4),
            classic_gpgpu::gl::picture::fixed(c.y, 4),
            f.half_width,
            classic_gpgpu::gl::picture::fixed(c.z, 4),
            f.half_depth,
            n = f.resolution
        );
        if let Some(z) = self.below {
            s += &format!("below           z = {z}\n");
        }
        s += &format!("peels           {}\n", self.result.peels);
        s += &format!(
            "{:16}{:>16}{:>16}{:>12}\n",
            "", "GPU", "analytic", "rel. error"
        );
        // Relative errors of values that are ~0 next to their kind's scale (a centre
        // coordinate on a symmetry plane, a vanishing product of inertia) mean nothing.
        let row = |name: &str, g: f64, w: f64, scale: f64| {
            let err = if w.abs() > 1e-3 * scale {
                format!("{:.2e}", ((g - w) / w).abs())
            } else {
                "~0".into()
            };
            format!("{name:16}{:>16}{:>16}{err:>12}\n", number(g), number(w))
        };
        s += &row("volume", self.got.volume, self.want.volume, 0.0);
        s += &row("mass", self.got.mass, self.want.mass, 0.0);
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            s += &row(
                &format!("centre {axis}"),
                self.got.center_of_mass[k],
                self.want.center_of_mass[k],
                f.half_width,
            );
        }
        let (gi, wi) = (self.got.inertia_rows(), self.want.inertia_rows());
        let scale = (0..3).map(|k| wi[k][k].abs()).fold(0.0, f64::max);
        for (r, a) in ["x", "y", "z"].iter().enumerate() {
            for (col, b) in ["x", "y", "z"].iter().enumerate().skip(r) {
                s += &row(&format!("I[{a}{b}]"), gi[r][col], wi[r][col], scale);
            }
        }
        let (gp, wp) = (self.got.principal_moments(), self.want.principal_moments());
        let names = ["I_1 (principal)", "I_2 (principal)", "I_3 (principal)"];
        for (k, name) in names.iter().enumerate() {
            s += &row(name, gp[k], wp[k], 0.0);
        }
        let gpu_clock = if self.classic() {
            "timer query"
        } else {
            "the dispatch to glFinish"
        };
        let t = &self.timings;
        s += &format!("time, GPU       {} by {gpu_clock}\n", runs_text(&t.gpu));
        s += &format!("time, GPU wall  {}\n", runs_text(&t.gpu_wall));
        s += &format!("time, analytic  {}\n", runs_text(&t.analytic));
        s += &format!(
            "timed           after one untimed run; {}\n",
            t.load
                .map_or("load average unknown".into(), |l| l.in_words())
        );
        if self.classic() {
            s += &format!(
                "peeling         {}, at most {} layers\n",
                self.result.settings.order.name(),
                self.result.settings.max_peels
            );
        }
        if let Some(w) = &t.stop_test {
            s += &format!(
                "waits           {:.2} ms of one run's {:.2} ms wall in {} waits for the \
                 occlusion queries that decide whether another layer exists (the paper's \
                 stopping test); a software renderer draws each peel while the command waits \
                 (it rasterizes what is queued when a result or a texture of it is needed), so \
                 they are not all lost time: the next lines time the passes without them\n",
                w.wait_ms, w.wall_ms, w.waits
            );
            s += &format!("  by pass       {}\n", by_pass_text(&w.passes));
        }
        if let Some(k) = &t.known_layers {
            let mirtich = |ms: f64| ms / t.analytic.median.max(f64::MIN_POSITIVE);
            // Decided only where the two runs lie apart, as the report judges timings.
            let (with, without) = (&t.gpu_wall, &k.runs);
            let verdict = if without.max < with.min {
                format!(
                    "the test costs {:.3} ms of the {:.3} ms, the passes themselves the rest",
                    with.median - without.median,
                    with.median
                )
            } else {
                "the runs with and without the test overlap: what the test costs is within \
                 their spread here, the passes themselves are the time"
                    .to_string()
            };
            s += &format!(
                "without test    the same {} peels with their count given in advance (no \
                 stopping test: no occlusion query read between two peels): {}; {:.1}x \
                 Mirtich's time, against {:.1}x with the test: {verdict}\n",
                self.result.peels,
                runs_text(without),
                mirtich(without.median),
                mirtich(with.median),
            );
            s += &format!(
                "  by pass       {} (one run, {:.2} ms wall)\n",
                by_pass_text(&k.passes),
                k.wall_ms
            );
            if let Some(n) = &t.no_arithmetic {
                s += &no_arithmetic_text(self.result.peels, &n.passes, &n.floor);
            }
        }
        if let Some(table) = &self.profile {
            s += &profile_text(table, "one more run");
        }
        for w in &self.warnings {
            s += &format!("warning         {w}\n");
        }
        s
    }
}

/// Hydrostatic buoyancy of rigid bodies on still water [paper 4, section 5].
#[derive(clap::Args, Debug)]
pub struct BuoyancyArgs {
    /// Number of bodies (the paper's scene has 50: spheres, boxes, tori, teapots, bunnies).
    #[arg(long, default_value_t = 50, value_parser = BODIES.of::<usize>())]
    pub bodies: usize,
    /// Simulation steps.
    #[arg(long, default_value_t = 300, value_parser = STEPS.of::<usize>())]
    pub steps: usize,
    /// Per-body framebuffer resolution (the paper's 32).
    #[arg(long, default_value_t = 32, value_parser = RESOLUTION.of::<u32>())]
    pub resolution: u32,
    /// Time step (s).
    #[arg(long, default_value_t = 1.0 / 60.0, value_parser = DT.of::<f64>())]
    pub dt: f64,
    /// Write every K-th frame into DIR as PNG (K from 1 to 10000000). A folder holding files
    /// `buoyancy --png-every` did not write is refused without --force; a rerun replaces the
    /// frames of the earlier one.
    #[arg(long, num_args = 2, value_names = ["K", "DIR"], allow_negative_numbers = true)]
    pub png_every: Option<Vec<String>>,
    /// Write the --png-every frames into a folder that holds other files (they are never
    /// removed or replaced).
    #[arg(long, requires = "png_every")]
    pub force: bool,
    /// Compute the submerged parts on the CPU (clip + Mirtich) instead of the GPU.
    #[arg(long)]
    pub cpu: bool,
    /// The submerged parts by the paper's n + 2 passes (classic) or by one compute pass that
    /// clips every body's triangles against the water plane (compute, OpenGL 4.3); the
    /// forces and the rigid-body step are the same.
    #[arg(long, value_enum, default_value_t)]
    pub formulation: super::Formulation,
    /// Add a linear drag (2/s) and a rotational damping (1/s) to the paper's quadratic drag
    /// (not in the paper: bodies settle in seconds instead of rocking on).
    #[arg(long)]
    pub extra_damping: bool,
    /// Instead of one run: R rounds of --steps steps from the drop, the GPU solver and the
    /// CPU solver in interleaved pairs of steps; print GPU/CPU steps per second (median
    /// and spread over the rounds) and the load average.
    #[arg(long, value_name = "R", value_parser = ROUNDS.of::<usize>())]
    pub race: Option<usize>,
    #[command(flatten)]
    pub peeling: PeelArgs,
    /// Print a per-pass table over all steps (GPU time by timestamp queries, wall time,
    /// waits, CPU steps; in the JSON with --json).
    #[arg(long)]
    pub profile: bool,
}

/// `classic-gpgpu buoyancy`.
pub fn run_buoyancy(args: &BuoyancyArgs, ctx: &Context, json_out: bool) -> anyhow::Result<()> {
    args.peeling.period.apply(ctx, 4);
    check_resolution(ctx, args.resolution)?;
    if args.bodies == 0 || args.bodies > 10_000 {
        bail!("--bodies {}: must be between 1 and 10000", args.bodies);
    }
    if !(args.dt.is_finite() && args.dt > 0.0 && args.dt <= 0.1) {
        bail!("--dt {}: must be in (0, 0.1] seconds", args.dt);
    }
    if args.peeling.order.is_some() && (args.cpu || args.formulation == super::Formulation::Compute)
    {
        bail!(
            "--order orders the depth peels of the GPU solver's classic formulation; {} does \
             not peel: leave out --order or {}",
            if args.cpu {
                "the CPU solver (clip + Mirtich)"
            } else {
                "the compute formulation"
            },
            if args.cpu {
                "--cpu"
            } else {
                "--formulation compute"
            }
        );
    }
    let frames = match &args.png_every {
        None => None,
        Some(v) => {
            let k = PNG_EVERY
                .parse("--png-every", &v[0])
                .map_err(anyhow::Error::msg)? as usize;
            let dir = PathBuf::from(&v[1]);
            let folder = Staged::begin("--png-every", "buoyancy --png-every", &dir, args.force)?;
            Some((k, folder))
        }
    };
    let settings = args.peeling.settings()?;
    if let Some(rounds) = args.race {
        return race(args, ctx, rounds, settings, json_out);
    }
    let mut sim = scene::paper_scene(args.bodies, args.dt).map_err(anyhow::Error::msg)?;
    if args.extra_damping {
        sim.water = sim.water.with_extra_damping();
    }
    let mut warnings: Vec<String> = Vec::new();
    let compute = args.formulation == super::Formulation::Compute;
    if compute && args.cpu {
        bail!("--cpu and --formulation compute: choose one solver");
    }
    let mut compute_solver = if compute {
        Some(ComputeSolver::new(ctx).context("setting up the compute pass")?)
    } else {
        None
    };
    let mut gpu = if args.cpu || compute {
        None
    } else {
        check_tiles_fit(ctx, args.bodies, args.resolution)?;
        // Any other refusal (a period limit, the renderer) names its own limit.
        let mut solver = GpuSolver::new(ctx, &sim.shapes, sim.bodies.len(), args.resolution)?;
        solver.set_settings(settings)?;
        Some(solver)
    };
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    let renderer = match frames {
        Some(_) => Some(render::FrameRenderer::new(ctx, &sim.shapes, 640, 400)?),
        None => None,
    };
    let progress = classic_gpgpu::mass::progress_bar(args.steps as u64, json_out, "buoyancy steps");
    let mut step_ms = Vec::with_capacity(args.steps);
    let mut peels = Vec::with_capacity(args.steps);
    let cpu_span = |name: &str, work: &mut dyn FnMut() -> Result<_, String>| {
        let _scope = profile::cpu_scope(ctx, name);
        work()
    };
    if args.profile {
        profile::start(ctx);
    }
    for step in 0..args.steps {
        let start = Instant::now();
        let subs = match (gpu.as_mut(), compute_solver.as_mut()) {
            (Some(solver), _) => {
                let subs = solver
                    .submerged(&sim.shapes, &sim.bodies, &sim.water)
                    .map_err(anyhow::Error::msg)?;
                peels.push(solver.last_peels);
                subs
            }
            (None, Some(solver)) => solver
                .submerged(&sim.shapes, &sim.bodies, &sim.water)
                .map_err(anyhow::Error::msg)?,
            (None, None) => cpu_span("buoyancy: CPU solver (clip + Mirtich)", &mut || {
                simulation::AnalyticSolver.submerged(&sim.shapes, &sim.bodies, &sim.water)
            })
            .map_err(anyhow::Error::msg)?,
        };
        cpu_span("buoyancy: rigid-body step", &mut || {
            sim.apply(&subs);
            Ok(Vec::new())
        })
        .map_err(anyhow::Error::msg)?;
        step_ms.push(start.elapsed().as_secs_f64() * 1e3);
        if let (Some((k, folder)), Some(r)) = (&frames, &renderer) {
            if step % k == 0 {
                r.write_png(&sim, &folder.path().join(format!("frame{step:05}.png")))?;
            }
        }
        progress.inc(1);
    }
    progress.finish_and_clear();
    if let Some((_, folder)) = frames {
        folder.finish()?;
    }
    let truncated_steps = gpu.as_ref().map_or(0, |g| g.truncated_steps);
    if truncated_steps > 0 {
        let w = format!(
            "{truncated_steps} steps: {}",
            truncation_warning(settings.max_peels)
        );
        eprintln!("warning: {w}");
        warnings.push(w);
    }
    let profile_table = if args.profile {
        profile::finish(ctx)
    } else {
        None
    };
    let total: f64 = step_ms.iter().sum();
    let mean = total / step_ms.len().max(1) as f64;
    let steps_per_s = 1e3 / mean;
    let bodies: Vec<_> = sim
        .bodies
        .iter()
        .map(|b| {
            json!({
                "shape": sim.shapes[b.shape].name,
                "density": b.density,
                "position": b.rigid.position.to_array(),
                "orientation_xyzw": b.rigid.orientation.to_array(),
                "submerged_volume": b.submerged.volume,
                "volume": sim.shapes[b.shape].unit.volume,
            })
        })
        .collect();
    let out = json!({
        "renderer": ctx.info().renderer_line(),
        "solver": if args.cpu {
            "cpu (clip + Mirtich)"
        } else if compute {
            "gpu compute (clip in the kernel, one dispatch)"
        } else {
            "gpu (n+2 passes, tiles)"
        },
        "formulation": args.formulation.name(),
        "bodies": sim.bodies.len(),
        "steps": args.steps,
        "resolution": args.resolution,
        "dt": args.dt,
        "drag": if args.extra_damping {
            "the paper's quadratic drag, plus a linear drag and a rotational damping"
        } else {
            "the paper's quadratic drag at the centre of buoyancy, at the body's velocity"
        },
        "mean_step_ms": mean,
        "step_ms": step_ms,
        "steps_per_second": steps_per_s,
        "max_peels": peels.iter().max(),
        "peeling": {
            "max_peels": settings.max_peels,
            "order": settings.order,
            "truncated_steps": truncated_steps,
        },
        "warnings": warnings,
        "profile": profile_table,
        "state": bodies,
    });
    if json_out {
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }
    if let Some(table) = &profile_table {
        print!("{}", profile_text(table, &format!("{} steps", args.steps)));
    }
    println!("renderer        {}", ctx.info().renderer_line());
    // Tiles and peels are the classic GPU solver's; the compute and CPU solvers have none.
    let (tiles, deepest) = match peels.iter().max() {
        Some(n) if gpu.is_some() => (
            format!(", {r}x{r} per body", r = args.resolution),
            format!(", deepest peel {n}"),
        ),
        _ => (String::new(), String::new()),
    };
    println!(
        "scene           {} bodies, {} steps of {:.4} s{tiles}, {}",
        sim.bodies.len(),
        args.steps,
        args.dt,
        out["solver"].as_str().unwrap_or("")
    );
    println!("per step        {mean:.2} ms ({steps_per_s:.1} steps/s){deepest}");
    println!(
        "{:>4} {:>8} {:>8} {:>28} {:>10}",
        "body", "shape", "density", "position", "submerged"
    );
    for (k, b) in sim.bodies.iter().enumerate() {
        let p = b.rigid.position;
        println!(
            "{k:>4} {:>8} {:>8.0} ({:>7.3}, {:>7.3}, {:>7.3}) {:>9.1}%",
            sim.shapes[b.shape].name,
            b.density,
            p.x,
            p.y,
            p.z,
            100.0 * b.submerged.volume / sim.shapes[b.shape].unit.volume
        );
    }
    Ok(())
}

/// `buoyancy --race R`: the GPU solver against the CPU one in interleaved pairs.
fn race(
    args: &BuoyancyArgs,
    ctx: &Context,
    rounds: usize,
    settings: PeelSettings,
    json_out: bool,
) -> anyhow::Result<()> {
    if args.formulation == super::Formulation::Compute {
        bail!(
            "--race runs the classic formulation against the CPU solver: no --formulation compute"
        );
    }
    if rounds == 0 || rounds > 1000 {
        bail!("--race {rounds}: must be between 1 and 1000 rounds");
    }
    if args.cpu || args.png_every.is_some() || args.profile {
        bail!("--race runs both solvers and draws nothing: no --cpu, --png-every or --profile");
    }
    let setup = classic_gpgpu::mass::buoyancy::race::RaceSetup {
        bodies: args.bodies,
        resolution: args.resolution,
        steps: args.steps,
        rounds,
        dt: args.dt,
        extra_damping: args.extra_damping,
    };
    let race = classic_gpgpu::mass::buoyancy::race::run(ctx, setup, settings)
        .map_err(anyhow::Error::msg)?;
    if json_out {
        let mut out = serde_json::to_value(&race)?;
        out["renderer"] = json!(ctx.info().renderer_line());
        println!("{}", serde_json::to_string_pretty(&out)?);
    } else {
        println!("renderer        {}", ctx.info().renderer_line());
        println!(
            "scene           {} bodies at {}x{}, {} steps of {:.4} s from the drop",
            args.bodies, args.resolution, args.resolution, args.steps, args.dt
        );
        println!("race            {}", race.in_words());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn runs(median: f64) -> Spread {
        Spread::of(&[median, median, median])
    }

    #[test]
    fn the_no_arithmetic_line_says_what_the_time_is() {
        let near = no_arithmetic_text(6, &runs(10.5), &runs(10.0));
        assert!(near.contains("1.05x"), "{near}");
        assert!(
            near.contains("the integrands' arithmetic is not the time"),
            "{near}"
        );
        let far = no_arithmetic_text(6, &runs(20.0), &runs(10.0));
        assert!(far.contains("2.00x"), "{far}");
        assert!(
            far.contains("arithmetic is 50% of the passes' time"),
            "{far}"
        );
    }
}
