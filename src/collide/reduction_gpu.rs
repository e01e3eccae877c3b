//! Stream reduction on the GPU [Sec. 5.3]: the encoding passes that fill `P1..P3` (4x4) or
//! `P1'` (8x8) from `P0`, and the reads the decoders of [`super::reduction`] ask for. The
//! scheme of each frame is `hierarchical`, `reduced` or `full`; or the paper's switch
//! (`paper-switch`: hierarchical below `eta` = 0.095%, reduced from it, Sec. 5.3.2); or
//! chosen by `auto` from the frame's `eta` (known before any readback: the occlusion query
//! counted the CAPs) and a calibration of all three schemes on this renderer at this `P0`
//! size, on clustered `P0` contents like the scenes' own (Sec. 5.3.1 rests on CAPs being
//! clustered).

use super::reduction::{
    caps_per_set_block, decode_full, decode_hierarchical, decode_reduced, encoded_size, fill_p0,
    hierarchy_sizes, Decoded, LevelReader, P0Contents, Scheme, HIER_BLOCK, HIER_LEVELS,
    REDUCED_BLOCK,
};
use super::streaming_test::{PairTarget, OVERLAP_PASS};
use crate::gl::{
    ensure_finite, Context, Framebuffer, GlError, Program, Rect, Texture, TextureFormat,
};
use crate::shader;
use std::time::{Duration, Instant};

/// How the CAPs are read back.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ReadbackMode {
    /// Per frame, the scheme the calibration found fastest at this frame's `eta`.
    #[default]
    Auto,
    Hierarchical,
    Reduced,
    Full,
    /// The paper's fixed switch [Sec. 5.3.2]: hierarchical below `eta` =
    /// [`PAPER_ETA_THRESHOLD`], reduced from it (measured on a GeForce 7800 for a 2048 x 2048
    /// `P0`).
    #[serde(rename = "paper-switch")]
    PaperSwitch,
}

/// The paper's threshold on `eta` (0.095%), the dotted line of Fig. 7.
pub const PAPER_ETA_THRESHOLD: f64 = 0.00095;

/// The scheme of the paper's fixed switch at `eta`.
pub fn paper_switch(eta: f64) -> Scheme {
    if eta < PAPER_ETA_THRESHOLD {
        Scheme::Hierarchical
    } else {
        Scheme::Reduced
    }
}

impl ReadbackMode {
    /// Every mode, as its name parses.
    pub const ALL: [ReadbackMode; 5] = [
        ReadbackMode::Auto,
        ReadbackMode::Hierarchical,
        ReadbackMode::Reduced,
        ReadbackMode::Full,
        ReadbackMode::PaperSwitch,
    ];

    /// The name [`std::str::FromStr`] takes (and serde writes): `auto`, `hierarchical`...
    pub fn name(self) -> &'static str {
        match self {
            ReadbackMode::Auto => "auto",
            ReadbackMode::Hierarchical => "hierarchical",
            ReadbackMode::Reduced => "reduced",
            ReadbackMode::Full => "full",
            ReadbackMode::PaperSwitch => "paper-switch",
        }
    }
}

impl std::fmt::Display for ReadbackMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for ReadbackMode {
    type Err = String;

    fn from_str(s: &str) -> Result<ReadbackMode, String> {
        ReadbackMode::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = ReadbackMode::ALL.iter().map(|m| m.name()).collect();
                format!("unknown readback '{s}' (one of: {})", names.join(", "))
            })
    }
}

/// One encoded level: an R32F (`P1..P3`) or RGBA32F (`P1'`) texture and its framebuffer.
struct Level {
    texture: Texture,
    framebuffer: Framebuffer,
}

impl Level {
    fn new(
        ctx: &Context,
        name: &str,
        (w, h): (usize, usize),
        f: TextureFormat,
    ) -> Result<Level, GlError> {
        let texture = Texture::new_2d(ctx, w as u32, h as u32, f)?;
        let framebuffer = Framebuffer::new(ctx, name, &[&texture], None)?;
        Ok(Level {
            texture,
            framebuffer,
        })
    }
}

