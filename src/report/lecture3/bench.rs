//! The measurements of the lecture-3 section, one function per technique. Each runs the GPU
//! path and its CPU reference side by side in one run, checks that they agree, and times
//! both (GL timer queries for GPU passes, wall clock for the CPU). The `lecture3` commands
//! call the same functions.

use super::images;
use super::results::*;
use super::scene::{DEPTH, DISTANCE, THETAS};
use super::timed::{gpu_ms, gpu_ms_warm, gpu_timing, runs, wall_once_ms};
use crate::gl::Context;
use crate::lecture3::blend_histogram::{self, Bins, Histogram, Values};
use crate::lecture3::depth_mask::{self, DepthMask, MaskShape};
use crate::lecture3::displacement::compare::ReferenceImage;
use crate::lecture3::displacement::{exact, Camera, DisplacementRenderer, Method, Pixel, Surface};
use crate::lecture3::function_texture::{
    error_against_exact, sample_x, Evaluation, Function, FunctionPasses, FunctionTable,
};
use crate::lecture3::light_hierarchy::gather::MIN_DISTANCE;
use crate::lecture3::light_hierarchy::light::brute_force_all;
use crate::lecture3::light_hierarchy::{Gather, IndirectLighting, Scene};
use crate::lecture3::pyramid::{cpu_pyramid, Extreme, PyramidBuilder};
use crate::lecture3::random_texture::statistics::{
    chi_square, chi_square_critical, correlation, correlation_bound,
};
use crate::lecture3::random_texture::{HybridTaus, RandomTexture};
use crate::lecture3::HeightMap;
use crate::report::BenchOptions;
use crate::timing::{wall_ms, Load, Runs, Spread};
use std::path::Path;

/// Everything, at the section's sizes.
pub fn measure(opts: &BenchOptions, height: Option<&Path>) -> anyhow::Result<Lecture3Results> {
    let ctx = opts.gl;
    let quick = opts.quick;
    let runs = runs(opts);
    let map = match height {
        Some(path) => HeightMap::load(path, ctx.info().limits.max_texture_size)?,
        None => HeightMap::generated(crate::lecture3::height_map::SHIPPED_SIZE),
    };
    let map_name = height.map_or_else(
        || format!("{} (generated)", crate::lecture3::height_map::SHIPPED_PATH),
        |p| p.display().to_string(),
    );
    let stage = |name: &str| {
        crate::timing::mark(&format!("lecture3: before {name}"));
        let bar = opts.progress.add(indicatif::ProgressBar::new_spinner());
        bar.set_message(format!("lecture 3: {name}"));
        bar
    };
    let mut load = Load::now();
    let bar = stage("image pyramid");
    // region: workload pyramid
    let sizes: &[u32] = if quick {
        &[64, 256]
    } else {
        &[64, 256, 1024, 2048]
    };
    // endregion
    let pyramid = sizes
        .iter()
        .map(|&s| pyramid_row(ctx, &HeightMap::generated(s), runs))
        .collect::<anyhow::Result<_>>()?;
    images::pyramid_png(
        &images::gpu_pyramids(ctx, &map)?,
        (map.width(), map.height()),
        &opts.out_dir.join(images::PYRAMID_PNG),
    )?;
    bar.finish_and_clear();

    let bar = stage("pyramidal displacement mapping");
    let prefilter = super::prefilter::measure(opts, &map, runs)?;
    crate::timing::mark("lecture3: prefilter");
    let displacement = displacement(opts, map, map_name, runs)?;
    load = Load::worst(load, Load::now());
    bar.finish_and_clear();
    let bar = stage("light hierarchy");
    let light = light(opts, runs)?;
    crate::timing::mark("lecture3: light");
    let light_uses = super::light_uses::measure(opts, ctx)?;
    bar.finish_and_clear();
    let bar = stage("function in a texture");
    let function = function(ctx, quick, runs)?;
    load = Load::worst(load, Load::now());
    bar.finish_and_clear();
    let bar = stage("random numbers in a texture");
    // region: workload random
    let random = random(opts, if quick { 64 } else { 256 }, 16, 2007, runs)?;
    // endregion
    bar.finish_and_clear();
    let bar = stage("if removed with the depth buffer");
    let depth_mask = depth_mask(opts, quick, runs)?;
    load = Load::worst(load, Load::now());
    bar.finish_and_clear();
    let bar = stage("octree on the GPU");
    let octree = super::octree::measure(opts, runs)?;
    bar.finish_and_clear();
    let bar = stage("histogram by blending");
    // region: workload histogram
    let counts: &[usize] = if quick {
        &[1 << 14, 65_535]
    } else {
        &[65_535, 1 << 20]
    };
    // endregion
    let histogram = counts
        .iter()
        .map(|&n| {
            let bins = Bins::new(0.0, 1.0, 256, ctx.info().limits.max_texture_size)?;
            let gather = n <= blend_histogram::MAX_GATHER_VALUES;
            histogram_row(ctx, &skewed_values(n, 3), bins, gather, runs)
        })
        .collect::<anyhow::Result<_>>()?;
    bar.finish_and_clear();
    crate::timing::mark("lecture3: histogram");
    Ok(Lecture3Results {
        renderer: ctx.info().renderer_line(),
        renderer_name: ctx.info().renderer.clone(),
        software: ctx.info().is_software(),
        gpu_timing: gpu_timing(ctx).into(),
        quick,
        runs: runs.in_words(),
        load,
        pyramid,
        displacement,
        prefilter,
        light,
        light_uses,
        function,
        random,
        depth_mask,
        histogram,
        octree,
    })
}

