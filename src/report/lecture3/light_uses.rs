//! Technique 3's other uses of the light hierarchy, measured: normal-aware clustering against
//! the fixed merge on the room, subsurface scattering and environment light on the bunny, each
//! tree search against the brute-force sum, GPU against the CPU reference (f64).

use super::images::Rgba;
use crate::gl::Context;
use crate::lecture3::light_hierarchy::light::{brute_force_with, tree_gather_with};
use crate::lecture3::light_hierarchy::normal_cone::{
    compare_clustering, relative_rms, ClusteringRow, MIN_COHERENCE,
};
use crate::lecture3::light_hierarchy::shade::Terms;
use crate::lecture3::light_hierarchy::uses::{base_exposure, default_scene};
use crate::lecture3::light_hierarchy::{Gather, IndirectLighting, LightUse, Scene};
use crate::lecture3::map_on_all_cores;
use crate::report::{BenchOptions, Figure};
use glam::DVec3;
use serde::Serialize;

/// One use of the hierarchy on one scene: the brute force, then each criterion.
#[derive(Clone, Debug, Serialize)]
pub struct UseRun {
    /// `indirect`, `sss` or `environment`.
    pub mode: String,
    /// Lights (VPLs, irradiance samples or sky directions) that carry light.
    pub lights: usize,
    /// The side of their image.
    pub side: u32,
    pub image: (u32, u32),
    pub receivers: usize,
    /// Largest |GPU - CPU| of the brute-force sums, over the largest CPU value.
    pub brute_gpu_vs_cpu: f64,
    pub rows: Vec<UseRow>,
}

/// One criterion of a [`UseRun`].
#[derive(Clone, Debug, Serialize)]
pub struct UseRow {
    pub theta: f32,
    /// Normal-aware clustering's coherence (0: the fixed merge).
    pub min_coherence: f32,
    /// Relative RMS error of the GPU tree search against the GPU brute force.
    pub relative_rms_error: f64,
    /// The same on the CPU (f64): tree against brute force.
    pub cpu_relative_rms_error: f64,
    /// Largest |GPU - CPU| of the tree search over the largest CPU value, on the receivers
    /// whose decisions are not within 1e-4 of a threshold.
    pub tree_gpu_vs_cpu: f64,
    /// Receivers left out of that comparison (a decision within 1e-4 of its threshold).
    pub marginal: usize,
    /// Nodes visited per receiver (GPU).
    pub mean_nodes: f64,
    /// Lights or clusters summed per receiver (CPU traversal of the same hierarchy).
    pub mean_gathered: f64,
}

/// Runs `light_use` on `scene`: lights of a `side x side` image, `width x height` receivers,
/// the brute force and each theta, GPU and CPU. The lighting is returned with the last
/// criterion's gather in its target.
pub fn use_run(
    ctx: &Context,
    light_use: LightUse,
    scene: Scene,
    side: u32,
    (width, height): (u32, u32),
    thetas: &[f32],
    min_coherence: f32,
) -> anyhow::Result<(UseRun, IndirectLighting)> {
    let lighting = IndirectLighting::for_use(ctx, light_use, scene, side, width, height)?;
    lighting.build_lights()?;
    lighting.draw_receivers()?;
    lighting.gather(Gather::BruteForce)?;
    let brute = lighting.gathers.read()?;
    let receivers = lighting.gbuffer.receivers()?;
    let covered: Vec<bool> = receivers.iter().map(Option::is_some).collect();
    let levels = lighting.clusters.read_atlas_levels()?;
    let kernel = light_use.kernel();
    let (cpu_brute, _) = map_on_all_cores(&receivers, |r| {
        r.map_or([0.0; 4], |r| rgb(brute_force_with(&r, &levels[0], &kernel)))
    });
    let largest = cpu_brute
        .iter()
        .flat_map(|c| [c[0], c[1], c[2]])
        .fold(0.0f32, f32::max)
        .max(f32::MIN_POSITIVE) as f64;
    let difference = |a: &[f32; 4], b: &[f32; 4]| -> f64 {
        (0..3)
            .map(|c| (a[c] as f64 - b[c] as f64).abs())
            .fold(0.0, f64::max)
    };
    let brute_gpu_vs_cpu = brute
        .iter()
        .zip(&cpu_brute)
        .map(|(g, c)| difference(g, c))
        .fold(0.0, f64::max)
        / largest;
    let count = covered.iter().filter(|&&c| c).count();
    let mut rows = Vec::with_capacity(thetas.len());
    for &theta in thetas {
        let gather = Gather::normal_aware(theta, min_coherence)?;
        let criterion = gather.criterion().expect("a tree gather");
        lighting.gather(gather)?;
        let gpu = lighting.gathers.read()?;
        let (cpu, _) = map_on_all_cores(&receivers, |r| {
            r.map(|r| tree_gather_with(&r, &levels, criterion, &kernel))
        });
        let cpu_rgb: Vec<[f32; 4]> = cpu
            .iter()
            .map(|t| t.map_or([0.0; 4], |t| rgb(t.irradiance)))
            .collect();
        let judged = || {
            cpu.iter()
                .zip(&gpu)
                .filter_map(|(t, g)| Some((t.as_ref()?, g)))
        };
        let marginal = judged().filter(|(t, _)| t.margin < 1e-4).count();
        let tree_gpu_vs_cpu = judged()
            .filter(|(t, _)| t.margin >= 1e-4)
            .map(|(t, g)| difference(g, &rgb(t.irradiance)))
            .fold(0.0, f64::max)
            / largest;
        rows.push(UseRow {
            theta,
            min_coherence,
            relative_rms_error: relative_rms(&gpu, &brute, &covered),
            cpu_relative_rms_error: relative_rms(&cpu_rgb, &cpu_brute, &covered),
            tree_gpu_vs_cpu,
            marginal,
            mean_nodes: gpu
                .iter()
                .zip(&covered)
                .filter(|(_, &c)| c)
                .map(|(g, _)| g[3] as f64)
                .sum::<f64>()
                / count.max(1) as f64,
            mean_gathered: judged().map(|(t, _)| t.gathered as f64).sum::<f64>()
                / count.max(1) as f64,
        });
    }
    for value in rows
        .iter()
        .flat_map(|r| {
            [
                r.relative_rms_error,
                r.cpu_relative_rms_error,
                r.tree_gpu_vs_cpu,
            ]
        })
        .chain([brute_gpu_vs_cpu])
    {
        if !value.is_finite() {
            anyhow::bail!(
                "lecture 3 light ({}): an error measure is not finite ({value})",
                light_use.name()
            );
        }
    }
    let lights = levels[0].nodes.iter().filter(|l| l.weight > 0.0).count();
    Ok((
        UseRun {
            mode: light_use.name().into(),
            lights,
            side,
            image: (width, height),
            receivers: count,
            brute_gpu_vs_cpu,
            rows,
        },
        lighting,
    ))
}