/// `P1..P3`, `P1'` and the two encoding programs, for one `P0` size.
pub struct Reduction {
    /// `P1`, `P2`, `P3`.
    levels: Vec<Level>,
    reduced: Level,
    encode4: Program,
    encode8: Program,
    width: usize,
    height: usize,
}

/// What one readback did and what it cost.
#[derive(Clone, Debug, Default)]
pub struct Readback {
    pub decoded: Decoded,
    /// GPU time of the encoding passes (timer queries), ms.
    pub encode_ms: f64,
    /// Wall time of reading back and decoding on the CPU, ms.
    pub decode_ms: f64,
}

impl Reduction {
    pub fn new(ctx: &Context, width: usize, height: usize) -> Result<Reduction, GlError> {
        let sizes = hierarchy_sizes(width, height);
        let names = ["P1", "P2", "P3"];
        let levels = (1..=HIER_LEVELS)
            .map(|i| Level::new(ctx, names[i - 1], sizes[i], TextureFormat::R32F))
            .collect::<Result<Vec<_>, _>>()?;
        let reduced = Level::new(
            ctx,
            "P1'",
            encoded_size(width, height, REDUCED_BLOCK),
            TextureFormat::Rgba32F,
        )?;
        Ok(Reduction {
            levels,
            reduced,
            encode4: Program::rect(ctx, &[shader!("glsl/collide/encode_4x4.frag")])?,
            encode8: Program::rect(ctx, &[shader!("glsl/collide/encode_8x8.frag")])?,
            width,
            height,
        })
    }

    /// `P1..P3` (for dumps).
    pub fn level_textures(&self) -> Vec<&Texture> {
        self.levels.iter().map(|l| &l.texture).collect()
    }

    /// `P1'` (for dumps).
    pub fn reduced_texture(&self) -> &Texture {
        &self.reduced.texture
    }

    /// Encode `P0` for `scheme`, read back and decode its CAPs (tile-local `(row, column)`).
    pub fn read(
        &self,
        ctx: &Context,
        p0: &PairTarget,
        scheme: Scheme,
    ) -> Result<Readback, GlError> {
        let (w, h) = (self.width, self.height);
        let ((), encode_ms) = crate::gl::query::time_gpu(ctx, || match scheme {
            Scheme::Hierarchical => self.encode_hierarchical(&p0.p0),
            Scheme::Reduced => self.encode(&self.encode8, &p0.p0, &self.reduced, ENCODE_8X8_PASS),
            Scheme::Full => Ok(()),
        })?;
        let start = Instant::now();
        let mut reader = GpuLevels {
            p0,
            reduction: self,
        };
        let decoded = match scheme {
            Scheme::Hierarchical => decode_hierarchical(&mut reader, w, h)?,
            Scheme::Reduced => decode_reduced(&mut reader, w, h)?,
            Scheme::Full => decode_full(&mut reader, w, h)?,
        };
        Ok(Readback {
            decoded,
            encode_ms,
            decode_ms: start.elapsed().as_secs_f64() * 1e3,
        })
    }

    fn encode_hierarchical(&self, p0: &Texture) -> Result<(), GlError> {
        // region: encode-hierarchical
        let mut source = p0;
        for (level, name) in self.levels.iter().zip(ENCODE_4X4_PASSES) {
            self.encode(&self.encode4, source, level, name)?;
            source = &level.texture;
        }
        Ok(())
        // endregion
    }

    fn encode(
        &self,
        program: &Program,
        source: &Texture,
        target: &Level,
        name: &str,
    ) -> Result<(), GlError> {
        self.encode_on(program, source, target, name, None)
    }

    /// [`Reduction::encode`] over `rect` of `target` only (all of it for `None`).
    fn encode_on(
        &self,
        program: &Program,
        source: &Texture,
        target: &Level,
        name: &str,
        rect: Option<Rect>,
    ) -> Result<(), GlError> {
        let mut pass = target.framebuffer.pass(program, name)?;
        pass.texture("u_level", source);
        match rect {
            Some(rect) => pass.draw_rect(rect),
            None => pass.draw_full(),
        }
    }

