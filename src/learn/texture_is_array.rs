//! Lesson 0, a texture is an array: upload an array, draw it into targets of three formats,
//! read each back, and compare with the CPU's rounding of the same values to each format
//! (what RGBA8, R16F and R32F keep and lose); then sample a row at texel centres and at texel
//! edges with linear filtering (what `(i + 0.5) / N` gives and what `i / N` gives).

use super::{
    chosen_exercise, max_difference, no_compute, Exercise, Grid, Lesson, LessonInfo, LessonOptions,
    LessonRun, PaperStep, PassBuffer,
};
use crate::gl::{
    memory_barrier, Barrier, Buffer, BufferUsage, ComputeProgram, Context, Filter, Framebuffer,
    Program, Texture, TextureFormat,
};
use crate::shader;

const COPY: &str = "glsl/learn/texture_copy.frag";
const SAMPLE: &str = "glsl/learn/texel_sample.frag";
const READ_COMPUTE: &str = "glsl/learn/compute/texture_read.comp";

/// The array is `SIDE x SIDE`; the sampled row `ROW` texels.
const SIDE: u32 = 8;
const ROW: u32 = 8;

pub struct TextureIsArray;

static INFO: LessonInfo = LessonInfo {
    id: "texture-is-array",
    number: 0,
    title: "A texture is an array",
    idea: "A 2D texture is a 2D array the GPU reads; a framebuffer is the array it writes. \
           Upload copies an array in, glGetTexImage copies it out, and the texel format decides \
           what survives: RGBA8 clamps to [0, 1] and keeps 256 steps, R16F keeps 11 significant \
           bits up to 65504, R32F keeps every float. Read by index with texelFetch; with \
           normalised coordinates, texel i's centre is (i + 0.5) / N, and its edge i / N under \
           linear filtering is the mean of two neighbours.",
    paper_steps: &[
        PaperStep {
            paper: "Paper 1, section 5.1",
            step: "the vertex positions of both models in float textures",
            file: "src/collide/vertex_textures.rs",
        },
        PaperStep {
            paper: "Paper 3, section 3",
            step: "texture creation: the weights and inputs as float textures",
            file: "src/mlp/textures.rs",
        },
    ],
    shaders: &[COPY, SAMPLE, READ_COMPUTE],
    exercises: &[Exercise {
        number: 1,
        task: "Sample texel i at the point u_offset into it (0.5: its centre), not at its left \
               edge, so that the centre pass reads each texel's own value.",
        shader: SAMPLE,
        hints: [
            "Texel i of a row of N covers [i/N, (i+1)/N) in normalised coordinates; a \
             point on a border between two texels gets half of each under linear \
             filtering, so a GPGPU read aims at a point inside the texel.",
            "The point u_offset of the way into texel i is x = (i + u_offset) / N; \
             u_offset = 0.5 is its centre, where linear filtering returns the texel's \
             own value.",
            "float x = (i + u_offset) / u_size.x;",
        ],
    }],
};

