//! The pipeline driver [Sec. 3, Fig. 2]: stream setup once, then per frame the texture
//! download and stream update (Sec. 6), the global AABB test (5.1), the streaming AABB test
//! tile by tile (5.2, 5.5), the stream reduction (5.3) and the primitive test (5.4).

use super::aabb_textures::AabbTextures;
use super::global_test::global_boxes_overlap;
use super::reduction::{P0Contents, Scheme};
use super::reduction_gpu::{self, CalibrationPoint, ReadbackMode, Reduction};
use super::stream_setup::{validate_mesh, AabbStream, DEFAULT_LEAF_SIZE};
use super::stream_update::StreamUpdate;
use super::streaming_test::{PairTarget, StreamingTest};
use super::tiles::TileLayout;
use super::tri_test::{test_caps, ModelView, Predicate};
use super::vertex_textures::VertexTexture;
use crate::gl::{profile, query::time_gpu, Context, GlError, Rect};
use crate::mesh::Mesh;
use glam::Vec3;
use serde::Serialize;
use std::time::Instant;

/// Default tile side: the GeForce 7800's texture limit of Sec. 5.5 (`d_max` <= 12 per
/// tile). It bounds the render target's memory (a 4096 x 4096 `P0` with its depth-stencil
/// buffer is 128 MB; a 16384 x 16384 one would be 2 GB) while keeping tiles few.
pub const DEFAULT_MAX_TILE: usize = 4096;

/// The user's choices.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Options {
    /// `n`: the most triangles per leaf.
    pub leaf_size: usize,
    pub readback: ReadbackMode,
    pub predicate: Predicate,
    /// Largest tile side; default [`DEFAULT_MAX_TILE`], never above the texture limit.
    /// Small values force tiling (tests, or to study Sec. 5.5).
    pub max_tile: Option<usize>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            leaf_size: DEFAULT_LEAF_SIZE,
            readback: ReadbackMode::Auto,
            predicate: Predicate::Exact,
            max_tile: None,
        }
    }
}

/// One model's stream on the GPU: one set of textures per segment.
pub struct GpuStream {
    pub stream: AabbStream,
    pub segments: Vec<(AabbTextures, VertexTexture)>,
}