    /// A warm-up of [`Reduction::read`] for `schemes`, smaller than a read of a whole `P0`:
    /// each level a scheme encodes is cleared whole, encoded over a corner of
    /// [`WARM_UP_TEXELS`] square only (the same programs, states and targets) and read at one
    /// texel, as `P0` is.
    pub fn warm_up(&self, p0: &PairTarget, schemes: &[Scheme]) -> Result<(), GlError> {
        p0.framebuffer.read_f32(0, Rect::sized(1, 1))?;
        for &scheme in schemes {
            let passes: Vec<(&Program, &Texture, &Level, &str)> = match scheme {
                Scheme::Hierarchical => (0..self.levels.len())
                    .map(|i| {
                        let source = if i == 0 {
                            &p0.p0
                        } else {
                            &self.levels[i - 1].texture
                        };
                        (&self.encode4, source, &self.levels[i], ENCODE_4X4_PASSES[i])
                    })
                    .collect(),
                Scheme::Reduced => vec![(&self.encode8, &p0.p0, &self.reduced, ENCODE_8X8_PASS)],
                Scheme::Full => Vec::new(),
            };
            for (program, source, level, name) in passes {
                level.framebuffer.clear_color(0, [0.0; 4])?;
                let (w, h) = (level.texture.width(), level.texture.height());
                let corner = Rect::sized(w.min(WARM_UP_TEXELS), h.min(WARM_UP_TEXELS));
                self.encode_on(program, source, level, name, Some(corner))?;
                level.framebuffer.read_f32(0, Rect::sized(1, 1))?;
            }
        }
        Ok(())
    }
}

/// Side of the corner of each level that [`Reduction::warm_up`] encodes.
pub const WARM_UP_TEXELS: u32 = 4;

/// The passes that write `P1`, `P2`, `P3` and `P1'` (named in errors).
const ENCODE_4X4_PASSES: [&str; 3] = [
    "encode P0 -> P1 (4x4)",
    "encode P1 -> P2 (4x4)",
    "encode P2 -> P3 (4x4)",
];
const ENCODE_8X8_PASS: &str = "encode P0 -> P1' (8x8)";

/// Reads the levels with `glReadPixels`. Every value read must be finite: the decoders
/// take any non-zero texel for a CAP, so a NaN would become pairs that do not exist.
struct GpuLevels<'a> {
    p0: &'a PairTarget,
    reduction: &'a Reduction,
}

impl LevelReader for GpuLevels<'_> {
    type Error = GlError;

    fn read_red(
        &mut self,
        level: usize,
        x: usize,
        y: usize,
        w: usize,
        h: usize,
    ) -> Result<Vec<f32>, GlError> {
        let rect = Rect::new(x as u32, y as u32, w as u32, h as u32);
        let (framebuffer, pass) = match level {
            0 => (&self.p0.framebuffer, OVERLAP_PASS),
            l => (
                &self.reduction.levels[l - 1].framebuffer,
                ENCODE_4X4_PASSES[l - 1],
            ),
        };
        let values = framebuffer.read_f32(0, rect)?;
        // An encoder passes a non-finite mark of its input on unchanged, so one read at a
        // coarser level started in P0.
        if !all_finite(&values) {
            let what = match level {
                0 => "collide: the CAP marks of P0".to_string(),
                l => format!("collide: the CAP marks of P0, as carried to P{l}"),
            };
            ensure_finite(values.iter().copied(), &what, pass)?;
        }
        Ok(values)
    }

    fn read_reduced(
        &mut self,
        x: usize,
        y: usize,
        w: usize,
        h: usize,
    ) -> Result<Vec<[f32; 4]>, GlError> {
        let rect = Rect::new(x as u32, y as u32, w as u32, h as u32);
        let flat = self.reduction.reduced.framebuffer.read_f32(0, rect)?;
        if !all_finite(&flat) {
            ensure_finite(
                flat.iter().copied(),
                "collide: the CAP marks of P0, as carried to P1'",
                ENCODE_8X8_PASS,
            )?;
        }
        Ok(flat
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect())
    }
}