impl Lesson for TextureIsArray {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        chosen_exercise(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        let values = test_values();
        // region: upload
        let input = Texture::from_f32(ctx, SIDE, SIDE, TextureFormat::R32F, &values)?;
        // endregion
        run.pass(
            "upload",
            "",
            "glTexSubImage2D copies 64 floats (rows from the bottom) into an 8x8 R32F texture",
            Some(PassBuffer::floats(SIDE, SIDE, 1, values.clone())),
        );
        formats(ctx, &mut run, &input, &values)?;
        texel_centres(ctx, &mut run)?;
        run.compute = Some(match no_compute(ctx) {
            Some(why) => why,
            None => compute(ctx, &mut run, &input, &values)?,
        });
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// The uploaded array: a ramp across [-0.25, 1.25] (so RGBA8 clamps both ends), then values
/// that show each format's steps: thirds and tenths, ties, large numbers up to R16F's
/// largest finite value 65504.
fn test_values() -> Vec<f32> {
    let mut values: Vec<f32> = (0..48).map(|k| -0.25 + 1.5 * k as f32 / 47.0).collect();
    values.extend([
        1.0 / 3.0,
        0.1,
        0.001,
        std::f32::consts::PI,
        1000.1,
        2049.0,
        4097.0,
        12345.678,
        60000.0,
        65504.0,
        -1000.0,
        -0.001,
        7.77,
        0.5 / 255.0,
        100.0 / 255.0,
        1.0 - 1e-7,
    ]);
    values
}

/// The CPU's rounding to a normalised byte: clamp to [0, 1], nearest of 256 steps.
pub fn round_unorm8(x: f32) -> f32 {
    (x.clamp(0.0, 1.0) * 255.0).round() / 255.0
}

/// The step of a half float at `x`: 2^(e - 10) for `x` in [2^e, 2^(e+1)), and the subnormal
/// step 2^-24 below 2^-14.
pub fn half_step(x: f32) -> f32 {
    let exponent = (((x.abs().to_bits() >> 23) & 0xff) as i32 - 127).max(-14);
    2f32.powi(exponent - 10)
}

/// The CPU's rounding to a half float (nearest, ties to even), for `|x| <= 65504`.
pub fn round_half(x: f32) -> f32 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let step = half_step(x);
    (x / step).round_ties_even() * step
}

/// Draw the array into an RGBA8, an R16F and an R32F target; compare each with the CPU's
/// rounding, and note what each lost against the values uploaded.
fn formats(
    ctx: &Context,
    run: &mut LessonRun,
    input: &Texture,
    values: &[f32],
) -> anyhow::Result<()> {
    let copy = Program::rect(ctx, &[shader!("glsl/learn/texture_copy.frag")])?;
    for format in [
        TextureFormat::Rgba8,
        TextureFormat::R16F,
        TextureFormat::R32F,
    ] {
        // region: copy-into-format
        let target = Texture::new_2d(ctx, SIDE, SIDE, format)?;
        let fb = Framebuffer::new(ctx, format.name(), &[&target], None)?;
        fb.pass(&copy, "copy")?
            .texture("u_input", input)
            .draw_full()?;
        let (back, float) = match format {
            TextureFormat::Rgba8 => (
                target
                    .download_u8()?
                    .chunks_exact(4)
                    .map(|t| t[0] as f32 / 255.0)
                    .collect::<Vec<f32>>(),
                false,
            ),
            _ => (target.download_f32()?, true),
        };
        // endregion
        let name = format!("copy into {}", format.name());
        let buffer = PassBuffer {
            float,
            ..PassBuffer::floats(SIDE, SIDE, 1, back.clone())
        };
        run.pass(
            &name,
            COPY,
            &format!(
                "one fragment per texel reads the R32F array with texelFetch and writes it to \
                 an 8x8 {} target; glGetTexImage reads it back",
                format.name()
            ),
            Some(buffer),
        );
        compare_format(run, format, values, &back);
    }
    Ok(())
}

/// The checks and notes of one format.
fn compare_format(run: &mut LessonRun, format: TextureFormat, values: &[f32], back: &[f32]) {
    match format {
        TextureFormat::Rgba8 => {
            // In whole steps of 1/255: GL lets the conversion round either way within one.
            let cpu: Vec<f32> = values.iter().map(|&x| round_unorm8(x)).collect();
            let steps: Vec<f64> = back
                .iter()
                .zip(&cpu)
                .map(|(&b, &c)| ((b as f64 - c as f64) * 255.0).abs().round())
                .collect();
            run.check(
                "RGBA8 read back = the CPU's rounding to 1/255 steps (error in steps)",
                largest(&steps),
                1.0,
            );
            run.note(
                "RGBA8 rounding",
                format!(
                    "{} of {} values came back one step from the nearest (the CPU's rounding)",
                    steps.iter().filter(|&&s| s > 0.0).count(),
                    values.len()
                ),
            );
            let inside: Vec<(f32, f32)> = values
                .iter()
                .zip(back)
                .filter(|(x, _)| (0.0..=1.0).contains(*x))
                .map(|(&x, &b)| (x, b))
                .collect();
            let lost = inside
                .iter()
                .map(|&(x, b)| (x as f64 - b as f64).abs())
                .fold(0.0, f64::max);
            let clamped = values.len() - inside.len();
            run.note(
                "RGBA8 keeps",
                format!(
                    "values in [0, 1] to within {lost:.2e} (half a step is {:.2e}); {clamped} of \
                     {} values outside [0, 1] came back clamped",
                    0.5 / 255.0,
                    values.len()
                ),
            );
        }
        TextureFormat::R16F => {
            // In whole steps of a half float at each value: GL lets the conversion round to
            // nearest or toward zero, at most one step apart.
            let steps: Vec<f64> = values
                .iter()
                .zip(back)
                .map(|(&x, &b)| ((round_half(x) as f64 - b as f64) / half_step(x) as f64).abs())
                .map(|s| s.round())
                .collect();
            run.check(
                "R16F read back = the CPU's rounding to half floats (error in half-float steps)",
                largest(&steps),
                1.0,
            );
            run.note(
                "R16F rounding",
                format!(
                    "{} of {} values came back one step from the nearest half float (the \
                     CPU's rounding, ties to even): this renderer rounds {}",
                    steps.iter().filter(|&&s| s > 0.0).count(),
                    values.len(),
                    if toward_zero(values, back) {
                        "toward zero"
                    } else {
                        "to nearest"
                    }
                ),
            );
            let relative = values
                .iter()
                .zip(back)
                .filter(|(x, _)| x.abs() >= 2f32.powi(-14))
                .map(|(&x, &b)| ((x as f64 - b as f64) / x as f64).abs())
                .fold(0.0, f64::max);
            run.note(
                "R16F keeps",
                format!(
                    "11 significant bits: largest relative error {relative:.2e} (2^-11 = {:.2e}); \
                     2049 came back as {}",
                    2f64.powi(-11),
                    back[values.iter().position(|&x| x == 2049.0).unwrap_or(0)]
                ),
            );
        }
        _ => {
            run.check_texels(
                "R32F read back = the values uploaded (exact)",
                Grid::new(SIDE, SIDE, 1),
                back,
                values,
                0.0,
            );
            run.note(
                "R32F keeps",
                "every value, bit for bit (24 significant bits)",
            );
        }
    }
}

/// The largest of `steps`, infinite if one is NaN (a value that did not come back finite).
fn largest(steps: &[f64]) -> f64 {
    steps.iter().fold(
        0.0,
        |m: f64, &d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
    )
}

/// Whether every value came back as its half float rounded toward zero.
fn toward_zero(values: &[f32], back: &[f32]) -> bool {
    values.iter().zip(back).all(|(&x, &b)| {
        let step = half_step(x);
        b == (x / step).trunc() * step
    })
}

/// Sample a row of `ROW` texels with linear filtering at each texel's centre and at its left
/// edge; compare with the texel values and with the means of neighbours.
fn texel_centres(ctx: &Context, run: &mut LessonRun) -> anyhow::Result<()> {
    // A row whose neighbours differ by different amounts, so a mean is never a texel value.
    let row: Vec<f32> = (0..ROW).map(|i| (i * i) as f32).collect();
    let input = Texture::from_f32(ctx, ROW, 1, TextureFormat::R32F, &row)?;
    input.set_filter(Filter::Linear);
    let sample = Program::rect(ctx, &[shader!("glsl/learn/texel_sample.frag")])?;
    let scale = row.iter().fold(0f32, |m, v| m.max(v.abs())) as f64;
    for (offset, name) in [
        (0.5f32, "sample at (i + 0.5) / N"),
        (0.0, "sample at i / N"),
    ] {
        // region: sample-texel-centres
        let target = Texture::new_2d(ctx, ROW, 1, TextureFormat::R32F)?;
        let fb = Framebuffer::new(ctx, name, &[&target], None)?;
        fb.pass(&sample, name)?
            .texture("u_input", &input)
            .uniform("u_size", glam::Vec2::new(ROW as f32, 1.0))
            .uniform("u_offset", offset)
            .draw_full()?;
        let back = target.download_f32()?;
        // endregion
        let expected: Vec<f32> = if offset == 0.5 {
            row.clone()
        } else {
            (0..ROW as usize)
                .map(|i| 0.5 * (row[i.saturating_sub(1)] + row[i]))
                .collect()
        };
        run.pass(
            name,
            SAMPLE,
            &format!(
                "texture() with GL_LINEAR at the point {offset} into each of {ROW} texels \
                 holding i*i"
            ),
            Some(PassBuffer::floats(ROW, 1, 1, back.clone())),
        );
        // The weights here are 0 and 1/2, exact in any filter's fixed-point weights, so the
        // only rounding is fp32's in the mean: relative 1e-6 of the row's largest value.
        let what = if offset == 0.5 {
            "centres (i + 0.5) / N read each texel's own value"
        } else {
            "edges i / N read the mean of texels i-1 and i (linear filtering)"
        };
        run.check_texels(what, Grid::new(ROW, 1, 1), &back, &expected, 1e-6 * scale);
        if offset == 0.0 {
            run.note(
                "texel edges",
                format!(
                    "at i / N linear filtering gave {:?} for texels holding {:?}; nearest \
                     filtering there may give either neighbour, so GPGPU code samples centres \
                     or uses texelFetch",
                    back, row
                ),
            );
        }
    }
    Ok(())
}

/// The compute counterpart: the same texture read by index into a storage buffer.
fn compute(
    ctx: &Context,
    run: &mut LessonRun,
    input: &Texture,
    values: &[f32],
) -> anyhow::Result<String> {
    // region: compute-read
    let program = ComputeProgram::new(ctx, &[shader!("glsl/learn/compute/texture_read.comp")])?;
    let out = Buffer::new(ctx, values.len() * 4, BufferUsage::Dynamic)?;
    program
        .dispatch("texture read")
        .texture("u_input", input)
        .uniform("u_size", glam::IVec2::new(SIDE as i32, SIDE as i32))
        .storage(0, &out)
        .run_over(values.len() as u32)?;
    memory_barrier(ctx, &[Barrier::BufferUpdate]);
    let back: Vec<f32> = out.read()?;
    // endregion
    run.pass(
        "compute: read by index",
        READ_COMPUTE,
        "one invocation per texel reads it with texelFetch into a storage buffer",
        Some(PassBuffer::floats(SIDE, SIDE, 1, back.clone())),
    );
    run.check(
        "compute: the storage buffer = the values uploaded (exact)",
        max_difference(&back, values),
        0.0,
    );
    Ok(format!(
        "ran {READ_COMPUTE}, checked against the same values"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_rounding_keeps_eleven_bits() {
        assert_eq!(round_half(1.0), 1.0);
        assert_eq!(round_half(2049.0), 2048.0); // a tie, to even
        assert_eq!(round_half(2051.0), 2052.0); // a tie, to even
        assert_eq!(round_half(65504.0), 65504.0);
        assert_eq!(round_half(1.0 + 2f32.powi(-10)), 1.0 + 2f32.powi(-10));
        assert_eq!(round_half(2f32.powi(-24)), 2f32.powi(-24));
        assert_eq!(round_unorm8(-0.5), 0.0);
        assert_eq!(round_unorm8(0.5), 128.0 / 255.0);
    }
}
