//! Technique 6, removing an `if` with the depth buffer (one of the lecture's debugging and
//! coding tips): a fragment shader that branches on a per-pixel condition before some
//! expensive work is replaced by two passes: a cheap one that writes the condition into the
//! depth buffer, and the expensive shader without the `if`, drawn so that the depth test
//! rejects the pixels that fail the condition before the shader runs (early depth test).
//!
//! An occlusion query counts the fragments that pass the depth test, which says nothing of
//! whether the test ran before the shader or after it. The shader's runs themselves are
//! counted by an atomic counter the shader increments (OpenGL 4.2 atomic counters, with 4.3's
//! buffers here; that variant asks for the early test explicitly, as a shader with a side
//! effect must, and helper invocations do not count), else by a pipeline statistics query
//! (fragment shader invocations, OpenGL 4.6 or `GL_ARB_pipeline_statistics_query`). On a
//! context with neither (softpipe's OpenGL 3.3 without the extension) the runs are not counted,
//! and [`RunCounter::Unavailable`] says why. Where the driver has pipeline statistics they are
//! reported beside the count ([`DepthMask::count_invocations`]), for the plain shader: llvmpipe
//! counts there every fragment it rasterizes, those its early depth test then drops included
//! (640 for a 32x16 target all of whose pixels the test rejects), although its time shows the
//! masked work skipped; so the atomic counter is preferred where both exist.
//!
//! GPUs shade in 2x2 quads, and a pipeline statistics query may count the helper invocations
//! of a quad's inactive pixels (four per quad, and a quad cut by the two triangles of the
//! full-target rectangle twice). So a count is judged against the mask at quad granularity
//! ([`runs_fit_mask`]): at least the active pixels, at most four runs for each of the two
//! triangles in each quad that holds an active pixel. Without the early test every pixel
//! would run, which breaks that bound wherever the active quads are fewer than an eighth of
//! all quads (sparse or coherent masks).
//!
//! On the GPUs of the time a branch cost both sides wherever the pixels of a group disagreed;
//! the depth test culls whole pixels before shading. The lecture names the tip only; the
//! expensive function, the masks and the measures are ours.

use crate::gl::{
    AtomicCounters, Compare, Context, DepthTest, DrawState, FragmentInvocationsQuery, Framebuffer,
    GlError, OcclusionQuery, Program, Rect, Texture, TextureFormat,
};
use crate::lecture3::error::{check_range, Error};
use crate::shader;
use glam::Vec2;
use serde::Serialize;

/// Which pixels are active.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MaskShape {
    /// Large smooth regions (neighbouring pixels agree: branches are coherent).
    Blobs,
    /// Pixels scattered at random (neighbours disagree: branches diverge).
    Scattered,
}