/// Whether every value is finite: the fast test of a readback (branch-free over runs, so
/// it vectorises); [`ensure_finite`] then names the first bad value when one is not.
fn all_finite(values: &[f32]) -> bool {
    values
        .chunks(64)
        .all(|run| run.iter().fold(true, |ok, v| ok & v.is_finite()))
}

/// What one scheme cost at one calibration point.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct SchemeCost {
    pub scheme: Scheme,
    /// GPU time of the encoding passes, ms.
    pub encode_ms: f64,
    /// Wall time of reading back and decoding, ms.
    pub decode_ms: f64,
    /// Bytes read back.
    pub bytes: u64,
    /// The slowest run's encode and decode, ms (the fields above are the fastest run's): the
    /// other end of the runs, for claims that must hold whichever run is taken.
    pub slowest_ms: f64,
}

impl SchemeCost {
    /// The fastest run's encode and decode, ms.
    pub fn total_ms(&self) -> f64 {
        self.encode_ms + self.decode_ms
    }

    /// The total at one end of the runs: the fastest (`fast`) or the slowest.
    pub fn end_ms(&self, fast: bool) -> f64 {
        if fast {
            self.total_ms()
        } else {
            self.slowest_ms
        }
    }
}

/// One calibration point: the time of each scheme on a `P0` with CAP ratio `eta`.
#[derive(Clone, Debug, serde::Serialize)]
pub struct CalibrationPoint {
    pub eta: f64,
    pub contents: P0Contents,
    pub caps: usize,
    /// CAPs per set `P1` texel (4x4 block of `P0`): 1 when no two CAPs share a block.
    pub caps_per_set_p1_texel: f64,
    /// Timed runs of each scheme (the best is kept).
    pub runs: usize,
    /// In the order hierarchical, reduced, full.
    pub schemes: Vec<SchemeCost>,
}

impl CalibrationPoint {
    pub fn fastest(&self) -> Scheme {
        self.schemes
            .iter()
            .min_by(|a, b| a.total_ms().total_cmp(&b.total_ms()))
            .map(|s| s.scheme)
            .unwrap_or(Scheme::Full)
    }

    /// The cost of `scheme` at this point, if it was measured.
    pub fn cost(&self, scheme: Scheme) -> Option<&SchemeCost> {
        self.schemes.iter().find(|s| s.scheme == scheme)
    }

    /// The faster of the paper's two schemes (hierarchical, reduced) and its total, ms.
    pub fn paper_fastest(&self) -> Option<(Scheme, f64)> {
        let h = self.cost(Scheme::Hierarchical)?.total_ms();
        let r = self.cost(Scheme::Reduced)?.total_ms();
        Some(if h <= r {
            (Scheme::Hierarchical, h)
        } else {
            (Scheme::Reduced, r)
        })
    }
}

/// The `eta` values the calibration samples (as fractions), spanning the paper's 0.095%.
pub const CALIBRATION_ETAS: [f64; 8] = [1e-5, 1e-4, 3e-4, 9.5e-4, 3e-3, 1e-2, 3e-2, 1e-1];

/// Timed runs per scheme and point of `auto`'s calibration (the best is kept): untimed
/// set-up, not a reported figure.
pub const CALIBRATION_REPEATS: usize = 2;

/// The schemes' costs on this renderer for a `P0` of this size: `P0` is filled with
/// `contents` at each `eta` ([`fill_p0`]), then every scheme encodes, reads and decodes it,
/// `repeats` times (the best time is kept). Also Fig. 7's data.
pub fn calibrate(
    ctx: &Context,
    p0: &PairTarget,
    reduction: &Reduction,
    etas: &[f64],
    repeats: usize,
    contents: P0Contents,
    seed: u64,
) -> Result<Vec<CalibrationPoint>, GlError> {
    let runs = |done: usize, _| done < repeats.max(1);
    calibrate_with(ctx, p0, reduction, etas, &runs, contents, seed)
}