impl GpuStream {
    fn new(ctx: &Context, stream: AabbStream, layout: &TileLayout) -> anyhow::Result<GpuStream> {
        let count = stream.len().div_ceil(layout.tile);
        let segments = (0..count)
            .map(|s| {
                let range = layout.segment(s, stream.len());
                Ok((
                    AabbTextures::new(ctx, &stream, range.clone())?,
                    VertexTexture::new(ctx, &stream, range)?,
                ))
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        Ok(GpuStream { stream, segments })
    }
}

/// Per-stage times of one frame, ms (GPU passes by timer query, the rest by wall clock).
#[derive(Clone, Debug, Default, Serialize)]
pub struct Timings {
    pub overlap: f64,
    /// Filling the stencil buffer from the stencil arrays: once for all frames when the pair
    /// fits one tile, for every tile of every frame otherwise [Sec. 5.5].
    pub stencil: f64,
    pub encode: f64,
    /// Reading back and decoding.
    pub readback: f64,
    pub tri_test: f64,
    /// Texture download: vertex textures, CPU to GPU.
    pub download: f64,
    /// Stream update (Table II passes).
    pub update: f64,
    /// Wall clock of the whole frame.
    pub total: f64,
}

/// What one frame found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FrameResult {
    /// Colliding AABB pairs, as pairs of real leaves.
    pub caps: usize,
    pub pctps: u64,
    pub ctps: usize,
    /// CAPs over all `2^dX * 2^dY` AABB pairs.
    pub eta: f64,
    pub global_overlap: bool,
    /// The scheme used (the last tile's, when tiles differ).
    pub scheme: Option<Scheme>,
    pub readback_bytes: u64,
    pub readback_reads: u32,
    pub tiles: usize,
    pub timings: Timings,
    /// Intersecting triangle pairs `(triangle of X, triangle of Y)`, sorted.
    #[serde(skip)]
    pub pairs: Vec<(u32, u32)>,
    /// The CAPs as leaf pairs, sorted.
    #[serde(skip)]
    pub cap_leaves: Vec<(u32, u32)>,
}

/// The seed of `auto`'s calibration fills.
const CALIBRATION_SEED: u64 = 0x5eed;

/// `auto`'s calibration at `etas`, measured point by point as frames need them
/// ([`StreamingCollider::calibrate_lazily`]).
#[derive(Clone, Debug)]
pub struct LazyCalibration {
    pub etas: Vec<f64>,
    /// Timed runs per scheme and point (the best is kept).
    pub repeats: usize,
    /// `points[k]`, at `etas[k]`: `None` until a frame needed it.
    pub points: Vec<Option<CalibrationPoint>>,
}

impl LazyCalibration {
    /// Nothing measured yet.
    pub fn new(etas: &[f64], repeats: usize) -> LazyCalibration {
        LazyCalibration {
            etas: etas.to_vec(),
            repeats,
            points: vec![None; etas.len()],
        }
    }
}

/// Streaming collision detection between two deforming meshes X and Y.
pub struct StreamingCollider {
    ctx: Context,
    pub options: Options,
    pub x: GpuStream,
    pub y: GpuStream,
    triangles_x: Vec<[u32; 3]>,
    triangles_y: Vec<[u32; 3]>,
    pub layout: TileLayout,
    pub target: PairTarget,
    pub reduction: Reduction,
    test: StreamingTest,
    update: StreamUpdate,
    /// `auto`'s calibration (empty for the fixed schemes, and when calibrated lazily).
    pub calibration: Vec<CalibrationPoint>,
    /// `auto`'s calibration made point by point ([`StreamingCollider::calibrate_lazily`]).
    lazy: Option<LazyCalibration>,
    /// Wall time this frame spent calibrating lazily (left out of the frame's total), ms.
    calibration_ms: f64,
    stencil_ready: bool,
}

impl StreamingCollider {
    /// Stream setup for X and Y (the preprocess of Sec. 4), then `auto`'s calibration.
    pub fn new(
        ctx: &Context,
        x: &Mesh,
        y: &Mesh,
        options: Options,
    ) -> anyhow::Result<StreamingCollider> {
        let mut collider = Self::new_uncalibrated(ctx, x, y, options)?;
        if options.readback == ReadbackMode::Auto {
            collider.calibrate(
                &reduction_gpu::CALIBRATION_ETAS,
                reduction_gpu::CALIBRATION_REPEATS,
            )?;
        }
        Ok(collider)
    }

    /// Stream setup only: `auto` then needs [`StreamingCollider::calibrate`] or
    /// [`StreamingCollider::set_calibration`] (a calibration made at the same `P0` size)
    /// before a frame.
    pub fn new_uncalibrated(
        ctx: &Context,
        x: &Mesh,
        y: &Mesh,
        options: Options,
    ) -> anyhow::Result<StreamingCollider> {
        for (name, mesh) in [("X", x), ("Y", y)] {
            validate_mesh(mesh).map_err(|e| anyhow::anyhow!("model {name}: {e}"))?;
        }
        let sx = AabbStream::build(x, options.leaf_size)?;
        let sy = AabbStream::build(y, options.leaf_size)?;
        // The renderer's limit, or the period GPU's (`Context::set_period`).
        let limit = ctx.max_texture_size() as usize;
        let max_tile = options.max_tile.unwrap_or(DEFAULT_MAX_TILE).min(limit);
        let layout = TileLayout::new(sx.len(), sy.len(), max_tile)?;
        let x_gpu = GpuStream::new(ctx, sx, &layout)?;
        let y_gpu = GpuStream::new(ctx, sy, &layout)?;
        let (w, h) = (
            y_gpu.segments[0].0.t_min.width() as usize,
            x_gpu.segments[0].0.t_min.width() as usize,
        );
        let target = PairTarget::new(ctx, w, h)?;
        let reduction = Reduction::new(ctx, w, h)?;
        Ok(StreamingCollider {
            ctx: ctx.clone(),
            options,
            x: x_gpu,
            y: y_gpu,
            triangles_x: x.triangles.clone(),
            triangles_y: y.triangles.clone(),
            layout,
            target,
            reduction,
            test: StreamingTest::new(ctx)?,
            update: StreamUpdate::new(ctx)?,
            calibration: Vec::new(),
            lazy: None,
            calibration_ms: 0.0,
            stencil_ready: false,
        })
    }

    /// Use `points`, a calibration made on a `P0` of this collider's size (by another
    /// collider of the same run), for `auto` instead of calibrating again.
    pub fn set_calibration(&mut self, points: Vec<CalibrationPoint>) {
        self.calibration = points;
    }