/// Technique 1 on one map: the max and min pyramids on the GPU against the CPU's, and the
/// times of the level passes and of the CPU pyramid.
pub fn pyramid_row(ctx: &Context, map: &HeightMap, runs: Runs) -> anyhow::Result<PyramidRow> {
    let builder = PyramidBuilder::new(ctx)?;
    let (w, h) = (map.width(), map.height());
    let mut equal = true;
    let mut gpu = Spread::default();
    for extreme in [Extreme::Max, Extreme::Min] {
        let pyramid = builder.from_image(w, h, map.heights(), extreme)?;
        equal &= pyramid.read_levels()? == cpu_pyramid(w, h, map.heights(), extreme);
        if extreme == Extreme::Max {
            // `from_image` drew the same levels with the same program: the warm-up.
            gpu = gpu_ms_warm(ctx, runs, || Ok(builder.build_levels(&pyramid)?))?;
        }
    }
    let levels = crate::lecture3::pyramid::level_count(w, h);
    let mean_gpu = builder
        .from_image(w, h, map.heights(), Extreme::Mean)?
        .read_levels()?;
    let mean_cpu = cpu_pyramid(w, h, map.heights(), Extreme::Mean);
    let mean_max_error = mean_gpu
        .iter()
        .zip(&mean_cpu)
        .flat_map(|(g, c)| g.values.iter().zip(&c.values))
        .map(|(&g, &c)| (g as f64 - c as f64).abs())
        .fold(0.0, f64::max);
    let cpu = wall_ms(runs, || cpu_pyramid(w, h, map.heights(), Extreme::Max));
    Ok(PyramidRow {
        size: w.max(h),
        levels,
        equal_to_cpu: equal,
        mean_max_error,
        gpu_ms: gpu.median,
        gpu_spread: gpu,
        cpu_ms: cpu.median,
        cpu_spread: cpu,
    })
}

/// The elevation of the grazing figure (degrees).
pub const GRAZING_FIGURE: f32 = 8.0;

fn displacement(
    opts: &BenchOptions,
    map: HeightMap,
    map_name: String,
    runs: Runs,
) -> anyhow::Result<DisplacementRun> {
    let ctx = opts.gl;
    // region: workload displacement-views
    let image = if opts.quick { 96 } else { 256 };
    let map_size = (map.width(), map.height());
    let renderer = DisplacementRenderer::new(ctx, Surface::new(map, DEPTH)?)?;
    let elevations = [60.0, 30.0, 15.0, 8.0, 4.0, 2.0];
    let methods = [
        Method::Pyramid,
        Method::Relief {
            linear_steps: 16,
            binary_steps: 6,
        },
        Method::RELIEF,
    ];
    // endregion
    let mut artifacts = Vec::new();
    for elevation in elevations {
        let row = artifact_row(&renderer, 225.0, elevation, image, &methods)?;
        artifacts.push(row.0);
        if elevation == GRAZING_FIGURE {
            images::grazing_png(opts, &row.1, image)?;
        }
    }
    images::orbit_png(opts, &renderer, image)?;
    // region: workload displacement-maps
    let map_sizes: &[u32] = if opts.quick {
        &[64, 256]
    } else {
        &[64, 256, 1024]
    };
    // endregion
    let speed = map_sizes
        .iter()
        .map(|&s| speed_row(ctx, s, image, runs))
        .collect::<anyhow::Result<_>>()?;
    Ok(DisplacementRun {
        map: map_name,
        map_size,
        depth: DEPTH,
        image,
        artifacts,
        speed,
    })
}

