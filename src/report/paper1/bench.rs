//! The measurements: every scene of Table III through the streaming pipeline, SOLID and
//! CULLIDE frame by frame (Tables III-IV, Fig. 8-12); CULLIDE's resolution; the readback
//! curves of Fig. 7 on clustered and on uniform `P0` contents; the readback schemes on real
//! frames; the tiles of Sec. 5.5; the leaf-size sweep. Numbers only: the tables and figures
//! are built from [`Paper1Results`] elsewhere.

use super::Paper1Args;
use crate::collide::cullide::{Cullide, CullideResult};
use crate::collide::pipeline::{FrameResult, LazyCalibration, Options, StreamingCollider};
use crate::collide::reduction::{P0Contents, HIER_BLOCK};
use crate::collide::reduction_gpu::{self, CalibrationPoint, ReadbackMode, Reduction};
use crate::collide::scenes::{Scene, SCENES};
use crate::collide::stream_setup::{auto_leaf_size_for_pair, max_slots, DEFAULT_LEAF_SIZE};
use crate::collide::streaming_test::PairTarget;
use crate::collide::tri_test::{test_caps, ModelView, Predicate, PrimitiveResult};
use crate::collide::{solid, AabbStream};
use crate::gl::profile::{self, ProfileTable};
use crate::mesh::Mesh;
use crate::report::evidence::{PairDigest, PairSet};
use crate::report::BenchOptions;
use crate::timing::Load;
use glam::Vec3;
use serde::Serialize;
use std::time::Instant;

/// Everything the section measures.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Paper1Results {
    pub renderer: String,
    pub quick: bool,
    pub setup: Setup,
    pub scenes: Vec<SceneRun>,
    pub cullide_resolutions: CullideResolutions,
    pub fig7: Fig7,
    pub readback_schemes: ReadbackSchemes,
    pub tiles: TileStudy,
    /// Empty when the sweep was skipped.
    pub leaf_sweep: Vec<SweepPoint>,
    /// Classic vs compute vs CPU: the 2007 formulation beside today's compute shaders.
    pub then_and_now: crate::report::then_and_now::ThenAndNow,
    /// Where the time of this run went, pass by pass.
    pub profile: Option<ProfileTable>,
    /// The machine's load when the scenes' timings ended (the frame-time claims).
    pub scenes_load: Option<Load>,
    /// The machine's load when Fig. 7's timings ended (the readback claims).
    pub fig7_load: Option<Load>,
}

/// How the run was set up.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Setup {
    /// Frames per scene, after one warm-up frame.
    pub frames: usize,
    /// Triangles per model when not the paper's.
    pub triangles: Option<usize>,
    /// The leaf size given on the command line; `None`: chosen per model.
    pub forced_leaf_size: Option<usize>,
    /// The automatic leaf size's bound on stream slots for this renderer.
    pub max_slots: usize,
    pub software_renderer: bool,
    pub cullide_resolution: u32,
}

/// Fig. 7: every scheme at each `eta`, on a `p0 x p0` `P0` filled two ways.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Fig7 {
    pub p0: usize,
    /// CAPs in blobs, as the scenes make them (what Sec. 5.3.1 assumes).
    pub clustered: Fig7Curve,
    /// CAPs uniformly at random.
    pub uniform: Fig7Curve,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct Fig7Curve {
    /// In increasing `eta`.
    pub points: Vec<CalibrationPoint>,
    /// The paper's crossover: from this `eta` on the reduced scheme beats the hierarchical
    /// one ([`reduction_gpu::crossover`]).
    pub crossover_eta: Option<f64>,
    /// Where `auto` leaves the hierarchical scheme: the first `eta` at which it is not the
    /// fastest of the three ([`reduction_gpu::measured_threshold`]).
    pub auto_switch_eta: Option<f64>,
}

impl Fig7Curve {
    fn of(points: Vec<CalibrationPoint>) -> Fig7Curve {
        Fig7Curve {
            crossover_eta: reduction_gpu::crossover(&points),
            auto_switch_eta: reduction_gpu::measured_threshold(&points),
            points,
        }
    }
}

