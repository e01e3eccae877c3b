//! Paper 4's benchmark (Kim, Kim, Ko & Terzopoulos 2006): Table 1 (objects and peels),
//! Fig. 4 (relative error against resolution), Fig. 5 (time against resolution beside
//! Mirtich's analytic method) and the buoyancy scene's steps per second (section 5.3), each
//! beside the published numbers of `assets/paper_tables.toml` `[paper4]`.

use super::plot::{Plot, Series};
use super::{BenchOptions, Claim, Fidelity, Figure, Section, Table};
use crate::gl::Context;
use crate::mass::buoyancy::{
    batch::GpuSolver, render::FrameRenderer, scene, simulation::SubmergedSolver,
};
use crate::mass::gpu::GpuMass;
use crate::mass::{analytic, models, surface, MassProperties};
use crate::mesh::Mesh;
use anyhow::Context as _;
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;

/// `classic-gpgpu mass-bench`.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// Small sizes (resolutions up to 128, a short buoyancy run), for CI and smoke tests.
    #[arg(long)]
    pub quick: bool,
    /// Where the figures (PNG) go.
    #[arg(long, default_value = "mass-bench")]
    pub out: PathBuf,
}

/// Runs the benchmark and prints its tables (or the whole section as JSON).
pub fn run_cli(args: &BenchArgs, ctx: &Context, json_out: bool) -> anyhow::Result<()> {
    super::bench_command(ctx, run, args.quick, &args.out, json_out)
}

/// Median of `runs` timings (ms) of `work`.
fn median_ms(runs: usize, mut work: impl FnMut() -> anyhow::Result<f64>) -> anyhow::Result<f64> {
    let mut t = (0..runs)
        .map(|_| work())
        .collect::<anyhow::Result<Vec<f64>>>()?;
    t.sort_by(f64::total_cmp);
    Ok(t[t.len() / 2])
}

struct ObjectRun {
    name: &'static str,
    mesh: Mesh,
    closed: bool,
    exact: MassProperties,
    analytic_ms: f64,
    /// (resolution, peels, errors [mass, Ixx, Iyy, Izz], GPU timer ms, GPU wall ms)
    rows: Vec<(u32, usize, [f64; 4], f64, f64)>,
    /// Peels at 32x32 with the object turned 90 degrees about x (the paper's views are not
    /// published; a torus seen edge-on has four layers, face-on two).
    turned_peels: usize,
}

/// Fig. 4 and 5 for one object at every resolution.
fn measure_object(
    ctx: &Context,
    name: &'static str,
    resolutions: &[u32],
    runs: usize,
) -> anyhow::Result<ObjectRun> {
    let mesh = models::paper_object(name).expect("a paper object");
    let closed = surface::check(&mesh).is_closed();
    let exact = MassProperties::from_integrals(&analytic::volume_integrals(&mesh), 1.0);
    let analytic_ms = median_ms(runs.max(5), || {
        let start = Instant::now();
        std::hint::black_box(analytic::volume_integrals(&mesh));
        Ok(start.elapsed().as_secs_f64() * 1e3)
    })?;
    let mut rows = Vec::new();
    for &n in resolutions {
        let gpu = GpuMass::new(ctx, n)?;
        let first = gpu.integrate(&mesh, None, None)?;
        let got = MassProperties::from_integrals(&first.integrals, 1.0);
        let mut timer = Vec::new();
        let wall = median_ms(runs, || {
            let start = Instant::now();
            let r = gpu.integrate(&mesh, None, None)?;
            timer.push(r.gpu_ms);
            Ok(start.elapsed().as_secs_f64() * 1e3)
        })?;
        timer.sort_by(f64::total_cmp);
        rows.push((
            n,
            first.peels,
            got.relative_errors(&exact),
            timer[timer.len() / 2],
            wall,
        ));
    }
    let turn = glam::Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
    let turned = Mesh::new(
        mesh.positions.iter().map(|p| turn * *p).collect(),
        mesh.triangles.clone(),
    );
    let turned_peels = GpuMass::new(ctx, 32)?.integrate(&turned, None, None)?.peels;
    Ok(ObjectRun {
        name,
        mesh,
        closed,
        exact,
        analytic_ms,
        rows,
        turned_peels,
    })
}