/// One view rendered by each method and judged against the exact tracer (traced once); the
/// frames (colour, verdicts) kept for the figures.
pub fn artifact_row(
    renderer: &DisplacementRenderer,
    azimuth: f32,
    elevation: f32,
    image: u32,
    methods: &[Method],
) -> anyhow::Result<(ArtifactRow, Vec<images::JudgedFrame>)> {
    let camera = Camera::orbit(
        renderer.surface().centre(),
        DISTANCE,
        azimuth,
        elevation,
        image,
        image,
    );
    let reference = ReferenceImage::trace(renderer.surface(), &camera);
    let target = renderer.target(image, image)?;
    let mut row = ArtifactRow {
        azimuth,
        elevation,
        methods: Vec::new(),
    };
    let mut frames = Vec::new();
    for &method in methods {
        renderer.render(&target, &camera, method)?;
        let frame = renderer.read(&target)?;
        frame.check_finished()?;
        let (comparison, verdicts) = reference.judge(&frame);
        row.methods.push(MethodComparison {
            method: method.name(),
            comparison,
        });
        frames.push(images::JudgedFrame {
            method: method.name(),
            colour: frame.colour,
            verdicts,
        });
    }
    Ok((row, frames))
}

/// One map size: pyramid and relief frames timed, against the exact CPU tracer.
pub fn speed_row(ctx: &Context, size: u32, image: u32, runs: Runs) -> anyhow::Result<SpeedRow> {
    let surface = Surface::new(HeightMap::generated(size), DEPTH)?;
    let renderer = DisplacementRenderer::new(ctx, surface)?;
    let view = |side| {
        Camera::orbit(
            renderer.surface().centre(),
            DISTANCE,
            225.0,
            30.0,
            side,
            side,
        )
    };
    let camera = view(image);
    let target = renderer.target(image, image)?;
    // Warm-up: both programs once on a small frame of the same view (their shader variants
    // compiled), not a full frame each.
    let small = view(WARM_UP_SIDE);
    let warm = renderer.target(WARM_UP_SIDE, WARM_UP_SIDE)?;
    for method in [Method::Pyramid, Method::RELIEF] {
        renderer.render(&warm, &small, method)?;
    }
    let pyramid = gpu_ms_warm(ctx, runs, || {
        Ok(renderer.render(&target, &camera, Method::Pyramid)?)
    })?;
    let frame = renderer.read(&target)?;
    frame.check_finished()?;
    let iterations: Vec<u32> = frame
        .pixels()
        .iter()
        .filter_map(|p| match p {
            Pixel::Hit { iterations, .. } => Some(*iterations),
            _ => None,
        })
        .collect();
    let relief = gpu_ms_warm(ctx, runs, || {
        Ok(renderer.render(&target, &camera, Method::RELIEF)?)
    })?;
    let cpu_ms = wall_once_ms(|| exact::trace_image(renderer.surface(), &camera, 0.0));
    Ok(SpeedRow {
        map_size: size,
        levels: renderer.bounds().levels(),
        pyramid_ms: pyramid.median,
        pyramid_spread: pyramid,
        pyramid_iterations: iterations.iter().map(|&i| i as f64).sum::<f64>()
            / iterations.len().max(1) as f64,
        relief_ms: relief.median,
        relief_spread: relief,
        cpu_ms,
        hit_pixels: iterations.len(),
    })
}

/// Side of the small frame that warms up the displacement programs.
const WARM_UP_SIDE: u32 = 16;