/// Averages over the frames of one scene.
#[derive(Clone, Debug, Default, Serialize)]
pub struct SceneRun {
    pub name: String,
    pub label: String,
    pub triangles: usize,
    /// Leaf size `n` used for this scene.
    pub leaf_size: usize,
    pub leaves: [usize; 2],
    pub p0: [usize; 2],
    pub frames: usize,
    pub stream: FrameResult,
    pub schemes: Vec<String>,
    /// SOLID: refit, traversal and triangle test, ms; and its CAPs.
    pub solid_refit: f64,
    pub solid_traverse: f64,
    pub solid_tri: f64,
    /// Frames in which SOLID's pairs equal the streaming pairs.
    pub solid_agrees: usize,
    /// The streaming pairs of every counted frame, as a set (`compare --baseline` checks that
    /// it does not change).
    pub pair_set: PairSet,
    pub cullide: CullideResult,
    pub cullide_missing_percent: f64,
    /// Mean CAPs per set `P1` texel (4x4 block of the slot pairs): how clustered this
    /// scene's CAPs are (1 when no two share a block).
    pub caps_per_set_p1_texel: f64,
    /// Each counted frame's times, for Fig. 10-12.
    pub frame_times: Vec<FrameTimes>,
    /// The Fig. 8-9 style snapshot of the last frame (file in the output folder).
    pub snapshot: Option<String>,
}

/// One frame's times (ms) as Fig. 10-12 split them.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct FrameTimes {
    /// Overlap test (with its stencil), readback and stream update (Fig. 10-11's streaming
    /// time).
    pub stream_cull: f64,
    /// Texture download, shown apart in Fig. 10-11.
    pub stream_download: f64,
    pub stream_tri_test: f64,
    /// The whole frame, wall clock (Fig. 12).
    pub stream_total: f64,
    /// Refit and traversal (Fig. 10-11's SOLID time).
    pub solid_cull: f64,
    pub solid_tri_test: f64,
    /// Pruning and triangle test (Fig. 12).
    pub cullide_total: f64,
}

impl SceneRun {
    /// The paper's culling time of Fig. 10-11: overlap test (with its stencil), readback and
    /// stream update.
    pub fn stream_cull_ms(&self) -> f64 {
        let t = &self.stream.timings;
        t.overlap + t.stencil + t.encode + t.readback + t.update
    }

    /// SOLID's culling: refit and traversal.
    pub fn solid_cull_ms(&self) -> f64 {
        self.solid_refit + self.solid_traverse
    }

    /// CULLIDE's whole frame: pruning and the triangle test.
    pub fn cullide_total_ms(&self) -> f64 {
        self.cullide.pruning_ms + self.cullide.tri_test_ms
    }
}

/// CULLIDE at several resolutions on the interlocking tori (Sec. 7.4.2).
#[derive(Clone, Debug, Default, Serialize)]
pub struct CullideResolutions {
    pub frames: usize,
    pub rows: Vec<CullideResolutionRow>,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct CullideResolutionRow {
    pub resolution: u32,
    /// Pruning + triangle test, mean ms per frame.
    pub ms: f64,
    pub pctps: u64,
    pub missing_percent: f64,
}

/// Each readback scheme forced in turn on the interlocking tori's frames.
#[derive(Clone, Debug, Default, Serialize)]
pub struct ReadbackSchemes {
    pub p0: usize,
    pub frames: usize,
    pub rows: Vec<SchemeRun>,
}

/// Means per frame of one scheme.
#[derive(Clone, Debug, Serialize)]
pub struct SchemeRun {
    pub scheme: ReadbackMode,
    pub eta: f64,
    pub encode_ms: f64,
    pub decode_ms: f64,
    pub bytes: f64,
}

/// Sec. 5.5's tiles: the interlocking tori at leaf sizes that double the streams, each run
/// in tiles of a fixed side (one tile at the smallest size) and as one rectangle.
#[derive(Clone, Debug, Default, Serialize)]
pub struct TileStudy {
    pub scene: String,
    pub triangles: usize,
    pub frames: usize,
    /// Tile side (slots).
    pub tile: usize,
    pub readback: ReadbackMode,
    pub rows: Vec<TileRow>,
}

#[derive(Clone, Debug, Default, Serialize)]
pub struct TileRow {
    pub leaf_size: usize,
    /// Slots of each stream.
    pub slots: [usize; 2],
    pub tiles: usize,
    pub tiled: CullTimes,
    /// The same frames as one rectangle (one tile).
    pub one_rectangle: CullTimes,
    /// CAPs per frame (the pairs are checked equal both ways).
    pub caps: usize,
}

/// The GPU culling stages of one frame, ms.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct CullTimes {
    pub overlap: f64,
    pub stencil: f64,
    pub encode: f64,
    /// Reading back and decoding (wall).
    pub readback: f64,
}