/// [`calibrate`] with the number of timed runs per point decided by `another(done, spent)`:
/// whether run `done + 1` happens after `done` runs (every scheme once each) that took
/// `spent` (a policy like the report's `timing::Runs`).
pub fn calibrate_with(
    ctx: &Context,
    p0: &PairTarget,
    reduction: &Reduction,
    etas: &[f64],
    another: &dyn Fn(usize, Duration) -> bool,
    contents: P0Contents,
    seed: u64,
) -> Result<Vec<CalibrationPoint>, GlError> {
    let points = calibrate_some(ctx, p0, reduction, etas, |_| true, another, contents, seed)?;
    Ok(points.into_iter().flatten().collect())
}

/// [`calibrate`] at the points `wanted(k)` picks (`None` at the others), each measured on
/// the same `P0` contents as in a whole calibration: the fills of the points skipped are
/// still made on the CPU, so the random sequence that fills the next point is the same.
#[allow(clippy::too_many_arguments)]
pub fn calibrate_some(
    ctx: &Context,
    p0: &PairTarget,
    reduction: &Reduction,
    etas: &[f64],
    wanted: impl Fn(usize) -> bool,
    another: &dyn Fn(usize, Duration) -> bool,
    contents: P0Contents,
    seed: u64,
) -> Result<Vec<Option<CalibrationPoint>>, GlError> {
    let (w, h) = (p0.width(), p0.height());
    let mut rng = super::deform::SplitMix64(seed);
    let mut points: Vec<Option<CalibrationPoint>> = vec![None; etas.len()];
    // The fills after the last wanted point would only be thrown away.
    let Some(last) = (0..etas.len()).rev().find(|&k| wanted(k)) else {
        return Ok(points);
    };
    for (k, &eta) in etas.iter().enumerate().take(last + 1) {
        let cells = fill_p0(w, h, eta, contents, &mut rng);
        if !wanted(k) {
            continue;
        }
        let caps = cells.iter().filter(|&&c| c != 0.0).count();
        p0.p0.upload_f32(&cells)?;
        let mut schemes =
            [Scheme::Hierarchical, Scheme::Reduced, Scheme::Full].map(|scheme| SchemeCost {
                scheme,
                encode_ms: f64::INFINITY,
                decode_ms: f64::INFINITY,
                bytes: 0,
                slowest_ms: 0.0,
            });
        // The schemes take turns, so that a change of load on a shared machine hits all alike.
        let (start, mut runs) = (Instant::now(), 0);
        while runs == 0 || another(runs, start.elapsed()) {
            runs += 1;
            for best in &mut schemes {
                ctx.finish_all();
                let r = reduction.read(ctx, p0, best.scheme)?;
                best.slowest_ms = best.slowest_ms.max(r.encode_ms + r.decode_ms);
                if r.encode_ms + r.decode_ms < best.total_ms() {
                    (best.encode_ms, best.decode_ms) = (r.encode_ms, r.decode_ms);
                    best.bytes = r.decoded.bytes;
                }
            }
        }
        let schemes = schemes.to_vec();
        points[k] = Some(CalibrationPoint {
            eta,
            contents,
            caps,
            caps_per_set_p1_texel: caps_per_set_block(&cells, w, h, HIER_BLOCK),
            runs,
            schemes,
        });
    }
    Ok(points)
}

/// The index of the `eta` of `etas` nearest to `eta` in log scale (the first of equals).
pub fn nearest(etas: impl Iterator<Item = f64>, eta: f64) -> Option<usize> {
    let log = |e: f64| e.max(1e-9).ln();
    etas.enumerate()
        .min_by(|(_, a), (_, b)| {
            (log(*a) - log(eta))
                .abs()
                .total_cmp(&(log(*b) - log(eta)).abs())
        })
        .map(|(k, _)| k)
}