fn light(opts: &BenchOptions, runs: Runs) -> anyhow::Result<LightRun> {
    // region: workload light
    let (vpl_side, side) = if opts.quick { (32, 128) } else { (64, 256) };
    // endregion
    let (run, lighting, brute_pictures) = light_run(
        opts.gl,
        vpl_side,
        side,
        side,
        &THETAS,
        runs,
        images::brute_force_pictures,
    )?;
    images::light_png(opts, &lighting, brute_pictures)?;
    Ok(run)
}

/// Technique 3: the hierarchy built and every criterion gathered, against the brute force on
/// the GPU and on the CPU. `with_brute_force` sees the lighting while the brute-force gather
/// is in its target (for pictures); what it returns is returned. Returns the pipeline too,
/// for pictures: its gather target then holds the last criterion's gather (its last timed
/// run), so a picture of that criterion needs no gather of its own.
///
/// Each gather pass is run the fewest times the timings allow: both gather programs are
/// warmed up once with one node per receiver ([`IndirectLighting::warm_up_gathers`]), and
/// the brute-force gather that is checked (and pictured) is the last timed one, still in its
/// target (every run draws the same).
pub fn light_run<T>(
    ctx: &Context,
    vpl_side: u32,
    width: u32,
    height: u32,
    thetas: &[f32],
    runs: Runs,
    with_brute_force: impl FnOnce(&IndirectLighting) -> anyhow::Result<T>,
) -> anyhow::Result<(LightRun, IndirectLighting, T)> {
    light_run_in(
        ctx,
        Scene::room(),
        vpl_side,
        (width, height),
        thetas,
        runs,
        with_brute_force,
    )
}

/// [`light_run`] on `scene`.
pub fn light_run_in<T>(
    ctx: &Context,
    scene: Scene,
    vpl_side: u32,
    (width, height): (u32, u32),
    thetas: &[f32],
    runs: Runs,
    with_brute_force: impl FnOnce(&IndirectLighting) -> anyhow::Result<T>,
) -> anyhow::Result<(LightRun, IndirectLighting, T)> {
    let lighting = IndirectLighting::new(ctx, scene, vpl_side, width, height)?;
    let build = gpu_ms(ctx, runs, || Ok(lighting.build_lights()?))?;
    lighting.draw_receivers()?;
    lighting.warm_up_gathers()?;
    let brute_gpu = gpu_ms_warm(ctx, runs, || Ok(lighting.gather(Gather::BruteForce)?))?;
    let brute = lighting.gathers.read()?;
    let seen = with_brute_force(&lighting)?;
    let receivers = lighting.gbuffer.receivers()?;
    let levels = lighting.clusters.read_atlas_levels()?;
    let (mut cpu, mut brute_cpu_threads) = (Vec::new(), 1);
    let brute_cpu_ms = wall_once_ms(|| {
        (cpu, brute_cpu_threads) = brute_force_all(&receivers, &levels[0], MIN_DISTANCE as f64);
    });
    let brute_gpu_vs_cpu = brute
        .iter()
        .zip(&cpu)
        .filter_map(|(g, c)| c.map(|c| (g, c)))
        .map(|(g, c)| {
            let gpu = glam::DVec3::new(g[0] as f64, g[1] as f64, g[2] as f64);
            (gpu - c).abs().max_element() / c.max_element().max(1e-30)
        })
        .fold(0.0, f64::max);
    let covered = receivers.iter().filter(|r| r.is_some()).count();
    let mut rows = Vec::with_capacity(thetas.len());
    for &theta in thetas {
        let gather = Gather::tree(theta)?;
        // In a sweep, theta 0 is the check and is timed once; a criterion gathered alone
        // (the `lecture3 light` command's) as `runs` says, whatever it is.
        let timed = if thetas.len() > 1 {
            theta_runs(theta, runs)
        } else {
            runs
        };
        let gpu = gpu_ms_warm(ctx, timed, || Ok(lighting.gather(gather)?))?;
        let tree = lighting.gathers.read()?;
        let (mut err, mut norm, mut nodes) = (0.0, 0.0, 0.0);
        for ((t, b), r) in tree.iter().zip(&brute).zip(&receivers) {
            if r.is_none() {
                continue;
            }
            for c in 0..3 {
                err += (t[c] as f64 - b[c] as f64).powi(2);
                norm += (b[c] as f64).powi(2);
            }
            nodes += t[3] as f64;
        }
        rows.push(LightRow {
            theta,
            relative_rms_error: (err / norm).sqrt(),
            mean_nodes: nodes / covered.max(1) as f64,
            gpu_ms: gpu.median,
            gpu_spread: gpu,
        });
    }
    let vpls = levels[0].nodes.iter().filter(|v| v.weight > 0.0).count();
    Ok((
        LightRun {
            vpl_side,
            vpls,
            image: (width, height),
            receivers: covered,
            build_ms: build.median,
            build_spread: build,
            brute_gpu_ms: brute_gpu.median,
            brute_gpu_spread: brute_gpu,
            brute_cpu_ms,
            brute_cpu_threads,
            brute_gpu_vs_cpu,
            rows,
        },
        lighting,
        seen,
    ))
}

