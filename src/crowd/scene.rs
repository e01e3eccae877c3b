//! The scenes of the paper's measurements and the frame loop that times them.
//!
//! - Table 1 / Fig. 3: n characters on a square field, the whole field in view, culling
//!   off and every character at the finest LOD ("all characters processed by GPU").
//! - Fig. 4-5: a large field seen from its edge near the ground, with the three LOD
//!   meshes and view-frustum culling on (the paper's setup), optionally with this project's
//!   sprite level (see [`super::lod`]).
//!
//! The cameras, spacings and paces are this project's: the paper's are not published.
//!
//! Every frame the behaviour layer moves the characters (not timed: it is not part of the
//! rendering method), then culling/LOD choice, bone matrices and the GPU passes are timed
//! by wall clock up to `glFinish`. One extra frame is run with GL timer queries around
//! each pass for the per-pass breakdown.

use std::time::Instant;

use glam::{DAffine3, Vec3};
use serde::Serialize;

use crate::gl::{Context, Framebuffer, GlError, Texture, TextureFormat};

use super::character::{Instances, ModelKind};
use super::culling::{plan_frame, Camera, FramePlan};
use super::lod::LodPolicy;
use super::renderer::{CrowdRenderer, FrameStats, Method};
use super::steering::Crowd;

/// Ground spacing between characters and walking pace for each model.
pub fn spacing_and_pace(kind: ModelKind) -> (f32, f32) {
    match kind {
        ModelKind::Soldier => (2.0, 1.4),
        ModelKind::Horse => (3.5, 5.0),
    }
}

/// A crowd and the camera that looks at it.
pub struct Scene {
    pub crowd: Crowd,
    pub camera: Camera,
    /// LOD and culling (Fig. 4-5) or neither (Table 1).
    pub lod: Option<LodPolicy>,
    pub cull: bool,
}

/// Table 1 / Fig. 3: the whole field in view from above one side, no LOD, no culling.
pub fn table1_scene(kind: ModelKind, n: usize, aspect: f32, seed: u64) -> Scene {
    let (spacing, pace) = spacing_and_pace(kind);
    let crowd = Crowd::new(n, spacing, pace, seed);
    let half = crowd.params.bounds.1.x;
    let fov_y = 45f32.to_radians();
    // The field's corners plus most of a character beyond them.
    let field_radius = half * std::f32::consts::SQRT_2 + 0.6 * spacing;
    let half_fov = (0.5 * fov_y).tan().min((0.5 * fov_y).tan() * aspect);
    // The sphere around the field is a loose fit for a square seen at a slant: 0.8 of the
    // distance that fits the sphere still shows (nearly) the whole field.
    let distance = 0.8 * field_radius / half_fov;
    let target = Vec3::new(0.0, 0.8, 0.0);
    let eye = target + Vec3::new(0.3, 0.7, -1.0).normalize() * distance;
    Scene {
        crowd,
        camera: Camera {
            eye,
            target,
            fov_y,
            aspect,
            near: 0.5,
            far: distance + 2.0 * field_radius,
        },
        lod: None,
        cull: false,
    }
}

/// Fig. 4-5: a large field seen from the middle of one edge, 8 m up, with culling and the
/// levels of `policy` ([`LodPolicy::default`] is the paper's three meshes, no sprites).
pub fn lod_scene(kind: ModelKind, n: usize, aspect: f32, seed: u64, policy: LodPolicy) -> Scene {
    let (spacing, pace) = spacing_and_pace(kind);
    let crowd = Crowd::new(n, spacing, pace, seed);
    let half = crowd.params.bounds.1.x;
    let eye = Vec3::new(0.0, 8.0, -half - 4.0);
    Scene {
        crowd,
        camera: Camera {
            eye,
            target: Vec3::new(0.0, 0.0, 0.0),
            fov_y: 60f32.to_radians(),
            aspect,
            near: 0.5,
            far: 3.0 * half + 10.0,
        },
        lod: Some(policy),
        cull: true,
    }
}

/// The off-screen colour + depth target frames are drawn into.
pub fn scene_target(ctx: &Context, width: u32, height: u32) -> Result<Framebuffer, GlError> {
    let colour = Texture::new_2d(ctx, width, height, TextureFormat::Rgba8)?;
    // Visibility only: 24-bit on the period GPU, which had no float depth.
    let depth = Texture::new_2d(ctx, width, height, ctx.z_buffer_format())?;
    Framebuffer::new(ctx, "crowd scene", &[&colour], Some(&depth))
}

/// Sky colour the scene is cleared to.
pub const SKY: [f32; 4] = [0.62, 0.72, 0.85, 1.0];