/// The scheme `auto` uses at `eta`: the fastest at the nearest calibrated `eta` (in log scale).
pub fn choose(points: &[CalibrationPoint], eta: f64) -> Scheme {
    nearest(points.iter().map(|p| p.eta), eta)
        .map(|k| points[k].fastest())
        .unwrap_or(Scheme::Hierarchical)
}

/// Where `auto` leaves the hierarchical scheme: the first calibrated `eta` at which it is not
/// the fastest of the three (`None` if it always is).
pub fn measured_threshold(points: &[CalibrationPoint]) -> Option<f64> {
    points
        .iter()
        .find(|p| p.fastest() != Scheme::Hierarchical)
        .map(|p| p.eta)
}

/// The paper's crossover [Sec. 5.3.2, Fig. 7], measured: the smallest calibrated `eta` from
/// which the reduced scheme is at least as fast as the hierarchical one at every larger
/// calibrated `eta` (points in increasing `eta`). `None` when the hierarchical scheme is
/// faster at the largest `eta`; the first `eta` when the reduced scheme always wins.
pub fn crossover(points: &[CalibrationPoint]) -> Option<f64> {
    let reduced_wins =
        |p: &CalibrationPoint| p.paper_fastest().map(|(s, _)| s) == Some(Scheme::Reduced);
    let mut from = None;
    for p in points.iter().rev() {
        if !reduced_wins(p) {
            break;
        }
        from = Some(p.eta);
    }
    from
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(eta: f64, totals: [f64; 3]) -> CalibrationPoint {
        let schemes = [Scheme::Hierarchical, Scheme::Reduced, Scheme::Full]
            .iter()
            .zip(totals)
            .map(|(&scheme, t)| SchemeCost {
                scheme,
                encode_ms: t / 2.0,
                decode_ms: t / 2.0,
                bytes: 0,
                slowest_ms: t,
            })
            .collect();
        CalibrationPoint {
            eta,
            contents: P0Contents::Clustered,
            caps: 0,
            caps_per_set_p1_texel: 0.0,
            runs: 1,
            schemes,
        }
    }

    #[test]
    fn auto_picks_the_fastest_scheme_at_the_nearest_calibrated_eta() {
        let points = [
            point(1e-5, [1.0, 2.0, 5.0]),
            point(1e-3, [3.0, 2.0, 5.0]),
            point(1e-1, [9.0, 7.0, 5.0]),
        ];
        assert_eq!(choose(&points, 2e-5), Scheme::Hierarchical);
        assert_eq!(choose(&points, 5e-4), Scheme::Reduced);
        assert_eq!(choose(&points, 0.5), Scheme::Full);
        assert_eq!(measured_threshold(&points), Some(1e-3));
        assert_eq!(measured_threshold(&points[..1]), None);
    }

    #[test]
    fn the_crossover_is_where_reduced_beats_hierarchical_for_good() {
        // Full readback is fastest everywhere: it does not move the paper's crossover.
        let points = [
            point(1e-5, [1.0, 2.0, 0.5]),
            point(1e-4, [2.5, 2.0, 0.5]),
            point(1e-3, [1.5, 2.0, 0.5]),
            point(1e-2, [3.0, 2.0, 0.5]),
            point(1e-1, [9.0, 2.0, 0.5]),
        ];
        assert_eq!(crossover(&points), Some(1e-2));
        assert_eq!(crossover(&points[..3]), None);
        assert_eq!(crossover(&points[1..2]), Some(1e-4));
        assert_eq!(measured_threshold(&points), Some(1e-5));
    }

    #[test]
    fn the_paper_switch_changes_scheme_at_0_095_percent() {
        assert_eq!(paper_switch(0.0009), Scheme::Hierarchical);
        assert_eq!(paper_switch(0.00095), Scheme::Reduced);
        assert_eq!(paper_switch(0.01), Scheme::Reduced);
        assert_eq!("paper-switch".parse(), Ok(ReadbackMode::PaperSwitch));
    }
}