/// The runs of the tree gather at `theta`: theta 0 opens every cluster, so its gather is the
/// brute force's sum by another road, there to check the tree against it (its error); no
/// claim takes its time, the slowest of the sweep (more nodes than VPLs), so it is timed
/// once. Every other criterion as `runs` says.
pub fn theta_runs(theta: f32, runs: Runs) -> Runs {
    if theta == 0.0 {
        Runs::exactly(1)
    } else {
        runs
    }
}

/// The table sizes of the error table.
pub const TEXELS: [u32; 5] = [16, 64, 256, 1024, 4096];

/// Technique 4: errors per table size, and the speed of computing against looking up.
pub fn function(ctx: &Context, quick: bool, runs: Runs) -> anyhow::Result<FunctionRun> {
    // region: workload function
    let side = if quick { 128 } else { 256 };
    let per_pixel = if quick { 16 } else { 64 };
    // endregion
    let passes = FunctionPasses::new(ctx, side, side)?;
    let mut errors = Vec::new();
    let mut speed = Vec::new();
    for f in Function::ALL {
        for texels in TEXELS {
            errors.push(function_error_row(ctx, &passes, f, texels)?);
        }
        speed.push(function_speed_row(ctx, &passes, f, 256, per_pixel, runs)?);
    }
    Ok(FunctionRun { errors, speed })
}

/// One function and table size: the GPU lookup against the exact function and against the
/// exact interpolation of the same table.
pub fn function_error_row(
    ctx: &Context,
    passes: &FunctionPasses,
    f: Function,
    texels: u32,
) -> anyhow::Result<FunctionErrorRow> {
    let table = FunctionTable::new(ctx, f, texels)?;
    passes.run(Evaluation::Lookup(&table), 1)?;
    let gpu = passes.read()?;
    let samples = passes.total(1);
    let (max_error, rms_error) = error_against_exact(f, |s| gpu[s as usize] as f64, samples);
    let filter_error = (0..samples)
        .map(|s| (gpu[s as usize] as f64 - table.interpolate(sample_x(f, s, samples))).abs())
        .fold(0.0, f64::max);
    Ok(FunctionErrorRow {
        function: f.name().into(),
        texels,
        samples,
        max_error,
        rms_error,
        bound: table.error_bound(),
        filter_error,
    })
}

/// One function: K values per pixel computed, looked up, and computed on the CPU.
pub fn function_speed_row(
    ctx: &Context,
    passes: &FunctionPasses,
    f: Function,
    texels: u32,
    per_pixel: u32,
    runs: Runs,
) -> anyhow::Result<FunctionSpeedRow> {
    let table = FunctionTable::new(ctx, f, texels)?;
    // Warm-up: both programs once at one value per pixel (the values per pixel are a uniform).
    passes.run(Evaluation::Exact(f), 1)?;
    passes.run(Evaluation::Lookup(&table), 1)?;
    let exact = gpu_ms_warm(ctx, runs, || {
        Ok(passes.run(Evaluation::Exact(f), per_pixel)?)
    })?;
    let lookup = gpu_ms_warm(ctx, runs, || {
        Ok(passes.run(Evaluation::Lookup(&table), per_pixel)?)
    })?;
    let total = passes.total(per_pixel);
    let cpu_ms = wall_once_ms(|| {
        (0..total)
            .map(|s| f.exact(sample_x(f, s, total)))
            .sum::<f64>()
    });
    Ok(FunctionSpeedRow {
        function: f.name().into(),
        evaluations: total,
        exact_ms: exact.median,
        exact_spread: exact,
        lookup_ms: lookup.median,
        lookup_spread: lookup,
        cpu_ms,
    })
}