fn rgb(v: DVec3) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, 0.0]
}

/// What the report measures: the clustering comparison on the room and the two other uses on
/// the bunny.
#[derive(Clone, Debug, Serialize)]
pub struct LightUsesRun {
    pub clustering: Vec<ClusteringRow>,
    pub subsurface: UseRun,
    pub environment: UseRun,
}

/// The criteria of the uses' tables.
pub const USE_THETAS: [f32; 4] = [0.0, 0.25, 0.5, 1.0];
/// The criteria of the clustering table.
pub const CLUSTERING_THETAS: [f32; 4] = [0.25, 0.5, 1.0, 2.0];
/// The uses' picture in the report.
pub const USES_PNG: &str = "lecture3_light_uses.png";

/// Measures the uses and writes their picture (subsurface scattering and environment light,
/// brute force and the coarsest criterion) into the report's folder.
pub fn measure(opts: &BenchOptions, ctx: &Context) -> anyhow::Result<LightUsesRun> {
    // The lights of both uses fill a finer image than the room's VPLs, so that the tree has
    // enough lights to group: subsurface scattering's samples are the light's image of the
    // model (the bunny fills about 30% of the fitted light's image: some 300 samples of
    // 32x32), environment light's the sky's lat-long grid.
    // region: workload light-uses
    let (vpls, size, lights_side) = if opts.quick {
        (16, 64, 32)
    } else {
        (32, 128, 64)
    };
    // endregion
    let room = IndirectLighting::new(ctx, Scene::room(), vpls, size, size)?;
    room.build_lights()?;
    room.draw_receivers()?;
    let clustering = compare_clustering(&room, &CLUSTERING_THETAS, MIN_COHERENCE)?;
    let mut pictures = Vec::new();
    let mut run = |light_use: LightUse| -> anyhow::Result<UseRun> {
        let scene = default_scene(&light_use);
        let (run, lighting) = use_run(
            ctx,
            light_use,
            scene,
            lights_side,
            (size, size),
            &USE_THETAS,
            0.0,
        )?;
        let coarse = picture(&lighting)?;
        lighting.gather(Gather::BruteForce)?;
        pictures.push(picture(&lighting)?);
        pictures.push(coarse);
        Ok(run)
    };
    let subsurface = run(LightUse::subsurface())?;
    let environment = run(LightUse::environment())?;
    let titles = [
        "subsurface, brute force",
        "subsurface, coarsest criterion",
        "environment light, brute force",
        "environment light, coarsest criterion",
    ];
    let frames: Vec<(String, image::RgbaImage)> = titles
        .iter()
        .zip(&pictures)
        .map(|(t, p)| (t.to_string(), p.to_image()))
        .collect();
    let scale = (300 / size.max(1)).max(1);
    crate::gl::dump::frames_png(&frames, 4, scale, &[], &opts.out_dir.join(USES_PNG))?;
    Ok(LightUsesRun {
        clustering,
        subsurface,
        environment,
    })
}

fn picture(lighting: &IndirectLighting) -> anyhow::Result<Rgba> {
    lighting.shade(Terms::Indirect, base_exposure(&lighting.light_use))?;
    let fb = &lighting.shade.target;
    Ok(Rgba {
        width: fb.width(),
        height: fb.height(),
        data: fb.read_u8(0, crate::gl::Rect::sized(fb.width(), fb.height()))?,
    })
}

pub fn figure() -> Figure {
    Figure {
        file: USES_PNG.into(),
        caption: format!(
            "3. Subsurface scattering (brute force, theta {0}) and environment light (brute \
             force, theta {0}) on the bunny, from the same light hierarchy",
            USE_THETAS.last().expect("criteria")
        ),
    }
}