/// What a run measured.
#[derive(Clone, Debug, Default, Serialize)]
pub struct RunStats {
    pub model: String,
    pub method: String,
    /// Characters per draw call of the vertex-shader method.
    pub vertex_shader_batch: u32,
    pub characters: usize,
    pub lod_and_culling: bool,
    /// Whether far characters were drawn as sprites (this project's extension).
    pub sprites_enabled: bool,
    pub frames: usize,
    /// Wall clock per frame (culling, bone matrices, GPU passes, glFinish): the median
    /// over the timed frames, so that a frame slowed by another process does not count.
    pub frame_ms: f64,
    /// The fastest and the slowest timed frame, ms: the ends of the runs behind `frame_ms`.
    pub frame_ms_range: [f64; 2],
    pub fps: f64,
    /// Per-pass breakdown of one frame measured with GL timer queries.
    pub passes: FrameStats,
    pub culled: usize,
    pub per_lod: [usize; 3],
}

/// Placements and phases of the crowd's characters.
pub fn placements(crowd: &Crowd) -> (Vec<DAffine3>, Vec<f64>) {
    crowd
        .agents
        .iter()
        .map(|a| (a.model_matrix(), a.phase))
        .unzip()
}

/// Culling and LOD choice of the scene's current frame.
fn plan_of(renderer: &CrowdRenderer, scene: &Scene, models: &[DAffine3]) -> FramePlan {
    let model = &renderer.model;
    plan_frame(
        models,
        model.bound_centre,
        model.bound_radius,
        &scene.camera,
        scene.lod.as_ref(),
        scene.cull,
    )
}

/// Plans and renders one frame (the scene must be cleared by the caller).
pub fn render_frame(
    renderer: &mut CrowdRenderer,
    target: &Framebuffer,
    scene: &Scene,
    method: Method,
    timing: bool,
) -> Result<(FrameStats, FramePlan), GlError> {
    let (models, phases) = placements(&scene.crowd);
    let plan = plan_of(renderer, scene, &models);
    let instances = Instances {
        models: &models,
        phases: &phases,
    };
    let stats = renderer.render(target, &scene.camera, &instances, &plan, method, timing)?;
    Ok((stats, plan))
}

/// Characters per level the warm-up frame draws.
const WARM_UP_PER_LEVEL: usize = 16;

/// The warm-up before a configuration's timed frames: the renderer makes the pass-1
/// resources of the whole crowd ([`CrowdRenderer::prepare`]), then draws one frame with
/// every pass of the configuration on at most [`WARM_UP_PER_LEVEL`] characters per level,
/// which compiles whatever the renderer compiles on first use. A frame of the whole crowd
/// would do the same at the cost of a timed frame (the largest crowds take seconds each).
fn warm_up(
    renderer: &mut CrowdRenderer,
    target: &Framebuffer,
    scene: &Scene,
    config: &Config,
) -> Result<(), GlError> {
    renderer.set_vertex_shader_batch(config.vertex_shader_batch);
    let (models, phases) = placements(&scene.crowd);
    let plan = plan_of(renderer, scene, &models);
    renderer.prepare(&plan)?;
    let instances = Instances {
        models: &models,
        phases: &phases,
    };
    clear(target)?;
    renderer.render(
        target,
        &scene.camera,
        &instances,
        &plan.truncated(WARM_UP_PER_LEVEL),
        config.method,
        false,
    )?;
    Ok(())
}

/// Clears `target` to the sky and the far depth, as every frame starts.
pub fn clear(target: &Framebuffer) -> Result<(), GlError> {
    target.clear_colors(SKY)?;
    target.clear_depth_stencil(1.0, 0)
}

/// The median of `values` (the mean of the middle two for an even count).
pub(crate) fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    match values.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => values[n / 2],
        n => 0.5 * (values[n / 2 - 1] + values[n / 2]),
    }
}

/// The smallest and largest of `values` (NaN for none).
pub(crate) fn range(values: &[f64]) -> [f64; 2] {
    if values.is_empty() {
        return [f64::NAN; 2];
    }
    values
        .iter()
        .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], &v| {
            [lo.min(v), hi.max(v)]
        })
}

/// How one measured configuration renders: the method, and for the vertex-shader method
/// how many characters go in one draw call (`u32::MAX`: as many as the uniforms hold);
/// whether its runs end with a frame timed stage by stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Config {
    pub method: Method,
    pub vertex_shader_batch: u32,
    /// A last frame with every stage inside a timer query and between `glFinish` calls,
    /// untimed as a frame: its stage times fill [`RunStats::passes`]. Without it they are
    /// zero (the counts are the last timed frame's), and the run is its timed frames alone.
    pub stage_times: bool,
}

impl Config {
    pub fn new(method: Method) -> Self {
        Self {
            method,
            vertex_shader_batch: u32::MAX,
            stage_times: true,
        }
    }
}