/// A mask of `width x height` distinct values in [0, 1): pixel i's rank among the pixels,
/// divided by their number, so that `mask < fraction` selects a `fraction` of the pixels
/// exactly (to one pixel).
pub fn mask(shape: MaskShape, width: u32, height: u32, seed: u64) -> Vec<f32> {
    let n = (width * height) as usize;
    let key: Vec<f64> = (0..n)
        .map(|i| {
            let (x, y) = ((i as u32 % width) as f64, (i as u32 / width) as f64);
            let (u, v) = (x / width as f64, y / height as f64);
            match shape {
                MaskShape::Blobs => {
                    let s = seed as f64 * 0.37;
                    (u * 7.0 + s).sin() * (v * 5.0 - s).cos()
                        + 0.6 * (u * 3.0 + v * 4.0 + 2.0 * s).sin()
                }
                MaskShape::Scattered => {
                    let mut z = seed ^ (i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
                    z = (z ^ (z >> 31)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
                    z = (z ^ (z >> 29)).wrapping_mul(0x94d0_49bb_1331_11eb);
                    (z >> 11) as f64
                }
            }
        })
        .collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| key[a].total_cmp(&key[b]).then(a.cmp(&b)));
    let mut out = vec![0.0f32; n];
    for (rank, &i) in order.iter().enumerate() {
        out[i] = (rank as f64 / n as f64) as f32;
    }
    out
}

/// The expensive function at pixel (x, y) of a `width x height` target, in f64.
pub fn expensive(x: u32, y: u32, width: u32, height: u32, iterations: u32) -> f64 {
    let tau = std::f64::consts::TAU;
    let u = (x as f64 + 0.5) / width as f64;
    let v = tau * (y as f64 + 0.5) / height as f64;
    (1..=iterations)
        .map(|k| ((tau * (k as f64 * u).fract() + v).sin()) / k as f64)
        .sum()
}

/// The picture on the CPU: the expensive function where the mask is active, 0 elsewhere;
/// and how many pixels are active.
pub fn cpu_picture(
    mask: &[f32],
    width: u32,
    height: u32,
    fraction: f32,
    iterations: u32,
) -> (Vec<f64>, u64) {
    let mut active = 0;
    let picture = mask
        .iter()
        .enumerate()
        .map(|(i, &m)| {
            if m < fraction {
                active += 1;
                expensive(
                    i as u32 % width,
                    i as u32 / width,
                    width,
                    height,
                    iterations,
                )
            } else {
                0.0
            }
        })
        .collect();
    (picture, active)
}

/// The expensive function at every pixel, active or not: the CPU picture of any mask and
/// fraction is this with the inactive pixels set to 0 ([`cpu_masked`]), so that a sweep over
/// masks and fractions computes it once.
pub fn cpu_expensive(width: u32, height: u32, iterations: u32) -> Vec<f64> {
    (0..width * height)
        .map(|i| expensive(i % width, i / width, width, height, iterations))
        .collect()
}

/// [`cpu_picture`] from the values of [`cpu_expensive`] (same size and iterations).
pub fn cpu_masked(expensive: &[f64], mask: &[f32], fraction: f32) -> (Vec<f64>, u64) {
    let mut active = 0;
    let picture = mask
        .iter()
        .zip(expensive)
        .map(|(&m, &e)| {
            if m < fraction {
                active += 1;
                e
            } else {
                0.0
            }
        })
        .collect();
    (picture, active)
}

/// How this context counts the expensive shader's runs.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RunCounter {
    /// A pipeline statistics query: fragment shader invocations.
    PipelineStatistics,
    /// An atomic counter incremented by the shader (early depth test asked for).
    AtomicCounter,
    /// Neither is available: why.
    Unavailable(String),
}

impl RunCounter {
    /// What counts the runs, in words.
    pub fn describe(&self) -> String {
        match self {
            RunCounter::PipelineStatistics => {
                "fragment shader invocations (pipeline statistics query)".into()
            }
            RunCounter::AtomicCounter => {
                "an atomic counter in the shader (early depth test asked for)".into()
            }
            RunCounter::Unavailable(why) => format!("not counted: {why}"),
        }
    }
}

/// The counting means, made once: the counting program and its counter, and the pipeline
/// statistics query, where the context has them.
struct Counting {
    atomic: Option<(Program, AtomicCounters)>,
    query: Option<FragmentInvocationsQuery>,
    /// Why neither is available.
    missing: String,
}

/// Both versions, their mask and their target (R32F colour, 32-bit depth).
pub struct DepthMask {
    branching: Program,
    write_depth: Program,
    masked: Program,
    mask: Texture,
    pub target: Framebuffer,
    query: OcclusionQuery,
    counting: Counting,
}

/// The atomic counter and the pipeline statistics query this context has.
fn counting(ctx: &Context) -> Result<Counting, Error> {
    let query = if FragmentInvocationsQuery::supported(ctx) {
        Some(FragmentInvocationsQuery::new(ctx)?)
    } else {
        None
    };
    let atomic = if ctx.has_compute() {
        let program = Program::rect(
            ctx,
            &[
                shader!("glsl/lecture3/depth_mask_counted.frag"),
                shader!("glsl/lecture3/depth_mask_common.glsl"),
                shader!("glsl/lecture3/depth_mask_counted_main.frag"),
            ],
        )?;
        Some((program, AtomicCounters::new(ctx, 1)?))
    } else {
        None
    };
    let info = ctx.info();
    let missing = format!(
        "this context (OpenGL {}.{}, {}) has neither atomic counters (OpenGL 4.2; 4.3's buffers \
         here) nor pipeline statistics queries (OpenGL 4.6 or {}); an occlusion query counts \
         the fragments that pass the depth test, not the shader's runs",
        info.gl_version.0,
        info.gl_version.1,
        info.renderer,
        crate::gl::query::PIPELINE_STATISTICS_EXTENSION
    );
    Ok(Counting {
        atomic,
        query,
        missing,
    })
}