impl CullTimes {
    pub fn total(&self) -> f64 {
        self.overlap + self.stencil + self.encode + self.readback
    }
}

/// The default leaf size, justified: interlocking tori at several `n`.
#[derive(Clone, Debug, Serialize)]
pub struct SweepPoint {
    pub leaf_size: usize,
    pub p0: usize,
    pub total_ms: f64,
    pub overlap_ms: f64,
    pub tri_ms: f64,
    pub pctps: u64,
}

// region: workload tori-size
/// Triangles per model for the fixed studies (tori): the paper's 15K, or 2000 in quick mode.
fn study_triangles(quick: bool) -> Option<usize> {
    if quick {
        Some(2000)
    } else {
        None
    }
}
// endregion

pub fn measure(opts: &BenchOptions, args: &Paper1Args) -> anyhow::Result<Paper1Results> {
    let (mut results, table) =
        crate::report::profile::profiled(opts.gl, || measure_all(opts, args))?;
    results.profile = Some(table);
    Ok(results)
}

fn measure_all(opts: &BenchOptions, args: &Paper1Args) -> anyhow::Result<Paper1Results> {
    let quick = opts.quick;
    // region: workload scenes
    let frames = args.frames.unwrap_or(if quick { 3 } else { 20 });
    let triangles = args.triangles.or(study_triangles(quick));
    let scenes: Vec<String> = if args.scenes.is_empty() {
        SCENES.iter().map(|s| s.to_string()).collect()
    } else {
        args.scenes.clone()
    };
    // endregion
    let bar = opts.progress.add(indicatif::ProgressBar::new(
        (scenes.len() * (frames + 1)) as u64,
    ));
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg} {bar:30} {pos}/{len} frames")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let mut runs = Vec::new();
    let mut calibrations = Calibrations::default();
    let scope = profile::scope(opts.gl, "Table III scenes (streaming, SOLID, CULLIDE)");
    for name in &scenes {
        bar.set_message(format!("paper 1: {name}"));
        runs.push(run_scene(
            opts,
            name,
            frames,
            triangles,
            args,
            &bar,
            &mut calibrations,
        )?);
    }
    drop(scope);
    bar.finish_and_clear();
    crate::timing::mark("paper1: Table III scenes");
    let scenes_load = Load::now();
    let tori_leaf_size = args.leaf_size.unwrap_or(DEFAULT_LEAF_SIZE);
    let cullide_resolutions = study(opts, "CULLIDE resolutions", || {
        cullide_resolutions(opts, tori_leaf_size)
    })?;
    crate::timing::mark("paper1: CULLIDE resolutions");
    let fig7 = study(opts, "Fig. 7 readback curves", || fig7(opts))?;
    crate::timing::mark("paper1: Fig. 7 readback curves");
    let fig7_load = Load::now();
    let software = opts.gl.info().is_software();
    Ok(Paper1Results {
        renderer: opts.gl.info().renderer_line(),
        quick,
        setup: Setup {
            frames,
            triangles,
            forced_leaf_size: args.leaf_size,
            max_slots: max_slots(software),
            software_renderer: software,
            cullide_resolution: args.cullide_resolution,
        },
        scenes: runs,
        cullide_resolutions,
        fig7,
        readback_schemes: study(opts, "readback schemes on real frames", || {
            readback_schemes(opts, tori_leaf_size, frames, &mut calibrations)
        })?,
        tiles: study(opts, "tiles (Sec. 5.5)", || tile_study(opts))?,
        leaf_sweep: if args.no_leaf_sweep {
            Vec::new()
        } else {
            study(opts, "leaf-size sweep", || {
                leaf_sweep(opts, &mut calibrations)
            })?
        },
        then_and_now: super::then_and_now::measure(opts)?,
        profile: None,
        scenes_load,
        fig7_load,
    })
}