    /// (Re)run the readback calibration that `auto` decides by, on clustered `P0` contents:
    /// the spatial coherence of CAPs that the hierarchical readback counts on [Sec. 5.3.1]
    /// (uniformly random CAPs make every set `P1` texel hold one CAP, which the scenes never
    /// show, and push the scheme off the hierarchy too early).
    pub fn calibrate(
        &mut self,
        etas: &[f64],
        repeats: usize,
    ) -> anyhow::Result<&[CalibrationPoint]> {
        let _scope = profile::scope(&self.ctx, "readback calibration (auto)");
        self.calibration = reduction_gpu::calibrate(
            &self.ctx,
            &self.target,
            &self.reduction,
            etas,
            repeats,
            P0Contents::Clustered,
            CALIBRATION_SEED,
        )?;
        Ok(&self.calibration)
    }

    /// Calibrate `auto` point by point instead: the first frame whose `eta` is nearest to a
    /// point of `lazy` that is not measured yet measures it, on a `P0` of its own (this
    /// frame's `P0` holds its CAPs) and with the fills of a whole calibration
    /// ([`reduction_gpu::calibrate_some`]), so `auto` chooses as [`StreamingCollider::calibrate`]
    /// would have it, without measuring the points no frame is near. The time it takes is
    /// left out of the frame's total. `lazy` may hold points measured by another collider of
    /// this `P0` size; [`StreamingCollider::take_lazy_calibration`] hands them on.
    pub fn calibrate_lazily(&mut self, lazy: LazyCalibration) {
        self.lazy = Some(lazy);
    }

    /// The lazy calibration with the points measured so far.
    pub fn take_lazy_calibration(&mut self) -> Option<LazyCalibration> {
        self.lazy.take()
    }

    fn scheme_for(&mut self, eta: f64) -> anyhow::Result<Scheme> {
        Ok(match self.options.readback {
            ReadbackMode::Hierarchical => Scheme::Hierarchical,
            ReadbackMode::Reduced => Scheme::Reduced,
            ReadbackMode::Full => Scheme::Full,
            ReadbackMode::PaperSwitch => reduction_gpu::paper_switch(eta),
            ReadbackMode::Auto if self.lazy.is_some() => self.lazy_point(eta)?.fastest(),
            ReadbackMode::Auto => reduction_gpu::choose(&self.calibration, eta),
        })
    }

    /// The lazy calibration's point nearest to `eta`, measured now if it was not yet.
    fn lazy_point(&mut self, eta: f64) -> anyhow::Result<&CalibrationPoint> {
        let lazy = self.lazy.as_mut().expect("a lazy calibration");
        let k = reduction_gpu::nearest(lazy.etas.iter().copied(), eta)
            .ok_or_else(|| anyhow::anyhow!("readback auto: a lazy calibration without etas"))?;
        if lazy.points[k].is_none() {
            let start = Instant::now();
            let _scope = profile::scope(&self.ctx, "readback calibration (auto)");
            let scratch = PairTarget::new(&self.ctx, self.target.width(), self.target.height())?;
            let mut points = reduction_gpu::calibrate_some(
                &self.ctx,
                &scratch,
                &self.reduction,
                &lazy.etas,
                |i| i == k,
                &|done, _| done < lazy.repeats,
                P0Contents::Clustered,
                CALIBRATION_SEED,
            )?;
            lazy.points[k] = points[k].take();
            self.calibration_ms += start.elapsed().as_secs_f64() * 1e3;
        }
        lazy.points[k]
            .as_ref()
            .ok_or_else(|| anyhow::anyhow!("readback auto: calibration point {k} not measured"))
    }

