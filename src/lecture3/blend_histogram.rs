//! Technique 7, simpler code with alpha blending (one of the lecture's tips): a histogram, or
//! any scatter-add, drawn as one point per value into a one-row target with additive
//! blending; the blending unit does the read-modify-write that a fragment shader cannot.
//! Compared with the gather formulation without blending (each bin reads every value) and
//! with the CPU histogram. Counts are sums of 1.0 in fp32, exact up to 2^24 per bin, so the
//! GPU histogram equals the CPU's exactly; weighted sums are compared with a tolerance.
//!
//! The lecture names the tip only; the histogram as its example is ours.

use crate::gl::{
    Blend, Buffer, BufferUsage, Context, DrawState, Framebuffer, GlError, Primitive, Program, Rect,
    Texture, TextureFormat, VertexArray,
};
use crate::lecture3::error::Error;
use crate::shader;

/// Which bins a histogram has: `bins` equal bins over `[lo, hi)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bins {
    pub lo: f32,
    pub hi: f32,
    pub bins: u32,
}

impl Bins {
    /// Checked: finite lo < hi, 1 to `max_bins` bins.
    pub fn new(lo: f32, hi: f32, bins: u32, max_bins: u32) -> Result<Bins, Error> {
        if !lo.is_finite() || !hi.is_finite() || lo >= hi {
            return Err(Error::input(
                "--range",
                format!("[{lo}, {hi}) is not a finite range with lo < hi"),
            ));
        }
        if !(1..=max_bins).contains(&bins) {
            return Err(Error::input(
                "--bins",
                format!("{bins} bins: 1 to {max_bins} on this renderer"),
            ));
        }
        Ok(Bins { lo, hi, bins })
    }

    /// bins / (hi - lo) in fp32, as the shaders get it.
    pub fn scale(&self) -> f32 {
        self.bins as f32 / (self.hi - self.lo)
    }

    /// The bin of `v`, by the shader's fp32 arithmetic; `None` outside `[lo, hi)`.
    pub fn bin(&self, v: f32) -> Option<u32> {
        let t = (v - self.lo) * self.scale();
        (t >= 0.0 && t < self.bins as f32).then(|| t.floor() as u32)
    }
}

/// The CPU histogram: per-bin sums of the weights (1 each without weights), and how many
/// values fell outside.
pub fn cpu_histogram(values: &[f32], weights: Option<&[f32]>, bins: &Bins) -> (Vec<f64>, usize) {
    let mut out = vec![0.0f64; bins.bins as usize];
    let mut outside = 0;
    for (i, &v) in values.iter().enumerate() {
        match bins.bin(v) {
            Some(b) => out[b as usize] += weights.map_or(1.0, |w| w[i] as f64),
            None => outside += 1,
        }
    }
    (out, outside)
}

/// Values (and weights) on the GPU: as a vertex buffer, one point each (the blending
/// version), and as textures in rows of at most 4096 texels (the gather version).
///
/// The points take their values from vertex attributes rather than from `texelFetch` in the
/// vertex shader: on Mesa 22.3's softpipe, vertex-stage fetches of texels in row 1 of a 2D
/// texture returned row 0.
pub struct Values {
    pub vertices: VertexArray,
    pub values: Texture,
    pub weights: Option<Texture>,
    pub count: usize,
}

/// The most values one histogram counts exactly (fp32 sums of 1.0).
pub const MAX_VALUES: usize = 1 << 24;

/// The most values the gather pass reads: its loop runs once per value, and llvmpipe ends a
/// shader's loops after 65535 iterations in all (nested loops share the count), silently.
pub const MAX_GATHER_VALUES: usize = 65535;