/// `auto`'s calibrations made so far in this run, by `P0` size. `auto` is calibrated per
/// `P0` size and lazily: a point is measured when a frame first needs it
/// ([`StreamingCollider::calibrate_lazily`]), and the colliders of one size (the tori
/// scenes, the readback schemes and the sweep share sizes) share the points measured.
#[derive(Default)]
struct Calibrations(Vec<((usize, usize), LazyCalibration)>);

impl Calibrations {
    fn collider(
        &mut self,
        ctx: &crate::gl::Context,
        x: &Mesh,
        y: &Mesh,
        options: Options,
    ) -> anyhow::Result<StreamingCollider> {
        let mut c = StreamingCollider::new_uncalibrated(ctx, x, y, options)?;
        if options.readback == ReadbackMode::Auto {
            let size = (c.target.width(), c.target.height());
            let lazy = match self.0.iter().position(|(s, _)| *s == size) {
                Some(k) => self.0.swap_remove(k).1,
                None => LazyCalibration::new(
                    &reduction_gpu::CALIBRATION_ETAS,
                    reduction_gpu::CALIBRATION_REPEATS,
                ),
            };
            c.calibrate_lazily(lazy);
        }
        Ok(c)
    }

    /// Keep the points `c` measured for the next collider of its size.
    fn keep(&mut self, c: &mut StreamingCollider) {
        if let Some(lazy) = c.take_lazy_calibration() {
            self.0.push(((c.target.width(), c.target.height()), lazy));
        }
    }
}

/// One study of the section, a named scope of the profile.
fn study<T>(
    opts: &BenchOptions,
    name: &str,
    run: impl FnOnce() -> anyhow::Result<T>,
) -> anyhow::Result<T> {
    let _scope = profile::scope(opts.gl, name);
    run()
}

/// One model as the tests see it: mesh, current positions, stream.
type Model<'a> = (&'a Mesh, &'a [Vec3], &'a AabbStream);

fn model_view<'a>(m: Model<'a>) -> ModelView<'a> {
    ModelView {
        triangles: &m.0.triangles,
        positions: m.1,
        stream: m.2,
    }
}

/// SOLID's answer (equal to the exact one: see the tests): refit, traverse, triangle test.
fn solid_pairs(x: Model, y: Model) -> PrimitiveResult {
    let bx = solid::refit(x.2, x.1);
    let by = solid::refit(y.2, y.1);
    let caps = solid::overlapping_leaves(x.2, &bx, y.2, &by);
    test_caps(model_view(x), model_view(y), &caps, Predicate::Moller)
}

/// CULLIDE at several resolutions on the interlocking tori: "a higher image space
/// resolution can reduce missing collisions, but then it requires more time" (Sec. 7.4.2).
fn cullide_resolutions(
    opts: &BenchOptions,
    leaf_size: usize,
) -> anyhow::Result<CullideResolutions> {
    let scene = Scene::build("interlocking-tori", study_triangles(opts.quick))?;
    let (x, y) = (&scene.x.rest, &scene.y.rest);
    let sx = AabbStream::build(x, leaf_size)?;
    let sy = AabbStream::build(y, leaf_size)?;
    let frames = if opts.quick { 1 } else { 3 };
    // The frames and their exact pairs, the same at every resolution: computed once (none
    // for the warm-up frame 0).
    let positions: Vec<(Vec<Vec3>, Vec<Vec3>)> = (0..=frames).map(|f| scene.frame(f)).collect();
    let exact: Vec<PrimitiveResult> = positions
        .iter()
        .skip(1)
        .map(|(px, py)| solid_pairs((x, px, &sx), (y, py, &sy)))
        .collect();
    let mut rows = Vec::new();
    for resolution in [256u32, 512, 1024, 2048] {
        let mut cullide = Cullide::new(opts.gl, (x, &sx), (y, &sy), resolution)?;
        let (mut ms, mut missed, mut exact_total, mut pctps) = (0.0, 0, 0, 0);
        // Frame 0 is the warm-up ([`Cullide::warm_up`]).
        cullide.warm_up(&positions[0].0, &positions[0].1)?;
        for (f, (px, py)) in positions.iter().enumerate().skip(1) {
            let c = cullide.frame(px, py, Predicate::Moller)?;
            let exact = &exact[f - 1];
            missed += exact.pairs.len() - c.pairs.len();
            exact_total += exact.pairs.len();
            ms += c.pruning_ms + c.tri_test_ms;
            pctps += c.pctps;
        }
        rows.push(CullideResolutionRow {
            resolution,
            ms: ms / frames as f64,
            pctps: pctps / frames as u64,
            missing_percent: 100.0 * missed as f64 / exact_total.max(1) as f64,
        });
    }
    Ok(CullideResolutions { frames, rows })
}