    /// A warm-up before timed frames, smaller than a frame that is not counted: the
    /// vertices downloaded and the streams updated, the first tile's stencil set (and kept,
    /// as a frame keeps it when there is one tile), the overlap pass drawn over one
    /// [`WARM_UP_SIDE`]-square corner of `P0` (the same program, states and target; `P0`
    /// cleared whole), and the encode passes and reads of every scheme the readback mode can
    /// choose ([`warm_up_schemes`]), each over a corner of its levels
    /// ([`Reduction::warm_up`]). A whole frame would also draw the overlap and encode passes
    /// over all of their targets and test the triangles, and `auto` would measure a
    /// calibration point for it.
    pub fn warm_up(&mut self, positions_x: &[Vec3], positions_y: &[Vec3]) -> anyhow::Result<()> {
        self.check_inputs(positions_x, positions_y)?;
        self.upload(positions_x, positions_y)?;
        self.update_streams()?;
        let (ax, _) = &self.x.segments[0];
        let (ay, _) = &self.y.segments[0];
        self.test.set_stencil(&self.target, ax, ay)?;
        self.stencil_ready = true;
        let corner = Rect::sized(
            WARM_UP_SIDE.min(self.target.width() as u32),
            WARM_UP_SIDE.min(self.target.height() as u32),
        );
        self.test.run_on(&self.target, ax, ay, Some(corner))?;
        self.reduction
            .warm_up(&self.target, warm_up_schemes(self.options.readback))?;
        self.ctx.finish_all();
        Ok(())
    }

    /// The positions of X and Y must match the meshes and be finite.
    fn check_inputs(&self, positions_x: &[Vec3], positions_y: &[Vec3]) -> anyhow::Result<()> {
        check_positions(
            "X",
            positions_x,
            self.x.stream.leaves.iter().flat_map(|l| &l.vertices),
        )?;
        check_positions(
            "Y",
            positions_y,
            self.y.stream.leaves.iter().flat_map(|l| &l.vertices),
        )
    }

    /// Texture download: the positions into every segment's vertex texture.
    fn upload(&mut self, positions_x: &[Vec3], positions_y: &[Vec3]) -> anyhow::Result<()> {
        for (stream, positions) in [(&mut self.x, positions_x), (&mut self.y, positions_y)] {
            for (_, vertices) in &mut stream.segments {
                vertices.upload(positions)?;
            }
        }
        Ok(())
    }

    /// Stream update: every segment's leaf boxes from its vertex texture.
    fn update_streams(&self) -> Result<(), GlError> {
        for stream in [&self.x, &self.y] {
            for (aabb, vertices) in &stream.segments {
                self.update.run(vertices, aabb)?;
            }
        }
        Ok(())
    }

    /// One frame: the vertices of X and Y (the meshes' topology, deformed) in, every
    /// intersecting triangle pair out.
    pub fn frame(
        &mut self,
        positions_x: &[Vec3],
        positions_y: &[Vec3],
    ) -> anyhow::Result<FrameResult> {
        let start = Instant::now();
        self.calibration_ms = 0.0;
        anyhow::ensure!(
            self.options.readback != ReadbackMode::Auto
                || !self.calibration.is_empty()
                || self.lazy.is_some(),
            "readback auto: no calibration (calibrate, or set one, before the first frame)"
        );
        self.check_inputs(positions_x, positions_y)?;
        let mut out = FrameResult {
            tiles: self.layout.count(),
            ..FrameResult::default()
        };
        // Global AABB overlap test: trivial rejection.
        out.global_overlap = global_boxes_overlap(positions_x, positions_y);
        if !out.global_overlap {
            out.timings.total = start.elapsed().as_secs_f64() * 1e3;
            return Ok(out);
        }
        // Texture download, then stream update.
        let ctx = self.ctx.clone();
        let t = Instant::now();
        let download = profile::scope(&ctx, "texture download");
        self.upload(positions_x, positions_y)?;
        self.ctx.finish_all();
        drop(download);
        out.timings.download = t.elapsed().as_secs_f64() * 1e3;
        let ((), update_ms) = time_gpu(&self.ctx, || self.update_streams())?;
        out.timings.update = update_ms;
        // Streaming AABB test and stream reduction, tile by tile.
        let total_pairs = (self.x.stream.len() * self.y.stream.len()) as f64;
        let mut caps = Vec::new();
        for a in 0..self.layout.segments[0] {
            for b in 0..self.layout.segments[1] {
                self.tile(a, b, &mut out, &mut caps)?;
            }
        }
        caps.sort_unstable();
        out.caps = caps.len();
        out.eta = out.caps as f64 / total_pairs;
        // Primitive-level intersection test.
        let t = Instant::now();
        let tri_scope = profile::cpu_scope(&self.ctx, "triangle test (CPU)");
        let view = |triangles, positions, stream| ModelView {
            triangles,
            positions,
            stream,
        };
        let result = test_caps(
            view(&self.triangles_x, positions_x, &self.x.stream),
            view(&self.triangles_y, positions_y, &self.y.stream),
            &caps,
            self.options.predicate,
        );
        drop(tri_scope);
        out.timings.tri_test = t.elapsed().as_secs_f64() * 1e3;
        out.pctps = result.pctps;
        out.ctps = result.pairs.len();
        out.pairs = result.pairs;
        out.cap_leaves = caps;
        out.timings.total = start.elapsed().as_secs_f64() * 1e3 - self.calibration_ms;
        Ok(out)
    }