/// Technique 5: `side^2` generators for `steps` steps against the CPU generator, the
/// numbers tested, the times per step.
pub fn random(
    opts: &BenchOptions,
    side: u32,
    steps: usize,
    seed: u64,
    runs: Runs,
) -> anyhow::Result<RandomRun> {
    let ctx = opts.gl;
    let gpu = RandomTexture::new(ctx, side, side, seed)?;
    let n = (side * side) as usize;
    let mut cpu: Vec<HybridTaus> = (0..n as u64).map(|i| HybridTaus::seeded(seed, i)).collect();
    let mut streams = vec![Vec::with_capacity(steps); n];
    let mut bit_exact = true;
    let mut raw = Vec::with_capacity(n * steps);
    for _ in 0..steps {
        gpu.step()?;
        let values = gpu.values()?;
        raw.extend_from_slice(&values);
        for ((s, g), v) in streams.iter_mut().zip(&mut cpu).zip(&values) {
            bit_exact &= g.next_f32().to_bits() == v.to_bits();
            s.push(*v);
        }
    }
    let states: Vec<u32> = cpu.iter().flat_map(|g| g.z).collect();
    bit_exact &= gpu.states()? == states;
    // The picture is the last checked step (the numbers the histogram below counts), taken
    // before the timed steps move the generators on by as many steps as the runs take.
    let last_step = &raw[raw.len() - n..];
    crate::gl::dump::picture_png(
        &[crate::gl::picture::Panel {
            title: format!("one number per texel, step {steps} of {side}x{side} generators"),
            values: last_step.to_vec(),
            width: side,
            height: side,
            scale: crate::gl::picture::Scale::fixed(0.0, 1.0),
        }],
        (640, 700),
        &opts.out_dir.join(images::RANDOM_PNG),
    )?;
    // The checked steps above were the warm-up.
    let gpu_step = gpu_ms_warm(ctx, runs, || Ok(gpu.step()?))?;
    let cpu_step = wall_ms(runs, || cpu.iter_mut().map(|g| g.next_f32()).sum::<f32>());
    let all: Vec<f32> = streams.iter().flatten().copied().collect();
    let serial: Vec<(f32, f32)> = streams
        .iter()
        .flat_map(|s| s.windows(2).map(|p| (p[0], p[1])))
        .collect();
    let neighbours: Vec<(f32, f32)> = (0..n)
        .filter(|i| (i + 1) % side as usize != 0)
        .flat_map(|i| (0..steps).map(move |t| (i, t)))
        .map(|(i, t)| (streams[i][t], streams[i + 1][t]))
        .collect();
    // The last step's numbers, counted by technique 7 (additive blending).
    let last: Vec<f32> = streams.iter().map(|s| s[steps - 1]).collect();
    let bins = Bins::new(0.0, 1.0, 64, ctx.info().limits.max_texture_size)?;
    let histogram = Histogram::new(ctx, bins)?;
    histogram.draw(
        &Values::new(ctx, &last, None)?,
        blend_histogram::Method::Blend,
    )?;
    Ok(RandomRun {
        side,
        steps,
        values: raw,
        bit_exact,
        gpu_ms_per_step: gpu_step.median,
        gpu_spread: gpu_step,
        cpu_ms_per_step: cpu_step.median,
        cpu_spread: cpu_step,
        chi_square: chi_square(&all, 64),
        chi_square_critical: chi_square_critical(63.0, 3.09),
        serial_correlation: correlation(&serial),
        neighbour_correlation: correlation(&neighbours),
        correlation_bound: correlation_bound(neighbours.len().min(serial.len()), 3.29),
        histogram: histogram.read()?,
    })
}

/// The mask fractions of the depth-mask table.
pub const FRACTIONS: [f32; 5] = [0.05, 0.25, 0.5, 0.75, 1.0];