/// The three readback schemes on the real interlocking-tori frames, each forced in turn.
fn readback_schemes(
    opts: &BenchOptions,
    leaf_size: usize,
    frames: usize,
    calibrations: &mut Calibrations,
) -> anyhow::Result<ReadbackSchemes> {
    let scene = Scene::build("interlocking-tori", study_triangles(opts.quick))?;
    let mut rows = Vec::new();
    let mut p0 = 0;
    for scheme in [
        ReadbackMode::Hierarchical,
        ReadbackMode::Reduced,
        ReadbackMode::Full,
        ReadbackMode::PaperSwitch,
        ReadbackMode::Auto,
    ] {
        let options = Options {
            leaf_size,
            readback: scheme,
            ..Options::default()
        };
        let mut c = calibrations.collider(opts.gl, &scene.x.rest, &scene.y.rest, options)?;
        p0 = c.target.width();
        let (mut enc, mut dec, mut bytes, mut eta) = (0.0, 0.0, 0u64, 0.0);
        // Frame 0 is the warm-up ([`StreamingCollider::warm_up`]).
        let (px, py) = scene.frame(0);
        c.warm_up(&px, &py)?;
        for f in 1..=frames {
            let (px, py) = scene.frame(f);
            let r = c.frame(&px, &py)?;
            enc += r.timings.encode;
            dec += r.timings.readback;
            bytes += r.readback_bytes;
            eta += r.eta;
        }
        calibrations.keep(&mut c);
        let n = frames.max(1) as f64;
        rows.push(SchemeRun {
            scheme,
            eta: eta / n,
            encode_ms: enc / n,
            decode_ms: dec / n,
            bytes: bytes as f64 / n,
        });
    }
    Ok(ReadbackSchemes { p0, frames, rows })
}