    /// One tile: segment `a` of X against segment `b` of Y.
    fn tile(
        &mut self,
        a: usize,
        b: usize,
        out: &mut FrameResult,
        caps: &mut Vec<(u32, u32)>,
    ) -> anyhow::Result<()> {
        let (ax, _) = &self.x.segments[a];
        let (ay, _) = &self.y.segments[b];
        // The stencil only depends on the tile; with one tile it is set once and kept.
        if self.layout.count() > 1 || !self.stencil_ready {
            let ((), stencil_ms) =
                time_gpu(&self.ctx, || self.test.set_stencil(&self.target, ax, ay))?;
            out.timings.stencil += stencil_ms;
            self.stencil_ready = true;
        }
        let (count, overlap_ms) = time_gpu(&self.ctx, || self.test.run(&self.target, ax, ay))?;
        out.timings.overlap += overlap_ms;
        if count == 0 {
            return Ok(());
        }
        let tile_pairs = (self.target.width() * self.target.height()) as f64;
        let scheme = self.scheme_for(count as f64 / tile_pairs)?;
        let readback = self.reduction.read(&self.ctx, &self.target, scheme)?;
        anyhow::ensure!(
            readback.decoded.caps.len() as u64 == count,
            "tile ({a}, {b}): the {scheme:?} readback decoded {} CAPs, the occlusion query counted {count}",
            readback.decoded.caps.len()
        );
        out.scheme = Some(scheme);
        out.timings.encode += readback.encode_ms;
        out.timings.readback += readback.decode_ms;
        out.readback_bytes += readback.decoded.bytes;
        out.readback_reads += readback.decoded.reads;
        let (row0, col0) = (a * self.layout.tile, b * self.layout.tile);
        for &(row, col) in &readback.decoded.caps {
            let sx = row0 + row as usize;
            let sy = col0 + col as usize;
            caps.push((self.x.stream.slot_leaf[sx], self.y.stream.slot_leaf[sy]));
        }
        Ok(())
    }

    /// `T_min`/`T_max` of every slot of X or Y as the GPU holds them (for tests and dumps).
    pub fn gpu_slot_boxes(&self, model_y: bool) -> anyhow::Result<Vec<super::Aabb>> {
        let stream = if model_y { &self.y } else { &self.x };
        let mut boxes = Vec::new();
        for (aabb, _) in &stream.segments {
            boxes.extend(aabb.download()?);
        }
        Ok(boxes)
    }

    pub fn context(&self) -> &Context {
        &self.ctx
    }
}

/// Side of the corner of `P0` that [`StreamingCollider::warm_up`] draws the overlap pass
/// over.
pub const WARM_UP_SIDE: u32 = 16;

/// The schemes that readback `mode` can choose, which [`StreamingCollider::warm_up`] warms up.
pub fn warm_up_schemes(mode: ReadbackMode) -> &'static [Scheme] {
    match mode {
        ReadbackMode::Hierarchical => &[Scheme::Hierarchical],
        ReadbackMode::Reduced => &[Scheme::Reduced],
        ReadbackMode::Full => &[Scheme::Full],
        ReadbackMode::PaperSwitch => &[Scheme::Hierarchical, Scheme::Reduced],
        ReadbackMode::Auto => &[Scheme::Hierarchical, Scheme::Reduced, Scheme::Full],
    }
}

/// The positions must match the mesh and be finite.
fn check_positions<'a>(
    name: &str,
    positions: &[Vec3],
    used: impl Iterator<Item = &'a u32>,
) -> anyhow::Result<()> {
    let mut max_used = 0;
    for &v in used {
        max_used = max_used.max(v as usize);
    }
    anyhow::ensure!(
        max_used < positions.len(),
        "model {name}: {} positions given, the mesh uses vertex {max_used}",
        positions.len()
    );
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        anyhow::bail!(
            "model {name}: vertex {i} is not finite ({:?})",
            positions[i]
        );
    }
    Ok(())
}