fn depth_mask(opts: &BenchOptions, quick: bool, runs: Runs) -> anyhow::Result<DepthMaskRun> {
    // region: workload depth-mask
    let (side, iterations) = if quick { (128, 64) } else { (256, 256) };
    // endregion
    let mut rows = Vec::new();
    let expensive = depth_mask::cpu_expensive(side, side, iterations);
    for shape in [MaskShape::Blobs, MaskShape::Scattered] {
        let mask = depth_mask::mask(shape, side, side, 1);
        let passes = DepthMask::new(opts.gl, &mask, side, side)?;
        for fraction in FRACTIONS {
            rows.push(depth_mask_row(
                opts.gl,
                &passes,
                &mask,
                shape,
                side,
                fraction,
                iterations,
                Some(&expensive),
                runs,
            )?);
            // The picture is the coherent mask at 25%, the row's masked picture still in
            // the target.
            if shape == MaskShape::Blobs && fraction == DEPTH_MASK_PICTURE_FRACTION {
                depth_mask_picture(opts, &passes, &mask, &expensive, side, fraction)?;
            }
        }
    }
    Ok(DepthMaskRun {
        side,
        iterations,
        rows,
    })
}

/// The depth-mask picture: the active pixels, the depth-masked shader's picture (the
/// expensive function where the mask is active, 0 elsewhere) and its difference to the CPU's.
fn depth_mask_picture(
    opts: &BenchOptions,
    passes: &DepthMask,
    mask: &[f32],
    expensive: &[f64],
    side: u32,
    fraction: f32,
) -> anyhow::Result<()> {
    use crate::gl::picture::{Panel, Scale};
    let gpu = passes.read()?;
    let (cpu, _) = depth_mask::cpu_masked(expensive, mask, fraction);
    let active: Vec<f32> = mask
        .iter()
        .map(|&m| if m < fraction { 1.0 } else { 0.0 })
        .collect();
    let difference: Vec<f32> = gpu.iter().zip(&cpu).map(|(&g, &c)| g - c as f32).collect();
    let panel = |title: String, values: Vec<f32>| Panel {
        scale: Scale::of([values.as_slice()]),
        title,
        values,
        width: side,
        height: side,
    };
    let percent = (fraction * 100.0).round();
    let panels = [
        panel(format!("active pixels (1: mask below {percent}%)"), active),
        panel("depth-masked shader's picture".into(), gpu),
        panel("GPU minus CPU".into(), difference),
    ];
    Ok(crate::gl::dump::picture_png(
        &panels,
        (1200, 560),
        &opts.out_dir.join(images::DEPTH_MASK_PNG),
    )?)
}

/// The fraction of the depth-mask picture (coherent mask).
const DEPTH_MASK_PICTURE_FRACTION: f32 = 0.25;

/// One mask and fraction: both versions timed, their fragments counted, their pictures
/// checked against the CPU's (from `expensive`, [`depth_mask::cpu_expensive`] of this size
/// and iteration count, where a sweep computed it once).
///
/// The checked pictures are those of each version's last timed run (every run draws the
/// same), so `passes.target` holds the depth-masked picture afterwards. Both versions are
/// warmed up first at one iteration per pixel (the iterations are a uniform: same programs
/// and states).
#[allow(clippy::too_many_arguments)]
pub fn depth_mask_row(
    ctx: &Context,
    passes: &DepthMask,
    mask: &[f32],
    shape: MaskShape,
    side: u32,
    fraction: f32,
    iterations: u32,
    expensive: Option<&[f64]>,
    runs: Runs,
) -> anyhow::Result<DepthMaskRow> {
    depth_mask::check_parameters(fraction, iterations)?;
    let (cpu, active) = match expensive {
        Some(values) => depth_mask::cpu_masked(values, mask, fraction),
        None => depth_mask::cpu_picture(mask, side, side, fraction, iterations),
    };
    let error = |gpu: Vec<f32>| {
        gpu.iter()
            .zip(&cpu)
            .map(|(&g, &c)| (g as f64 - c).abs())
            .fold(0.0, f64::max)
    };
    passes.run_branching(fraction, 1)?;
    passes.run_masked(fraction, 1)?;
    let mut branching_fragments = 0;
    let branching = gpu_ms_warm(ctx, runs, || {
        branching_fragments = passes.run_branching(fraction, iterations)?;
        Ok(())
    })?;
    let mut max_error = error(passes.read()?);
    let mut masked_fragments = 0;
    let masked = gpu_ms_warm(ctx, runs, || {
        masked_fragments = passes.run_masked(fraction, iterations)?;
        Ok(())
    })?;
    max_error = max_error.max(error(passes.read()?));
    // The shader's runs, counted: every pixel without the mask (the counter counts runs),
    // then behind it (last, so that the target keeps the depth-masked picture).
    let masked_invocations = passes.count_invocations(fraction, iterations, true)?;
    let unmasked_runs = passes.count_runs(fraction, iterations, false)?;
    let masked_runs = passes.count_runs(fraction, iterations, true)?;
    if masked_runs.is_some() {
        max_error = max_error.max(error(passes.read()?));
    }
    Ok(DepthMaskRow {
        mask: shape,
        fraction,
        active,
        pixels: side as u64 * side as u64,
        active_quads: depth_mask::active_quads(mask, side, side, fraction),
        masked_runs,
        unmasked_runs,
        masked_invocations,
        counted_by: passes.run_counter(),
        masked_fragments,
        branching_fragments,
        branching_ms: branching.median,
        branching_spread: branching,
        masked_ms: masked.median,
        masked_spread: masked,
        max_error,
    })
}