/// The 2x2 quads of a `width x height` mask that hold at least one active pixel (mask value
/// below `fraction`).
pub fn active_quads(mask: &[f32], width: u32, height: u32, fraction: f32) -> u64 {
    let (qw, qh) = (width.div_ceil(2), height.div_ceil(2));
    let active =
        |x: u32, y: u32| x < width && y < height && mask[(y * width + x) as usize] < fraction;
    (0..qh)
        .flat_map(|qy| (0..qw).map(move |qx| (qx, qy)))
        .filter(|&(qx, qy)| (0..4).any(|k| active(2 * qx + k % 2, 2 * qy + k / 2)))
        .count() as u64
}

/// Whether `runs` counted shader runs fit a mask with `active` pixels in `active_quads` quads:
/// every active pixel ran, and nothing ran outside the active quads (at most four runs per
/// quad for each of the rectangle's two triangles: helper invocations may be counted).
pub fn runs_fit_mask(runs: u64, active: u64, active_quads: u64) -> bool {
    (active..=8 * active_quads).contains(&runs)
}

/// Checks a mask fraction (0..=1) and an iteration count (1..=16384: llvmpipe stops a
/// shader's loops after 65535 iterations).
pub fn check_parameters(fraction: f32, iterations: u32) -> Result<(), Error> {
    check_range("--fraction", fraction as f64, 0.0, 1.0)?;
    check_range("--iterations", iterations as f64, 1.0, 16384.0)
}

impl DepthMask {
    /// For a `width x height` mask (powers of two).
    pub fn new(ctx: &Context, mask: &[f32], width: u32, height: u32) -> Result<DepthMask, Error> {
        if !width.is_power_of_two() || !height.is_power_of_two() {
            return Err(Error::input(
                "--size",
                format!("{width}x{height}: both sides must be powers of two"),
            ));
        }
        if mask.len() != (width * height) as usize {
            return Err(Error::input(
                "mask",
                format!("{} values for {width}x{height} pixels", mask.len()),
            ));
        }
        let common = shader!("glsl/lecture3/depth_mask_common.glsl");
        let colour = Texture::new_2d(ctx, width, height, TextureFormat::R32F)?;
        let depth = Texture::new_2d(ctx, width, height, TextureFormat::Depth32F)?;
        Ok(DepthMask {
            branching: Program::rect(
                ctx,
                &[common, shader!("glsl/lecture3/depth_mask_branching.frag")],
            )?,
            write_depth: Program::rect(ctx, &[shader!("glsl/lecture3/depth_mask_write.frag")])?,
            masked: Program::rect(
                ctx,
                &[common, shader!("glsl/lecture3/depth_mask_masked.frag")],
            )?,
            mask: Texture::from_f32(ctx, width, height, TextureFormat::R32F, mask)?,
            target: Framebuffer::new(ctx, "depth mask picture", &[&colour], Some(&depth))?,
            query: OcclusionQuery::new(ctx)?,
            counting: counting(ctx)?,
        })
    }

    /// How the expensive shader's runs are counted here.
    pub fn run_counter(&self) -> RunCounter {
        match (&self.counting.atomic, &self.counting.query) {
            (Some(_), _) => RunCounter::AtomicCounter,
            (None, Some(_)) => RunCounter::PipelineStatistics,
            (None, None) => RunCounter::Unavailable(self.counting.missing.clone()),
        }
    }

    fn size(&self) -> Vec2 {
        Vec2::new(self.target.width() as f32, self.target.height() as f32)
    }

    /// The branching shader over every pixel; the fragments it ran (every pixel).
    pub fn run_branching(&self, fraction: f32, iterations: u32) -> Result<u64, Error> {
        check_parameters(fraction, iterations)?;
        self.target.clear_color(0, [0.0; 4])?;
        self.query.begin();
        let drawn = self
            .target
            .pass(&self.branching, "branching shader")?
            .texture("u_mask", &self.mask)
            .uniform("u_fraction", fraction)
            .uniform("u_iterations", iterations as i32)
            .uniform("u_size", self.size())
            .draw_full();
        self.query.end();
        drawn?;
        Ok(self.query.samples()?)
    }

