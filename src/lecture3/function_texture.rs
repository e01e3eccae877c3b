//! Technique 4, a function in a texture: a costly function tabulated once into a 1D texture
//! and read back with the texture unit's linear interpolation, instead of being computed in
//! every fragment. Two functions: paper 3's sigmoid (eq. 3, where the lecture's network spends
//! its `exp`), and a band-limited square wave of 16 odd harmonics (16 sines per value).
//!
//! Measured: the interpolation error against the exact function for several table sizes (on
//! the GPU, and on the CPU by the same linear interpolation, whose error is bounded by
//! h^2 max|f''| / 8 for texel spacing h), and the time of a lookup pass against the pass that
//! computes the function. The lecture names the technique only; the functions, the table
//! layout (texel centres on the domain's end points) and the measures are ours.

use crate::gl::{Context, Filter, Framebuffer, GlError, Program, Rect, Texture, TextureFormat};
use crate::lecture3::error::Error;
use crate::shader;
use serde::Serialize;

/// The tabulated function.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Function {
    /// 1 / (1 + e^-x) on [-8, 8].
    Sigmoid,
    /// (4 / pi) sum_{k<16} sin(2 pi (2k+1) x) / (2k+1) on one period, [0, 1].
    SquareWave,
}

impl Function {
    pub const ALL: [Function; 2] = [Function::Sigmoid, Function::SquareWave];

    pub fn name(self) -> &'static str {
        match self {
            Function::Sigmoid => "sigmoid",
            Function::SquareWave => "square wave (16 harmonics)",
        }
    }

    /// The tabulated interval.
    pub fn domain(self) -> (f64, f64) {
        match self {
            Function::Sigmoid => (-8.0, 8.0),
            Function::SquareWave => (0.0, 1.0),
        }
    }

    /// The exact value, in f64.
    pub fn exact(self, x: f64) -> f64 {
        match self {
            Function::Sigmoid => 1.0 / (1.0 + (-x).exp()),
            Function::SquareWave => {
                let sum: f64 = (0..16)
                    .map(|k| {
                        let n = (2 * k + 1) as f64;
                        (std::f64::consts::TAU * n * x).sin() / n
                    })
                    .sum();
                sum * 4.0 / std::f64::consts::PI
            }
        }
    }

    /// max |f''| on the domain (for the interpolation error bound): the sigmoid's is
    /// 1 / (6 sqrt 3); the wave's at most (4/pi) sum (2 pi)^2 n.
    pub fn max_second_derivative(self) -> f64 {
        match self {
            Function::Sigmoid => 1.0 / (6.0 * 3f64.sqrt()),
            Function::SquareWave => {
                let tau2 = std::f64::consts::TAU.powi(2);
                (0..16).map(|k| tau2 * (2 * k + 1) as f64).sum::<f64>() * 4.0 / std::f64::consts::PI
            }
        }
    }

    /// The shaders' `u_function`.
    fn shader_id(self) -> i32 {
        match self {
            Function::Sigmoid => 0,
            Function::SquareWave => 1,
        }
    }
}

/// Sample `s` of `total` (a power of two): x = lo + (hi - lo) (s + 0.5) / total, exact in
/// fp32 for the domains above, so CPU and GPU evaluate the same points.
pub fn sample_x(function: Function, s: u64, total: u64) -> f64 {
    let (lo, hi) = function.domain();
    lo + (hi - lo) * ((s as f64 + 0.5) / total as f64)
}

/// A function tabulated into a 1D R32F texture with linear filtering.
pub struct FunctionTable {
    pub function: Function,
    /// Texel i holds f(lo + i (hi - lo) / (n - 1)), rounded to fp32.
    pub values: Vec<f32>,
    pub texture: Texture,
}

impl FunctionTable {
    /// A table of `texels` values (2 up to the renderer's texture size).
    pub fn new(ctx: &Context, function: Function, texels: u32) -> Result<FunctionTable, Error> {
        let max = ctx.info().limits.max_texture_size;
        if !(2..=max).contains(&texels) {
            return Err(Error::input(
                "--texels",
                format!("{texels} texels: a table needs 2 to GL_MAX_TEXTURE_SIZE = {max}"),
            ));
        }
        let (lo, hi) = function.domain();
        let values: Vec<f32> = (0..texels)
            .map(|i| function.exact(lo + (hi - lo) * i as f64 / (texels - 1) as f64) as f32)
            .collect();
        let texture = Texture::new_1d(ctx, texels, TextureFormat::R32F)?;
        texture.upload_f32(&values)?;
        texture.set_filter(Filter::Linear);
        Ok(FunctionTable {
            function,
            values,
            texture,
        })
    }

    pub fn texels(&self) -> u32 {
        self.values.len() as u32
    }