/// Runs a warm-up (see `warm_up`), `frames` wall-clock-timed frames and (where the
/// configuration asks for stage times) one frame with per-stage timing. The crowd walks `dt`
/// seconds per frame.
pub fn run(
    ctx: &Context,
    renderer: &mut CrowdRenderer,
    target: &Framebuffer,
    scene: &mut Scene,
    method: Method,
    frames: usize,
    dt: f32,
) -> Result<RunStats, GlError> {
    let configs = [Config::new(method)];
    let mut runs = run_side_by_side(
        ctx,
        renderer,
        target,
        std::slice::from_mut(scene),
        &configs,
        frames,
        dt,
        |_, _| Ok::<(), GlError>(()),
    )?;
    Ok(runs.remove(0))
}

/// For each scene, the first earlier scene whose crowd equals its own (agents, parameters
/// and random stream), if any: stepped alike, the two stay equal ([`step_crowd`]).
pub fn crowd_sources(scenes: &[Scene]) -> Vec<Option<usize>> {
    (0..scenes.len())
        .map(|j| (0..j).find(|&k| scenes[k].crowd == scenes[j].crowd))
        .collect()
}

/// Steps scene `i`'s crowd by `dt`, in a round that steps the scenes in order: a crowd with
/// a source ([`crowd_sources`]) becomes a copy of it, already stepped this round, instead of
/// taking the same step again.
pub fn step_crowd(scenes: &mut [Scene], sources: &[Option<usize>], i: usize, dt: f32, stride: f64) {
    match sources[i] {
        Some(k) => {
            let (before, from_i) = scenes.split_at_mut(i);
            from_i[0].crowd.clone_from(&before[k].crowd);
        }
        None => scenes[i].crowd.step(dt, stride),
    }
}

/// Measures several configurations side by side: frame by frame in turn, each on its own
/// copy of the scene, so that whatever else the machine is doing slows them alike. Each
/// gets a warm-up (`warm_up`), `frames` timed frames (median reported) and one frame
/// with per-stage timing. Copies of one crowd are stepped once per round ([`step_crowd`]).
///
/// `shown(i, target)` is called right after configuration `i`'s per-stage frame, while
/// `target` still holds it: a caller that wants a picture of a configuration's last frame
/// takes it there instead of drawing the frame again.
#[allow(clippy::too_many_arguments)]
pub fn run_side_by_side<E: From<GlError>>(
    ctx: &Context,
    renderer: &mut CrowdRenderer,
    target: &Framebuffer,
    scenes: &mut [Scene],
    configs: &[Config],
    frames: usize,
    dt: f32,
    mut shown: impl FnMut(usize, &Framebuffer) -> Result<(), E>,
) -> Result<Vec<RunStats>, E> {
    assert_eq!(scenes.len(), configs.len(), "one scene per configuration");
    let stride = renderer.model.clip.stride;
    let mut times_ms = vec![Vec::with_capacity(frames); configs.len()];
    let frame = |renderer: &mut CrowdRenderer, scene: &Scene, config: &Config, timing: bool| {
        renderer.set_vertex_shader_batch(config.vertex_shader_batch);
        clear(target)?;
        let result = render_frame(renderer, target, scene, config.method, timing);
        ctx.finish_all();
        result
    };
    for (scene, config) in scenes.iter().zip(configs) {
        warm_up(renderer, target, scene, config)?;
        ctx.finish_all();
    }
    let sources = crowd_sources(scenes);
    // Each configuration's last timed frame: its counts (draws, sprites) and plan.
    let mut last = vec![None; configs.len()];
    for _ in 0..frames {
        for (i, (config, times)) in configs.iter().zip(&mut times_ms).enumerate() {
            step_crowd(scenes, &sources, i, dt, stride);
            let started = Instant::now();
            let stats = frame(renderer, &scenes[i], config, false)?;
            times.push(started.elapsed().as_secs_f64() * 1e3);
            last[i] = Some(stats);
        }
    }
    let mut out = Vec::with_capacity(configs.len());
    for (i, (config, times)) in configs.iter().zip(&mut times_ms).enumerate() {
        let (passes, plan) = match last[i].take() {
            // The last timed frame's counts and plan; no stage times.
            Some(stats) if !config.stage_times => {
                renderer.set_vertex_shader_batch(config.vertex_shader_batch);
                stats
            }
            _ => {
                step_crowd(scenes, &sources, i, dt, stride);
                let stats = frame(renderer, &scenes[i], config, true)?;
                shown(i, target)?;
                stats
            }
        };
        let scene = &scenes[i];
        let frame_ms = median(times);
        out.push(RunStats {
            frame_ms_range: range(times),
            model: renderer.model.kind.name().to_string(),
            method: config.method.name().to_string(),
            vertex_shader_batch: renderer.vertex_shader_batch(),
            characters: scene.crowd.agents.len(),
            lod_and_culling: scene.lod.is_some(),
            sprites_enabled: scene.lod.is_some_and(|p| p.sprites_beyond.is_some()),
            frames,
            frame_ms,
            fps: 1e3 / frame_ms,
            passes,
            culled: plan.culled,
            per_lod: [0, 1, 2].map(|l| plan.lods[l].len()),
        });
    }
    Ok(out)
}