fn run_scene(
    opts: &BenchOptions,
    name: &str,
    frames: usize,
    triangles: Option<usize>,
    args: &Paper1Args,
    bar: &indicatif::ProgressBar,
    calibrations: &mut Calibrations,
) -> anyhow::Result<SceneRun> {
    let ctx = opts.gl;
    let scene = Scene::build(name, triangles)?;
    let (x, y) = (&scene.x.rest, &scene.y.rest);
    let leaf_size = match args.leaf_size {
        Some(n) => n,
        None => auto_leaf_size_for_pair(x, y, ctx.info().is_software())?,
    };
    let options = Options {
        leaf_size,
        readback: ReadbackMode::Auto,
        ..Options::default()
    };
    let mut stream = calibrations.collider(ctx, x, y, options)?;
    let mut cullide = Cullide::new(
        ctx,
        (x, &stream.x.stream),
        (y, &stream.y.stream),
        args.cullide_resolution,
    )?;
    let mut out = SceneRun {
        name: scene.name.into(),
        label: scene.label.clone(),
        triangles: scene.triangles,
        leaf_size,
        leaves: [stream.x.stream.leaves.len(), stream.y.stream.leaves.len()],
        p0: [stream.target.width(), stream.target.height()],
        ..SceneRun::default()
    };
    let mut missed = 0usize;
    let mut exact_total = 0usize;
    let mut clustering = 0.0;
    let mut pair_digest = PairDigest::default();
    // Frame 0 warms up shader compilation and is not counted: a whole streaming frame (it
    // also measures the calibration point `auto` needs first), CULLIDE's object level only
    // (the same shader variants as every level; [`Cullide::warm_up`]); SOLID is CPU code.
    let (px, py) = scene.frame(0);
    study(opts, "streaming frame", || stream.frame(&px, &py))?;
    cullide.warm_up(&px, &py)?;
    bar.inc(1);
    for f in 1..=frames {
        let (px, py) = scene.frame(f);
        let s = study(opts, "streaming frame", || stream.frame(&px, &py))?;
        // SOLID: refit, traverse, the same triangle test.
        let solid_scope = profile::cpu_scope(ctx, "SOLID frame (CPU)");
        let t = Instant::now();
        let bx = solid::refit(&stream.x.stream, &px);
        let by = solid::refit(&stream.y.stream, &py);
        let refit = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let caps = solid::overlapping_leaves(&stream.x.stream, &bx, &stream.y.stream, &by);
        let traverse = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let sp = test_caps(
            model_view((x, &px, &stream.x.stream)),
            model_view((y, &py, &stream.y.stream)),
            &caps,
            Predicate::Moller,
        );
        let solid_tri = t.elapsed().as_secs_f64() * 1e3;
        drop(solid_scope);
        let c = study(opts, "CULLIDE frame", || {
            Ok(cullide.frame(&px, &py, Predicate::Moller)?)
        })?;
        bar.inc(1);
        out.solid_agrees += usize::from(sp.pairs == s.pairs);
        pair_digest.frame(&s.pairs);
        let found = c
            .pairs
            .iter()
            .filter(|p| s.pairs.binary_search(p).is_ok())
            .count();
        missed += s.pairs.len() - found;
        exact_total += s.pairs.len();
        let t = &s.timings;
        out.frame_times.push(FrameTimes {
            stream_cull: t.overlap + t.stencil + t.encode + t.readback + t.update,
            stream_download: t.download,
            stream_tri_test: t.tri_test,
            stream_total: t.total,
            solid_cull: refit + traverse,
            solid_tri_test: solid_tri,
            cullide_total: c.pruning_ms + c.tri_test_ms,
        });
        clustering += caps_per_set_p1_texel(&stream, &s.cap_leaves);
        accumulate(&mut out, &s, refit, traverse, solid_tri, &c);
        if f == frames {
            // Fig. 8-9: a snapshot of the last frame.
            let mx = Mesh::new(px.clone(), x.triangles.clone());
            let my = Mesh::new(py.clone(), y.triangles.clone());
            let file = snapshot_file(scene.name);
            crate::collide::snapshot::frame_png(
                &stream,
                &s,
                (&mx, &my),
                &opts.out_dir.join(&file),
            )?;
            out.snapshot = Some(file);
        }
    }
    calibrations.keep(&mut stream);
    average(&mut out, frames.max(1) as f64);
    out.caps_per_set_p1_texel = clustering / frames.max(1) as f64;
    out.frames = frames;
    out.pair_set = pair_digest.finish();
    out.cullide_missing_percent = if exact_total == 0 {
        0.0
    } else {
        100.0 * missed as f64 / exact_total as f64
    };
    Ok(out)
}

fn accumulate(
    out: &mut SceneRun,
    s: &FrameResult,
    refit: f64,
    traverse: f64,
    solid_tri: f64,
    c: &CullideResult,
) {
    let a = &mut out.stream;
    a.caps += s.caps;
    a.pctps += s.pctps;
    a.ctps += s.ctps;
    a.eta += s.eta;
    a.readback_bytes += s.readback_bytes;
    let (t, u) = (&mut a.timings, &s.timings);
    t.overlap += u.overlap;
    t.stencil += u.stencil;
    t.encode += u.encode;
    t.readback += u.readback;
    t.tri_test += u.tri_test;
    t.download += u.download;
    t.update += u.update;
    t.total += u.total;
    if let Some(scheme) = s.scheme {
        let name = format!("{scheme:?}").to_lowercase();
        if !out.schemes.contains(&name) {
            out.schemes.push(name);
        }
    }
    out.solid_refit += refit;
    out.solid_traverse += traverse;
    out.solid_tri += solid_tri;
    let k = &mut out.cullide;
    k.pruning_ms += c.pruning_ms;
    k.tri_test_ms += c.tri_test_ms;
    k.pctps += c.pctps;
    k.ctps += c.ctps;
    k.queries += c.queries;
}