/// `n` values in [0, 1), skewed (a cube of uniform numbers), from the CPU generator.
pub fn skewed_values(n: usize, seed: u64) -> Vec<f32> {
    let mut g = HybridTaus::seeded(seed, 0);
    (0..n).map(|_| g.next_f32().powi(3)).collect()
}

/// The draw calls of one blended histogram of `data`, as the gl layer's profiler counts them
/// (every draw of a pass is recorded under the pass's name); `None` while a profile of the
/// caller's runs, which this does not interrupt.
fn blend_draws(ctx: &Context, histogram: &Histogram, data: &Values) -> anyhow::Result<Option<u64>> {
    if crate::gl::profile::is_on(ctx) {
        return Ok(None);
    }
    crate::gl::profile::start_wall_only(ctx);
    let drawn = histogram.draw(data, blend_histogram::Method::Blend);
    let profile = crate::gl::profile::finish(ctx);
    drawn?;
    Ok(profile.map(|p| {
        p.rows
            .iter()
            .filter(|row| row.name == "histogram")
            .map(|row| row.calls)
            .sum()
    }))
}

/// Values of the histogram passes' warm-up.
const WARM_UP_VALUES: usize = 256;

/// Technique 7: the histogram of `values` into `bins`, blended (and gathered if asked),
/// against the CPU's.
pub fn histogram_row(
    ctx: &Context,
    values: &[f32],
    bins: Bins,
    with_gather: bool,
    runs: Runs,
) -> anyhow::Result<HistogramRow> {
    let (cpu, _) = blend_histogram::cpu_histogram(values, None, &bins);
    let data = Values::new(ctx, values, None)?;
    let histogram = Histogram::new(ctx, bins)?;
    let equal = |h: &Histogram| -> anyhow::Result<bool> {
        Ok(h.read()?.iter().map(|&c| c as f64).eq(cpu.iter().copied()))
    };
    // Warm-up: each timed pass once over the first few values (same programs and state).
    let few = Values::new(ctx, &values[..values.len().min(WARM_UP_VALUES)], None)?;
    histogram.draw(&few, blend_histogram::Method::Blend)?;
    if with_gather {
        histogram.draw(&few, blend_histogram::Method::Gather)?;
    }
    let blend = gpu_ms_warm(ctx, runs, || {
        Ok(histogram.draw(&data, blend_histogram::Method::Blend)?)
    })?;
    let blend_draws = blend_draws(ctx, &histogram, &data)?;
    let counts = histogram.read()?;
    let blend_equal = counts.iter().map(|&c| c as f64).eq(cpu.iter().copied());
    let (gather, gather_equal) = if with_gather {
        let spread = gpu_ms_warm(ctx, runs, || {
            Ok(histogram.draw(&data, blend_histogram::Method::Gather)?)
        })?;
        (Some(spread), Some(equal(&histogram)?))
    } else {
        (None, None)
    };
    let cpu = wall_ms(runs, || blend_histogram::cpu_histogram(values, None, &bins));
    Ok(HistogramRow {
        values: values.len(),
        bins: bins.bins,
        counts,
        blend_equal,
        gather_equal,
        blend_draws,
        blend_ms: blend.median,
        blend_spread: blend,
        gather_ms: gather.map(|g| g.median),
        gather_spread: gather,
        cpu_ms: cpu.median,
        cpu_spread: cpu,
    })
}