impl Values {
    /// Uploads `values` (finite) and optional `weights` (finite, one per value).
    pub fn new(ctx: &Context, values: &[f32], weights: Option<&[f32]>) -> Result<Values, Error> {
        if values.is_empty() || values.len() > MAX_VALUES {
            return Err(Error::input(
                "values",
                format!("{} values: 1 to 2^24 can be counted exactly", values.len()),
            ));
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(Error::input(
                "values",
                format!("value {i} is {}", values[i]),
            ));
        }
        if let Some(w) = weights {
            if w.len() != values.len() {
                return Err(Error::input(
                    "weights",
                    format!("{} weights for {} values", w.len(), values.len()),
                ));
            }
            if let Some(i) = w.iter().position(|v| !v.is_finite()) {
                return Err(Error::input("weights", format!("weight {i} is {}", w[i])));
            }
        }
        let columns = values.len().min(4096) as u32;
        let rows = values.len().div_ceil(columns as usize) as u32;
        let texture = |data: &[f32]| -> Result<Texture, GlError> {
            let mut padded = data.to_vec();
            padded.resize((columns * rows) as usize, 0.0);
            Texture::from_f32(ctx, columns, rows, TextureFormat::R32F, &padded)
        };
        let ones = vec![1.0f32; values.len()];
        let value_buffer = Buffer::from_slice(ctx, values, BufferUsage::Static)?;
        let weight_buffer = Buffer::from_slice(ctx, weights.unwrap_or(&ones), BufferUsage::Static)?;
        let mut vertices = VertexArray::new(ctx)?;
        vertices.float_attribute(0, &value_buffer, 1, 4, 0, 0)?;
        vertices.float_attribute(1, &weight_buffer, 1, 4, 0, 0)?;
        Ok(Values {
            vertices,
            values: texture(values)?,
            weights: weights.map(texture).transpose()?,
            count: values.len(),
        })
    }
}

/// How the GPU builds the histogram.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// One point per value, added by the blending unit.
    Blend,
    /// Each bin's pixel loops over every value (at most [`MAX_GATHER_VALUES`]).
    Gather,
}

/// The two programs and a `bins x 1` R32F target.
pub struct Histogram {
    points: Program,
    gather: Program,
    pub target: Framebuffer,
    pub bins: Bins,
}

impl Histogram {
    pub fn new(ctx: &Context, bins: Bins) -> Result<Histogram, Error> {
        let texture = Texture::new_2d(ctx, bins.bins, 1, TextureFormat::R32F)?;
        Ok(Histogram {
            points: Program::new(
                ctx,
                &[shader!("glsl/lecture3/histogram_points.vert")],
                &[shader!("glsl/lecture3/histogram_add.frag")],
            )?,
            gather: Program::rect(ctx, &[shader!("glsl/lecture3/histogram_gather.frag")])?,
            target: Framebuffer::new(ctx, "histogram", &[&texture], None)?,
            bins,
        })
    }

    /// Draws the histogram of `values` into the target.
    pub fn draw(&self, values: &Values, method: Method) -> Result<(), GlError> {
        if method == Method::Gather && values.count > MAX_GATHER_VALUES {
            return Err(GlError::Invalid(format!(
                "the gather histogram reads at most {MAX_GATHER_VALUES} values (one loop \
                 iteration each; llvmpipe stops loops there), not {}",
                values.count
            )));
        }
        self.target.clear_color(0, [0.0; 4])?;
        let program = match method {
            Method::Blend => &self.points,
            Method::Gather => &self.gather,
        };
        let mut pass = self.target.pass(program, "histogram")?;
        pass.uniform("u_lo", self.bins.lo)
            .uniform("u_scale", self.bins.scale())
            .uniform("u_bins", self.bins.bins as i32);
        match method {
            Method::Blend => pass
                .state(DrawState {
                    blend: Some(Blend::Add),
                    ..DrawState::default()
                })
                .draw_arrays(&values.vertices, Primitive::Points, 0, values.count),
            Method::Gather => pass
                .texture("u_values", &values.values)
                .texture(
                    "u_weights",
                    values.weights.as_ref().unwrap_or(&values.values),
                )
                .uniform("u_weighted", values.weights.is_some())
                .uniform("u_columns", values.values.width() as i32)
                .uniform("u_count", values.count as i32)
                .draw_full(),
        }
    }

    /// The bins read back.
    pub fn read(&self) -> Result<Vec<f32>, GlError> {
        self.target.read_f32(0, Rect::sized(self.bins.bins, 1))
    }
}
