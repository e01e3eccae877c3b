//! The depth the peels are compared at [section 3.2 on the paper's own GPU]. Today the peel
//! depths `T_d(k)` and the fluid surface `T_dw` are 32-bit floats. The GeForce 7800 GTX the
//! paper ran on had no float depth: its depth buffer, and the depth texture a peel is
//! compared with, held 24-bit fixed-point values, whole steps of 2^-24 of the depth range.
//! Under that GPU's profile (`gl::period`) the peeler takes the period's way: 24-bit depth
//! with stencil, and the peel test of `glsl/mass/peel_depth24.glsl`, which compares a
//! fragment with the previous layer in whole steps (a shadow compare with a one-step bias).
//!
//! What changes: two surfaces whose depths fall in the same step are one layer. The nearer
//! is peeled (or, at exactly equal stored depths, the one drawn first) and the other is
//! lost with it, so its integrand `sgn(n_z) z` is missing at that pixel. With the body framed
//! to the depth range, a step is 2^-24 of the body's height (plus 1 %): only surfaces that
//! nearly touch merge. Float depth is no finer where it matters: the clip-space depth the
//! vertices carry is an fp32 number in [-1, 1], so fp32 depths are spaced 2^-25 to 2^-24
//! apart over most of the range. [`keep_distinct_steps`] is the CPU model of what a 24-bit
//! peel keeps at one pixel.

use super::framing::Framing;
use crate::gl::{peel, Context, ShaderSource, TextureFormat};
use crate::shader;
use serde::Serialize;

/// The peel test at 24 bits (replaces the GL layer's float snippet).
pub const PEEL_SNIPPET_24: ShaderSource<'static> = shader!("glsl/mass/peel_depth24.glsl");
/// The file naming the 24-bit peel stage's parts (adds no code).
pub const PEEL_MAIN_24: ShaderSource<'static> = shader!("glsl/mass/peel_main_depth24.frag");

/// Steps of a 24-bit depth buffer over the depth range [0, 1].
pub const STEPS_24: f64 = 16_777_215.0;

/// How peel depths are stored and compared.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PeelDepth {
    /// 32-bit float depth, compared exactly (today's GPUs).
    #[default]
    Float32,
    /// 24-bit fixed-point depth, compared in whole steps (the GeForce 7800 GTX).
    Fixed24,
}

impl PeelDepth {
    /// 32-bit float depth unless `ctx` runs under a period GPU without it.
    pub fn for_context(ctx: &Context) -> PeelDepth {
        if ctx.allows_format(TextureFormat::Depth32FStencil8) {
            PeelDepth::Float32
        } else {
            PeelDepth::Fixed24
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            PeelDepth::Float32 => "32-bit float depth",
            PeelDepth::Fixed24 => "24-bit depth",
        }
    }

    /// The depth (with stencil) of each peel `T_d(k)`.
    pub fn layer_format(self) -> TextureFormat {
        match self {
            PeelDepth::Float32 => TextureFormat::Depth32FStencil8,
            PeelDepth::Fixed24 => TextureFormat::Depth24Stencil8,
        }
    }

    /// The fluid surface's depth `T_dw` (no stencil needed, but the G70 had no depth-only
    /// float format either).
    pub fn water_format(self) -> TextureFormat {
        match self {
            PeelDepth::Float32 => TextureFormat::Depth32F,
            PeelDepth::Fixed24 => TextureFormat::Depth24Stencil8,
        }
    }

    /// The fragment-shader parts of the peel test, placed where `glsl/gl/peel.glsl` goes,
    /// and what follows the main file (nothing for float depth).
    pub fn peel_test(self) -> (ShaderSource<'static>, Option<ShaderSource<'static>>) {
        match self {
            PeelDepth::Float32 => (peel::PEEL_SNIPPET, None),
            PeelDepth::Fixed24 => (PEEL_SNIPPET_24, Some(PEEL_MAIN_24)),
        }
    }
}

/// The window depth in [0, 1] of a point at framing-relative height `z` (the framing's top
/// is depth 0, its bottom 1; the orthographic view of [`Framing::projection`]).
pub fn window_depth(framing: &Framing, z: f64) -> f64 {
    0.5 * (1.0 - z / framing.half_depth)
}

/// The 24-bit step a depth falls in, as the peel test counts it (rounded down).
pub fn step_24(depth: f64) -> u32 {
    (depth.clamp(0.0, 1.0) * STEPS_24).floor() as u32
}

/// What a 24-bit peel keeps of one pixel's surface crossings, given as framing-relative
/// heights in drawing order: the nearest crossing of each step, the others of its step lost
/// with it (a driver that stores two of them at one value keeps the one drawn first; tests
/// draw the nearer first). Returns the indices kept, nearest first. Exact for crossings two
/// or more steps apart or within one step; a pair across a step boundary less than two steps
/// apart may go either way, with how the driver rounds depths into the buffer
/// (`glsl/mass/peel_depth24.glsl`).
pub fn keep_distinct_steps(framing: &Framing, heights: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..heights.len()).collect();
    // Nearest first (highest z); a stable sort keeps drawing order among equal heights.
    order.sort_by(|&a, &b| heights[b].total_cmp(&heights[a]));
    let mut kept: Vec<usize> = Vec::new();
    let mut last_step: Option<u32> = None;
    for i in order {
        let step = step_24(window_depth(framing, heights[i]));
        if last_step.is_none_or(|s| step > s) {
            kept.push(i);
            last_step = Some(step);
        }
    }
    kept
}