    /// The mask into the depth buffer, then the expensive shader behind the depth test; the
    /// fragments that passed the depth test (occlusion query).
    pub fn run_masked(&self, fraction: f32, iterations: u32) -> Result<u64, Error> {
        check_parameters(fraction, iterations)?;
        self.write_mask(fraction)?;
        self.query.begin();
        let drawn = self.draw_expensive(&self.masked, iterations, Compare::Greater);
        self.query.end();
        drawn?;
        Ok(self.query.samples()?)
    }

    /// Checks the parameters, writes the mask, and gives the depth test of a counted draw:
    /// behind the mask (`masked`: only active pixels pass) or passing every pixel.
    fn prepare_count(
        &self,
        fraction: f32,
        iterations: u32,
        masked: bool,
    ) -> Result<Compare, Error> {
        check_parameters(fraction, iterations)?;
        self.write_mask(fraction)?;
        Ok(if masked {
            Compare::Greater
        } else {
            Compare::Always
        })
    }

    /// The runs of the expensive shader, counted as [`DepthMask::run_counter`] says, behind
    /// the depth mask (`masked`) or with the depth test passing every pixel; `None` where the
    /// context cannot count them. The picture is the same as [`DepthMask::run_masked`]'s (or
    /// the expensive function everywhere).
    pub fn count_runs(
        &self,
        fraction: f32,
        iterations: u32,
        masked: bool,
    ) -> Result<Option<u64>, Error> {
        let test = self.prepare_count(fraction, iterations, masked)?;
        if let Some((program, counters)) = &self.counting.atomic {
            counters.reset()?;
            counters.bind_for_draws(0)?;
            self.draw_expensive(program, iterations, test)?;
            return Ok(Some(counters.read()?[0] as u64));
        }
        self.invocations(iterations, test)
    }

    /// The plain expensive shader's invocations as the driver's pipeline statistics count
    /// them, behind the depth mask (`masked`) or not; `None` without pipeline statistics.
    pub fn count_invocations(
        &self,
        fraction: f32,
        iterations: u32,
        masked: bool,
    ) -> Result<Option<u64>, Error> {
        let test = self.prepare_count(fraction, iterations, masked)?;
        self.invocations(iterations, test)
    }

    fn invocations(&self, iterations: u32, test: Compare) -> Result<Option<u64>, Error> {
        let Some(query) = &self.counting.query else {
            return Ok(None);
        };
        query.begin();
        let drawn = self.draw_expensive(&self.masked, iterations, test);
        query.end();
        drawn?;
        Ok(Some(query.invocations()?))
    }

    /// The mask test into the depth buffer: depth 0 where active, 1 elsewhere.
    fn write_mask(&self, fraction: f32) -> Result<(), Error> {
        self.target.clear_color(0, [0.0; 4])?;
        self.target
            .pass(&self.write_depth, "mask into depth")?
            .texture("u_mask", &self.mask)
            .uniform("u_fraction", fraction)
            .state(DrawState {
                depth: Some(DepthTest {
                    func: Compare::Always,
                    write: true,
                }),
                color_write: false,
                ..DrawState::default()
            })
            .draw_full()?;
        Ok(())
    }

    /// `program` (the expensive sum, no `if`) over the target at depth 0.5 with depth test
    /// `test`, depth writes off.
    fn draw_expensive(
        &self,
        program: &Program,
        iterations: u32,
        test: Compare,
    ) -> Result<(), GlError> {
        self.target
            .pass(program, "expensive shader behind the depth test")?
            .uniform("u_iterations", iterations as i32)
            .uniform("u_size", self.size())
            .state(DrawState {
                depth: Some(DepthTest {
                    func: test,
                    write: false,
                }),
                ..DrawState::default()
            })
            .draw_full()
    }

    /// The picture of the last run, row by row from the bottom.
    pub fn read(&self) -> Result<Vec<f32>, GlError> {
        self.target
            .read_f32(0, Rect::sized(self.target.width(), self.target.height()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn masked_expensive_values_are_the_cpu_picture() {
        let (w, h, iterations) = (32, 16, 8);
        let expensive = cpu_expensive(w, h, iterations);
        for shape in [MaskShape::Blobs, MaskShape::Scattered] {
            let mask = mask(shape, w, h, 1);
            for fraction in [0.0, 0.05, 0.5, 1.0] {
                let (picture, active) = cpu_masked(&expensive, &mask, fraction);
                assert_eq!(
                    (picture, active),
                    cpu_picture(&mask, w, h, fraction, iterations),
                    "{shape:?} {fraction}"
                );
            }
        }
    }
}