    /// The table's linear interpolation at x, exactly (f64 weights), as a texture unit with
    /// exact weights would return it.
    pub fn interpolate(&self, x: f64) -> f64 {
        let (lo, hi) = self.function.domain();
        let n = self.values.len();
        let pos = ((x - lo) / (hi - lo) * (n - 1) as f64).clamp(0.0, (n - 1) as f64);
        let i = (pos.floor() as usize).min(n - 2);
        let w = pos - i as f64;
        self.values[i] as f64 * (1.0 - w) + self.values[i + 1] as f64 * w
    }

    /// The largest difference between neighbouring texels (how much a weight error matters).
    pub fn max_step(&self) -> f64 {
        self.values
            .windows(2)
            .map(|w| (w[1] - w[0]).abs() as f64)
            .fold(0.0, f64::max)
    }

    /// The interpolation error bound h^2 max|f''| / 8 (plus fp32 rounding of the texels).
    pub fn error_bound(&self) -> f64 {
        let (lo, hi) = self.function.domain();
        let h = (hi - lo) / (self.texels() - 1) as f64;
        h * h * self.function.max_second_derivative() / 8.0 + 1e-7
    }
}

/// How a pass gets the function's values.
#[derive(Clone, Copy)]
pub enum Evaluation<'a> {
    /// Computed in the shader.
    Exact(Function),
    /// Looked up in a table.
    Lookup(&'a FunctionTable),
}

/// The two passes and their R32F target: pixel p holds the sum of its K values.
pub struct FunctionPasses {
    exact: Program,
    lookup: Program,
    pub target: Framebuffer,
}

impl FunctionPasses {
    /// A `width x height` target (powers of two, so that sample positions are exact).
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<FunctionPasses, Error> {
        if !width.is_power_of_two() || !height.is_power_of_two() {
            return Err(Error::input(
                "function pass size",
                format!("{width}x{height}: both sides must be powers of two"),
            ));
        }
        let common = shader!("glsl/lecture3/function_common.glsl");
        let texture = Texture::new_2d(ctx, width, height, TextureFormat::R32F)?;
        Ok(FunctionPasses {
            exact: Program::rect(ctx, &[common, shader!("glsl/lecture3/function_exact.frag")])?,
            lookup: Program::rect(
                ctx,
                &[common, shader!("glsl/lecture3/function_lookup.frag")],
            )?,
            target: Framebuffer::new(ctx, "function values", &[&texture], None)?,
        })
    }

    /// Samples in one pass with `per_pixel` values per pixel.
    pub fn total(&self, per_pixel: u32) -> u64 {
        self.target.width() as u64 * self.target.height() as u64 * per_pixel as u64
    }

    /// One pass: every pixel sums `per_pixel` values (a power of two up to 4096, a loop
    /// well within llvmpipe's 65535 iterations; the whole pass below 2^22 samples, so that
    /// positions stay exact in fp32).
    pub fn run(&self, evaluation: Evaluation, per_pixel: u32) -> Result<(), Error> {
        let total = self.total(per_pixel);
        if !per_pixel.is_power_of_two() || per_pixel > 4096 || total > 1 << 22 {
            return Err(Error::input(
                "--per-pixel",
                format!(
                    "{per_pixel} values per pixel: a power of two up to 4096, with at most 2^22 \
                     samples in the pass"
                ),
            ));
        }
        let function = match evaluation {
            Evaluation::Exact(f) => f,
            Evaluation::Lookup(t) => t.function,
        };
        let (lo, hi) = function.domain();
        let program = match evaluation {
            Evaluation::Exact(_) => &self.exact,
            Evaluation::Lookup(_) => &self.lookup,
        };
        let mut pass = self.target.pass(program, "function values")?;
        pass.uniform("u_lo", lo as f32)
            .uniform("u_hi", hi as f32)
            .uniform("u_per_pixel", per_pixel as i32)
            .uniform("u_total", total as f32)
            .uniform("u_width", self.target.width() as i32);
        match evaluation {
            Evaluation::Exact(f) => pass.uniform("u_function", f.shader_id()),
            Evaluation::Lookup(t) => pass
                .texture("u_table", &t.texture)
                .uniform("u_texels", t.texels() as f32),
        };
        pass.draw_full()?;
        Ok(())
    }

    /// Each pixel's sum, row by row from the bottom.
    pub fn read(&self) -> Result<Vec<f32>, GlError> {
        self.target
            .read_f32(0, Rect::sized(self.target.width(), self.target.height()))
    }
}

/// Interpolation error of a table over `samples` points spread over the domain: (max, RMS)
/// of |lookup - exact|, for the given lookup.
pub fn error_against_exact(
    function: Function,
    lookup: impl Fn(u64) -> f64,
    samples: u64,
) -> (f64, f64) {
    let (mut max, mut sum2) = (0.0f64, 0.0f64);
    for s in 0..samples {
        let e = (lookup(s) - function.exact(sample_x(function, s, samples))).abs();
        max = max.max(e);
        sum2 += e * e;
    }
    (max, (sum2 / samples as f64).sqrt())
}