fn average(out: &mut SceneRun, n: f64) {
    let a = &mut out.stream;
    let avg = |v: usize| (v as f64 / n).round() as usize;
    a.caps = avg(a.caps);
    a.ctps = avg(a.ctps);
    a.pctps = (a.pctps as f64 / n).round() as u64;
    a.eta /= n;
    a.readback_bytes = (a.readback_bytes as f64 / n).round() as u64;
    let t = &mut a.timings;
    for v in [
        &mut t.overlap,
        &mut t.stencil,
        &mut t.encode,
        &mut t.readback,
        &mut t.tri_test,
        &mut t.download,
        &mut t.update,
        &mut t.total,
    ] {
        *v /= n;
    }
    out.solid_refit /= n;
    out.solid_traverse /= n;
    out.solid_tri /= n;
    let k = &mut out.cullide;
    k.pruning_ms /= n;
    k.tri_test_ms /= n;
    k.pctps = (k.pctps as f64 / n).round() as u64;
    k.ctps = avg(k.ctps);
    k.queries = avg(k.queries);
}

/// CAPs per set 4x4 block of the slot-pair rectangle, each CAP at the first slots of its
/// leaves (the pixel the stencil keeps).
fn caps_per_set_p1_texel(c: &StreamingCollider, cap_leaves: &[(u32, u32)]) -> f64 {
    let first_slot = |s: &AabbStream| {
        let mut first = vec![0usize; s.leaves.len()];
        for (slot, &leaf) in s.slot_leaf.iter().enumerate().rev() {
            first[leaf as usize] = slot;
        }
        first
    };
    let (fx, fy) = (first_slot(&c.x.stream), first_slot(&c.y.stream));
    let mut blocks: Vec<(usize, usize)> = cap_leaves
        .iter()
        .map(|&(a, b)| (fx[a as usize] / HIER_BLOCK, fy[b as usize] / HIER_BLOCK))
        .collect();
    blocks.sort_unstable();
    blocks.dedup();
    if blocks.is_empty() {
        0.0
    } else {
        cap_leaves.len() as f64 / blocks.len() as f64
    }
}

/// Fig. 7: encode and read+decode time of each scheme against eta, on a P0 of the paper's
/// 2048 x 2048 (512 x 512 in quick mode), filled with clustered and with uniform CAPs.
fn fig7(opts: &BenchOptions) -> anyhow::Result<Fig7> {
    // region: workload fig7
    let p0 = if opts.quick { 512 } else { 2048 };
    // Each point is one timed measurement: every scheme is run as often as the report's
    // policy says (5 runs exactly under --quick), the best run is kept.
    let runs = opts.runs(5);
    // endregion
    let another = |done, spent| runs.another(done, spent);
    let target = PairTarget::new(opts.gl, p0, p0)?;
    let reduction = Reduction::new(opts.gl, p0, p0)?;
    let etas = [
        1e-5, 3e-5, 1e-4, 3e-4, 6e-4, 9.5e-4, 2e-3, 5e-3, 1e-2, 3e-2, 1e-1,
    ];
    let curve = |contents| -> anyhow::Result<Fig7Curve> {
        Ok(Fig7Curve::of(reduction_gpu::calibrate_with(
            opts.gl, &target, &reduction, &etas, &another, contents, 7,
        )?))
    };
    Ok(Fig7 {
        p0,
        clustered: curve(P0Contents::Clustered)?,
        uniform: curve(P0Contents::Uniform)?,
    })
}