/// The resolution at which the GPU wall time equals the analytic time (log-log
/// interpolation between measured resolutions), as text.
fn break_even(run: &ObjectRun) -> String {
    let t = run.analytic_ms;
    let pts: Vec<(f64, f64)> = run.rows.iter().map(|r| (r.0 as f64, r.4)).collect();
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

/// The buoyancy scene: mean step time, the buoyancy share, peels.
fn measure_buoyancy(opts: &BenchOptions, steps: usize) -> anyhow::Result<serde_json::Value> {
    let ctx = opts.gl;
    let mut sim = scene::paper_scene(50, 1.0 / 60.0).map_err(anyhow::Error::msg)?;
    let mut solver = GpuSolver::new(ctx, &sim.shapes, sim.bodies.len(), 32)?;
    // The bodies start in the air; time them once they are in the water (after 1 s, past
    // the first plunge), as the paper's average over its interactive run would.
    let settle = 60;
    let bar = opts
        .progress
        .add(indicatif::ProgressBar::new((settle + steps) as u64));
    bar.set_message("buoyancy, 50 bodies");
    for _ in 0..settle {
        sim.step(&mut solver).map_err(anyhow::Error::msg)?;
        bar.inc(1);
    }
    let (mut total, mut buoyancy_ms, mut max_peels, mut sum_peels) = (0.0, 0.0, 0, 0);
    for _ in 0..steps {
        let start = Instant::now();
        let subs = solver
            .submerged(&sim.shapes, &sim.bodies, &sim.water)
            .map_err(anyhow::Error::msg)?;
        buoyancy_ms += start.elapsed().as_secs_f64() * 1e3;
        sim.apply(&subs);
        total += start.elapsed().as_secs_f64() * 1e3;
        max_peels = max_peels.max(solver.last_peels);
        sum_peels += solver.last_peels;
        bar.inc(1);
    }
    bar.finish_and_clear();
    let cpu_steps_per_s = cpu_solver_rate(settle, steps)?;
    let (batched_ms, one_by_one_ms) =
        batching_gain(ctx, &sim, &mut solver, if steps > 50 { 20 } else { 5 })?;
    let frame = "buoyancy_frame.png";
    FrameRenderer::new(ctx, &sim.shapes, 800, 500)?.write_png(&sim, &opts.out_dir.join(frame))?;
    Ok(json!({
        "bodies": sim.bodies.len(),
        "resolution": 32,
        "steps": steps,
        "settle_steps": settle,
        "mean_step_ms": total / steps as f64,
        "steps_per_second": 1e3 * steps as f64 / total,
        "buoyancy_share": buoyancy_ms / total,
        "max_peels": max_peels,
        "mean_peels": sum_peels as f64 / steps as f64,
        "cpu_solver_steps_per_second": cpu_steps_per_s,
        "batched_ms": batched_ms,
        "one_body_at_a_time_ms": one_by_one_ms,
        "frame": frame,
    }))
}

/// Fig. 4 (one plot per quantity) and Fig. 5 as PNG line plots.
fn error_and_time_plots(opts: &BenchOptions, objects: &[ObjectRun]) -> anyhow::Result<Vec<Figure>> {
    let mut figures = Vec::new();
    for (k, quantity) in ["mass", "Ixx", "Iyy", "Izz"].iter().enumerate() {
        let plot = Plot {
            title: format!("Fig. 4: relative error of {quantity}"),
            x_label: "resolution (pixels per side)".into(),
            y_label: "relative error".into(),
            log_x: true,
            log_y: true,
            series: objects
                .iter()
                .map(|o| {
                    Series::new(
                        o.name,
                        o.rows
                            .iter()
                            .map(|r| (r.0 as f64, r.2[k].max(1e-9)))
                            .collect(),
                    )
                })
                .collect(),
        };
        let file = format!("fig4_{}.png", quantity.to_lowercase());
        plot.write_png(&opts.out_dir.join(&file))?;
        figures.push(Figure {
            file,
            caption: format!(
                "Fig. 4: relative error of {quantity} against resolution, each object"
            ),
        });
    }
    let mut series: Vec<Series> = objects
        .iter()
        .map(|o| {
            Series::new(
                format!("{} GPU", o.name),
                o.rows.iter().map(|r| (r.0 as f64, r.4)).collect(),
            )
        })
        .collect();
    for o in objects {
        let (lo, hi) = (
            o.rows.first().map(|r| r.0).unwrap_or(8),
            o.rows.last().map(|r| r.0).unwrap_or(512),
        );
        series.push(Series::new(
            format!("{} analytic", o.name),
            vec![(lo as f64, o.analytic_ms), (hi as f64, o.analytic_ms)],
        ));
    }
    let plot = Plot {
        title: format!(
            "Fig. 5: time against resolution ({})",
            opts.gl.info().renderer
        ),
        x_label: "resolution (pixels per side)".into(),
        y_label: "milliseconds (wall clock)".into(),
        log_x: true,
        log_y: true,
        series,
    };
    plot.write_png(&opts.out_dir.join("fig5_time.png"))?;
    figures.push(Figure {
        file: "fig5_time.png".into(),
        caption: "Fig. 5: GPU path (wall clock per call) against resolution; flat lines: Mirtich's analytic method".into(),
    });
    Ok(figures)
}

/// Steps per second of the same scene with the CPU reference solver (clip + Mirtich).
fn cpu_solver_rate(settle: usize, steps: usize) -> anyhow::Result<f64> {
    let mut sim = scene::paper_scene(50, 1.0 / 60.0).map_err(anyhow::Error::msg)?;
    let mut cpu = crate::mass::buoyancy::simulation::AnalyticSolver;
    for _ in 0..settle {
        sim.step(&mut cpu).map_err(anyhow::Error::msg)?;
    }
    let start = Instant::now();
    for _ in 0..steps {
        sim.step(&mut cpu).map_err(anyhow::Error::msg)?;
    }
    Ok(steps as f64 / start.elapsed().as_secs_f64())
}

/// The submerged parts of the scene's current state, all bodies as tiles of one target
/// versus one body per round of passes (what batching saves), mean milliseconds of `reps`.
fn batching_gain(
    ctx: &Context,
    sim: &crate::mass::buoyancy::simulation::Simulation,
    batched: &mut GpuSolver,
    reps: usize,
) -> anyhow::Result<(f64, f64)> {
    let mut single = GpuSolver::new(ctx, &sim.shapes, 1, 32)?;
    // Interleaved, so that a change of load on a shared machine hits both alike.
    let (mut batched_ms, mut single_ms) = (0.0, 0.0);
    for _ in 0..reps {
        let start = Instant::now();
        batched
            .submerged(&sim.shapes, &sim.bodies, &sim.water)
            .map_err(anyhow::Error::msg)?;
        batched_ms += start.elapsed().as_secs_f64() * 1e3;
        let start = Instant::now();
        for body in &sim.bodies {
            single
                .submerged(&sim.shapes, std::slice::from_ref(body), &sim.water)
                .map_err(anyhow::Error::msg)?;
        }
        single_ms += start.elapsed().as_secs_f64() * 1e3;
    }
    Ok((batched_ms / reps as f64, single_ms / reps as f64))
}

/// The section: tables beside the paper, claims, figures.
pub fn run(opts: &BenchOptions) -> anyhow::Result<Section> {
    let ctx = opts.gl;
    let paper = super::paper_tables::load();
    let paper = paper
        .get("paper4")
        .and_then(|v| v.as_table())
        .context("paper4 tables")?;
    let resolutions: Vec<u32> = if opts.quick {
        vec![8, 16, 32, 64, 128]
    } else {
        vec![8, 16, 32, 64, 128, 256, 512]
    };
    let runs = if opts.quick { 3 } else { 5 };
    let bar = opts.progress.add(indicatif::ProgressBar::new(
        models::PAPER_OBJECTS.len() as u64
    ));
    bar.set_message("mass properties, paper objects");
    let mut objects = Vec::new();
    for name in models::PAPER_OBJECTS {
        objects.push(measure_object(ctx, name, &resolutions, runs)?);
        bar.inc(1);
    }
    bar.finish_and_clear();
    let renderer = ctx.info().renderer_line();

    // Table 1.
    let published = paper
        .get("table1")
        .and_then(|v| v.as_array())
        .cloned()
        .unwrap_or_default();
    let row_of = |name: &str| {
        published
            .iter()
            .find(|r| r.get("object").and_then(|o| o.as_str()) == Some(name))
    };
    let int = |r: Option<&toml::Value>, key: &str| {
        r.and_then(|r| r.get(key))
            .and_then(|v| v.as_integer())
            .map(|v| v.to_string())
            .unwrap_or_else(|| "-".into())
    };
    let mut table1 = Table {
        caption: "Table 1: test objects (paper beside ours; peels = depth layers under the view down -z, which depend on orientation and resolution; turned = rotated 90 degrees about x, at 32x32)".into(),
        header: [
            "object", "vertices", "paper", "faces", "paper", "peels (32x32)", "peels (finest)", "peels (turned)", "paper", "closed",
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    for o in &objects {
        let r = row_of(o.name);
        let peels32 = o.rows.iter().find(|r| r.0 == 32).map(|r| r.1).unwrap_or(0);
        table1.rows.push(vec![
            o.name.into(),
            o.mesh.positions.len().to_string(),
            int(r, "vertices"),
            o.mesh.triangles.len().to_string(),
            int(r, "faces"),
            peels32.to_string(),
            o.rows
                .last()
                .map(|r| format!("{} ({}x{})", r.1, r.0, r.0))
                .unwrap_or_default(),
            o.turned_peels.to_string(),
            int(r, "peels"),
            if o.closed {
                "yes".into()
            } else {
                "no (analytic unreliable)".into()
            },
        ]);
    }

    // Fig. 4 and Fig. 5 as tables.
    let mut fig4 = Table {
        caption: "Fig. 4: relative error against Mirtich's analytic result (%)".into(),
        header: ["object", "resolution", "mass", "Ixx", "Iyy", "Izz"]
            .map(String::from)
            .to_vec(),
        rows: Vec::new(),
    };
    let mut fig5 = Table {
        caption: format!("Fig. 5: time (ms) against resolution, on {renderer}"),
        header: [
            "object",
            "resolution",
            "GPU (timer query)",
            "GPU (wall)",
            "analytic (CPU)",
            "GPU / analytic",
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    let mut break_even_table = Table {
        caption: "Resolution where the GPU path costs the same as the analytic one (wall clock)"
            .into(),
        header: ["object", "faces", "analytic (ms)", "break-even"]
            .map(String::from)
            .to_vec(),
        rows: Vec::new(),
    };
    for o in &objects {
        for &(n, _, e, timer, wall) in &o.rows {
            fig4.rows.push(
                [o.name.to_string(), format!("{n}x{n}")]
                    .into_iter()
                    .chain(e.iter().map(|v| format!("{:.3}", 100.0 * v)))
                    .collect(),
            );
            fig5.rows.push(vec![
                o.name.into(),
                format!("{n}x{n}"),
                format!("{timer:.3}"),
                format!("{wall:.3}"),
                format!("{:.3}", o.analytic_ms),
                format!("{:.1}", wall / o.analytic_ms),
            ]);
        }
        break_even_table.rows.push(vec![
            o.name.into(),
            o.mesh.triangles.len().to_string(),
            format!("{:.3}", o.analytic_ms),
            break_even(o),
        ]);
    }

    // Claims.
    let worst_at = |n: u32, closed_only: bool| {
        objects
            .iter()
            .filter(|o| o.closed || !closed_only)
            .flat_map(|o| o.rows.iter().filter(|r| r.0 == n).flat_map(|r| r.2))
            .fold(0.0f64, f64::max)
    };
    let worst32 = worst_at(32, false);
    let worst32_closed = worst_at(32, true);
    let at64 = |name: &str| {
        objects.iter().find(|o| o.name == name).and_then(|o| {
            o.rows
                .iter()
                .find(|r| r.0 == 64)
                .map(|r| (r.4, o.analytic_ms))
        })
    };
    let mut claims = vec![Claim {
        claim: "32x32 is enough for 5% error in mass and principal moments".into(),
        paper: "every object within 5% at 32x32 (Fig. 4)".into(),
        measured: format!(
            "worst relative error at 32x32: {:.2}% over the closed objects; {:.2}% with the open \
             teapot, whose analytic reference is unreliable (Newell's surface has gaps), so it is \
             not judged",
            100.0 * worst32_closed,
            100.0 * worst32
        ),
        holds: Some(worst32_closed < 0.05),
    }];
    for name in ["bunny", "pipe"] {
        if let Some((gpu, ana)) = at64(name) {
            claims.push(Claim {
                claim: format!(
                    "at 64x64 the GPU method outperforms the analytic one for the {name}"
                ),
                paper: "GeForce 7800 GTX vs 2.53 GHz Pentium 4 (Fig. 5)".into(),
                measured: format!("GPU {gpu:.3} ms (wall) vs analytic {ana:.3} ms on {renderer}"),
                holds: Some(gpu < ana),
            });
        }
    }

    // Buoyancy.
    let steps = if opts.quick { 20 } else { 200 };
    let buoyancy = measure_buoyancy(opts, steps)?;
    let paper_b = paper.get("buoyancy");
    let paper_fps = paper_b
        .and_then(|b| b.get("frames_per_second"))
        .and_then(|v| v.as_float())
        .unwrap_or(16.0);
    let sps = buoyancy["steps_per_second"].as_f64().unwrap_or(0.0);
    let table_b = Table {
        caption: format!("Section 5.3: 50 bodies at 32x32 on {renderer} (paper: GeForce 7800 GTX)"),
        header: ["measure", "ours", "paper"].map(String::from).to_vec(),
        rows: vec![
            vec![
                "steps per second".into(),
                format!("{sps:.1}"),
                format!("{paper_fps}"),
            ],
            vec![
                "steps per second, CPU reference solver (clip + Mirtich)".into(),
                format!(
                    "{:.1}",
                    buoyancy["cpu_solver_steps_per_second"]
                        .as_f64()
                        .unwrap_or(0.0)
                ),
                "-".into(),
            ],
            vec![
                "share of step time in buoyancy".into(),
                format!(
                    "{:.0}%",
                    100.0 * buoyancy["buoyancy_share"].as_f64().unwrap_or(0.0)
                ),
                "over 90%".into(),
            ],
            vec![
                "buoyancy of 50 bodies: tiles of one target vs one body at a time (ms)".into(),
                format!(
                    "{:.1} vs {:.1}",
                    buoyancy["batched_ms"].as_f64().unwrap_or(0.0),
                    buoyancy["one_body_at_a_time_ms"].as_f64().unwrap_or(0.0)
                ),
                "-".into(),
            ],
            vec![
                "deepest peel (mean)".into(),
                format!(
                    "{} ({:.1})",
                    buoyancy["max_peels"],
                    buoyancy["mean_peels"].as_f64().unwrap_or(0.0)
                ),
                "6 (teapot, bunny; mostly 3-4)".into(),
            ],
        ],
    };
    claims.push(Claim {
        claim: "interactive buoyancy of 50 bodies".into(),
        paper: format!("{paper_fps} frames/s on a GeForce 7800 GTX"),
        measured: format!("{sps:.1} steps/s on {renderer} (target: 30)"),
        holds: Some(sps >= paper_fps),
    });

    // Fig. 10: the integrands of each peel of a buoyant bunny (the part below the water
    // when the water line passes through its centre of mass).
    let bunny = models::paper_object("bunny").expect("bunny");
    let bunny_com =
        MassProperties::from_integrals(&analytic::volume_integrals(&bunny), 1.0).center_of_mass;
    let dump_dir = opts.out_dir.join("fig10_bunny");
    let bunny_peels = GpuMass::new(ctx, 128)?
        .integrate(&bunny, Some(bunny_com.z), Some(&dump_dir))?
        .peels;
    let mut figures = error_and_time_plots(opts, &objects)?;
    figures.push(Figure {
        file: buoyancy["frame"].as_str().unwrap_or("").into(),
        caption:
            "Fig. 9: the 50-body scene after the benchmark run (gravity blue, buoyancy yellow)"
                .into(),
    });
    for k in 1..=bunny_peels {
        figures.push(Figure {
            file: format!("fig10_bunny/peel{k}_target0.png"),
            caption: format!(
                "Fig. 10: bunny below the water, peel {k}, target 0 (rx, ry, rz, V integrands), 128x128"
            ),
        });
    }

    let results = json!({
        "renderer": renderer,
        "quick": opts.quick,
        "objects": objects.iter().map(|o| json!({
            "object": o.name,
            "vertices": o.mesh.positions.len(),
            "faces": o.mesh.triangles.len(),
            "closed": o.closed,
            "peels_turned_90_about_x": o.turned_peels,
            "analytic": {"volume": o.exact.volume, "inertia": o.exact.inertia_rows()},
            "analytic_ms": o.analytic_ms,
            "resolutions": o.rows.iter().map(|&(n, peels, e, timer, wall)| json!({
                "resolution": n, "peels": peels,
                "relative_error": {"mass": e[0], "Ixx": e[1], "Iyy": e[2], "Izz": e[3]},
                "gpu_ms": timer, "gpu_wall_ms": wall,
            })).collect::<Vec<_>>(),
            "break_even": break_even(o),
        })).collect::<Vec<_>>(),
        "buoyancy": buoyancy,
    });

    Ok(Section {
        id: "paper4".into(),
        title: "Paper 4: Kim, Kim, Ko & Terzopoulos 2006, mass properties by depth peeling, and buoyancy".into(),
        summary: format!(
            "The seven test objects of Table 1 (the mesh module's generators and the shipped bunny; the exact meshes \
             are not published) integrated by the section 3.1 fragment shader under depth peeling at {} resolutions, \
             against Mirtich's analytic method on the CPU (f64). Times are medians of {runs} runs after a warm-up, \
             on {renderer}: a software rasterizer runs the 'GPU' passes on the CPU, so the ratios are not the \
             paper's. The buoyancy scene is the 50 bodies of section 5.3 at 32x32 per body, all bodies as tiles of \
             one target, timed after 60 steps that bring them into the water. On a software renderer the GL layer \
             raises glibc's trim and mmap thresholds, so the driver's per-draw buffers are not faulted in afresh \
             every time (about 30 -> 40 steps/s on llvmpipe, 2 cores).{}",
            resolutions.len(),
            if opts.quick { " Quick mode: resolutions up to 128 and a short buoyancy run." } else { "" }
        ),
        tables: vec![table1, fig4, fig5, break_even_table, table_b],
        claims,
        figures,
        fidelity: vec![
            Fidelity {
                feature: "integrands of eq. 4 and 6 in a fragment shader, three render targets (MRT)".into(),
                paper: "GLSL listing, section 3.1".into(),
                code: "cg_ports/mass_integrands.frag".into(),
            },
            Fidelity {
                feature: "depth peeling until an occlusion query counts nothing".into(),
                paper: "section 3.2".into(),
                code: "src/mass/peel.rs, src/gl/peel.rs".into(),
            },
            Fidelity {
                feature: "summation by ping-pong buffer reduction".into(),
                paper: "section 3.3, Fig. 2".into(),
                code: "src/mass/reduce.rs, src/gl/reduce.rs".into(),
            },
            Fidelity {
                feature: "n + 2 passes: fluid depth, peels below it, fluid patch where pass 1 faced down".into(),
                paper: "section 5.2, Fig. 7-8".into(),
                code: "src/mass/peel.rs, glsl/mass/peel_main.frag, glsl/mass/water_patch.frag".into(),
            },
            Fidelity {
                feature: "Mirtich's analytic algorithm as the baseline".into(),
                paper: "section 4 [13]".into(),
                code: "src/mass/analytic.rs".into(),
            },
        ],
        results,
    })
}