/// Sec. 5.5: the interlocking tori with streams of `s`, `2s` and `4s` slots, in tiles of
/// `s` (1, 4 and 16 tiles sharing one render target) and as one rectangle, the two taking
/// turns frame by frame, read back by the paper's switch. The frame of median culling time
/// is kept for each.
fn tile_study(opts: &BenchOptions) -> anyhow::Result<TileStudy> {
    let scene = Scene::build("interlocking-tori", study_triangles(opts.quick))?;
    let (x, y) = (&scene.x.rest, &scene.y.rest);
    let frames = if opts.quick { 5 } else { 7 };
    let readback = ReadbackMode::PaperSwitch;
    let base = if opts.quick { 8 } else { 32 };
    let tile = AabbStream::build(x, base)?
        .len()
        .max(AabbStream::build(y, base)?.len());
    let mut rows = Vec::new();
    for leaf_size in [base, base / 2, base / 4] {
        let collider = |max_tile| {
            let options = Options {
                leaf_size,
                readback,
                max_tile,
                ..Options::default()
            };
            StreamingCollider::new(opts.gl, x, y, options)
        };
        let mut tiled = collider(Some(tile))?;
        let mut whole = collider(None)?;
        let (mut tiled_times, mut whole_times, mut caps) = (Vec::new(), Vec::new(), 0);
        // Frame 0 is the warm-up ([`StreamingCollider::warm_up`]).
        let (px, py) = scene.frame(0);
        tiled.warm_up(&px, &py)?;
        whole.warm_up(&px, &py)?;
        for f in 1..=frames {
            let (px, py) = scene.frame(f);
            let t = tiled.frame(&px, &py)?;
            let w = whole.frame(&px, &py)?;
            anyhow::ensure!(t.pairs == w.pairs, "tiles changed the pairs at frame {f}");
            tiled_times.push(cull_times(&t));
            whole_times.push(cull_times(&w));
            caps += t.caps;
        }
        rows.push(TileRow {
            leaf_size,
            slots: [tiled.x.stream.len(), tiled.y.stream.len()],
            tiles: tiled.layout.count(),
            tiled: median(tiled_times),
            one_rectangle: median(whole_times),
            caps: caps / frames,
        });
    }
    Ok(TileStudy {
        scene: scene.label.clone(),
        triangles: scene.triangles,
        frames,
        tile,
        readback,
        rows,
    })
}

fn cull_times(r: &FrameResult) -> CullTimes {
    CullTimes {
        overlap: r.timings.overlap,
        stencil: r.timings.stencil,
        encode: r.timings.encode,
        readback: r.timings.readback,
    }
}

/// The frame of median total.
fn median(mut frames: Vec<CullTimes>) -> CullTimes {
    frames.sort_by(|a, b| a.total().total_cmp(&b.total()));
    frames.get(frames.len() / 2).copied().unwrap_or_default()
}

fn leaf_sweep(
    opts: &BenchOptions,
    calibrations: &mut Calibrations,
) -> anyhow::Result<Vec<SweepPoint>> {
    let scene = Scene::build("interlocking-tori", study_triangles(opts.quick))?;
    let frames = if opts.quick { 2 } else { 5 };
    let mut out = Vec::new();
    for n in [4, 8, 16, 32, 64] {
        let options = Options {
            leaf_size: n,
            ..Options::default()
        };
        let mut c = calibrations.collider(opts.gl, &scene.x.rest, &scene.y.rest, options)?;
        let mut p = SweepPoint {
            leaf_size: n,
            p0: c.target.width().max(c.target.height()),
            total_ms: 0.0,
            overlap_ms: 0.0,
            tri_ms: 0.0,
            pctps: 0,
        };
        // Frame 0 is the warm-up ([`StreamingCollider::warm_up`]).
        let (px, py) = scene.frame(0);
        c.warm_up(&px, &py)?;
        for f in 1..=frames {
            let (px, py) = scene.frame(f);
            let r = c.frame(&px, &py)?;
            p.total_ms += r.timings.total / frames as f64;
            p.overlap_ms += r.timings.overlap / frames as f64;
            p.tri_ms += r.timings.tri_test / frames as f64;
            p.pctps += r.pctps / frames as u64;
        }
        calibrations.keep(&mut c);
        out.push(p);
    }
    Ok(out)
}

/// Fig. 8-9's snapshot file name for scene `name` (the bench writes it; it holds the GL state).
fn snapshot_file(name: &str) -> String {
    format!("paper1_fig8-9_{name}.png")
}
