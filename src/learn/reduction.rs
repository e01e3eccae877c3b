//! Lesson 3, reduction level by level: the sum and the maximum of an array by passes that each
//! combine a block of the level below into one texel, until one texel is left; first with
//! 2x2 blocks, then with 4x4 blocks (a wider fan-in: fewer passes, more reads per fragment).

use super::{
    chosen_exercise, no_compute, random_values, Exercise, Grid, Lesson, LessonInfo, LessonOptions,
    LessonRun, PaperStep, PassBuffer,
};
use crate::gl::reduce::ReduceOp;
use crate::gl::reduce_shared::SharedReducer;
use crate::gl::{Buffer, BufferUsage, Context, Framebuffer, Program, Texture, TextureFormat};
use crate::shader;

const REDUCE_2X2: &str = "glsl/learn/reduce_2x2.frag";
const REDUCE_WIDE: &str = "glsl/learn/reduce_wide.frag";
const REDUCE_COMPUTE: &str = "glsl/gl/compute/reduce.comp";

/// The array is `W x H` (not powers of two: the edges take the identities).
pub(crate) const W: u32 = 48;
pub(crate) const H: u32 = 40;
/// The wider fan-in.
const WIDE: u32 = 4;

/// fp32's unit roundoff, 2^-24.
pub(crate) const UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;

pub struct Reduction;

static INFO: LessonInfo = LessonInfo {
    id: "reduction",
    number: 3,
    title: "Reduction, level by level",
    idea: "A fragment writes one texel, so a sum over the whole array takes several passes: \
           each output texel combines a block of the level below, each level is smaller by \
           the block's side, and the last is one texel. 2x2 blocks take ceil(log2 n) passes; \
           4x4 blocks take ceil(log4 n), half as many, with four times the reads per \
           fragment. The same ladder gives the maximum (or any associative operation). \
           Lesson 10 times these passes against wider fan-ins and compute kernels, rung by \
           rung: `learn reduction --bench`.",
    paper_steps: &[
        PaperStep {
            paper: "Paper 4, section 3.3",
            step: "two-dimensional integrals by buffer reduction of the integrand targets",
            file: "src/mass/reduce.rs",
        },
        PaperStep {
            paper: "Paper 1, section 5.3.1",
            step: "hierarchical readback: P0 encoded 4x4 into P1, P2, P3",
            file: "src/collide/reduction_gpu.rs",
        },
    ],
    shaders: &[REDUCE_2X2, REDUCE_WIDE, REDUCE_COMPUTE],
    exercises: &[Exercise {
        number: 1,
        task: "Widen the reduction's fan-in to 4x4: each output texel must combine the whole \
               u_fan x u_fan block below it.",
        shader: REDUCE_WIDE,
        hints: [
            "Each output texel must combine its whole u_fan x u_fan block of the \
             level below; reading only part of it drops values, so the sum comes out \
             short.",
            "Texel (x, y) of the next level = the sum (and the maximum) over i, j in \
             [0, u_fan) of the level below at (u_fan x + i, u_fan y + j), skipping \
             those past its edge.",
            "for (int j = 0; j < u_fan; ++j) { for (int i = 0; i < u_fan; ++i) { ... \
             } }",
        ],
    }],
};

impl Lesson for Reduction {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        chosen_exercise(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        let values = random_values((W * H) as usize, 4, 0.0, 1.0);
        let sum: f64 = values.iter().map(|&v| v as f64).sum();
        let max = values.iter().fold(f32::MIN, |m, &v| m.max(v));
        // Red and green both start as the value: red will hold sums, green maxima.
        let rg: Vec<f32> = values.iter().flat_map(|&v| [v, v, 0.0, 0.0]).collect();
        let input = Texture::from_f32(ctx, W, H, TextureFormat::Rgba32F, &rg)?;
        run.pass(
            "upload",
            "",
            &format!(
                "{} values in [0, 1) into a {W}x{H} RGBA32F texture, red = green = value",
                W * H
            ),
            Some(PassBuffer::floats(W, H, 1, values.clone())),
        );
        let two = Program::rect(ctx, &[shader!("glsl/learn/reduce_2x2.frag")])?;
        let wide = Program::rect(ctx, &[shader!("glsl/learn/reduce_wide.frag")])?;
        for (program, fan, shader) in [(&two, 2, REDUCE_2X2), (&wide, WIDE, REDUCE_WIDE)] {
            let (gpu_sum, gpu_max, sizes) =
                ladder(ctx, &mut run, (&input, &values), program, fan, shader)?;
            check_results(
                &mut run,
                &format!("{fan}x{fan}"),
                (gpu_sum, gpu_max),
                (sum, max),
                &values,
                sizes.len() as u32 * (fan * fan - 1),
            );
            let ladder: Vec<String> = std::iter::once((W, H))
                .chain(sizes.iter().copied())
                .map(|(w, h)| format!("{w}x{h}"))
                .collect();
            run.note(
                &format!("{fan}x{fan} passes"),
                format!("{} ({})", sizes.len(), ladder.join(" -> ")),
            );
        }
        run.compute = Some(match no_compute(ctx) {
            Some(why) => why,
            None => compute(ctx, &mut run, &values, (sum, max))?,
        });
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// A ladder's result: the sum, the maximum, and the size of each level drawn.
type Ladder = (f32, f32, Vec<(u32, u32)>);

/// The passes of one fan-in down to one texel: (sum, maximum, the size of each level drawn).
fn ladder(
    ctx: &Context,
    run: &mut LessonRun,
    (input, values): (&Texture, &[f32]),
    program: &Program,
    fan: u32,
    shader: &str,
) -> anyhow::Result<Ladder> {
    let mut level = input.clone();
    let mut sizes = Vec::new();
    // region: reduce-level
    while level.width() > 1 || level.height() > 1 {
        let (w, h) = (level.width().div_ceil(fan), level.height().div_ceil(fan));
        let next = Texture::new_2d(ctx, w, h, TextureFormat::Rgba32F)?;
        let fb = Framebuffer::new(ctx, "reduction level", &[&next], None)?;
        let size = glam::IVec2::new(level.width() as i32, level.height() as i32);
        fb.pass(program, "reduce")?
            .texture("u_level", &level)
            .uniform("u_size", size)
            .uniform_if_used("u_fan", fan as i32)
            .draw_full()?;
        let rgba = next.download_f32()?;
        // endregion
        let rg: Vec<f32> = rgba.chunks_exact(4).flat_map(|t| [t[0], t[1]]).collect();
        sizes.push((w, h));
        run.pass(
            &format!("{fan}x{fan} level {}", sizes.len()),
            shader,
            &format!(
                "{}x{} -> {w}x{h}: each texel sums (panel \"sum\") and takes the maximum \
                 (panel \"max\") of the {fan}x{fan} block below it",
                level.width(),
                level.height()
            ),
            Some(PassBuffer::floats(w, h, 2, rg.clone()).named(&["sum", "max"])),
        );
        if sizes.len() == 1 {
            // The first level texel by texel: each block's sum (within fp32's rounding of its
            // fan x fan additions of values below 1) and its maximum.
            let blocks = (fan * fan) as f64;
            run.check_texels(
                &format!("{fan}x{fan} level 1 = the CPU's block sums and maxima"),
                Grid::new(w, h, 2),
                &rg,
                &blocks_cpu(values, fan),
                blocks * blocks * UNIT_ROUNDOFF,
            );
        }
        level = next;
    }
    let top = level.download_f32()?;
    Ok((top[0], top[1], sizes))
}

/// The first level on the CPU: for each `fan x fan` block of the `W x H` values (those past
/// the edge left out), its sum and its maximum.
pub(crate) fn blocks_cpu(values: &[f32], fan: u32) -> Vec<f32> {
    let (w, h) = (W.div_ceil(fan), H.div_ceil(fan));
    let mut out = Vec::with_capacity((w * h * 2) as usize);
    for by in 0..h {
        for bx in 0..w {
            let (mut sum, mut max) = (0f32, f32::MIN);
            for y in (by * fan..(by + 1) * fan).filter(|&y| y < H) {
                for x in (bx * fan..(bx + 1) * fan).filter(|&x| x < W) {
                    let v = values[(y * W + x) as usize];
                    sum += v;
                    max = max.max(v);
                }
            }
            out.extend([sum, max]);
        }
    }
    out
}

/// Compare a reduction's sum and maximum with the CPU's. `path` is the most additions any one
/// value goes through; the fp32 sum is then within `path * 2^-24 * sum |x|` of the exact one
/// (the values are non-negative, so sum |x| is the sum).
fn check_results(
    run: &mut LessonRun,
    how: &str,
    (gpu_sum, gpu_max): (f32, f32),
    (sum, max): (f64, f32),
    values: &[f32],
    path: u32,
) {
    let magnitude: f64 = values.iter().map(|&v| (v as f64).abs()).sum();
    run.check(
        &format!("{how}: sum = the CPU's (f64) sum, within {path} additions' fp32 rounding"),
        (gpu_sum as f64 - sum).abs(),
        path as f64 * UNIT_ROUNDOFF * magnitude,
    );
    run.check(
        &format!("{how}: maximum = the CPU's (exact)"),
        (gpu_max as f64 - max as f64).abs(),
        0.0,
    );
}

/// The compute counterpart: the GL layer's work-group reduction in shared memory.
fn compute(
    ctx: &Context,
    run: &mut LessonRun,
    values: &[f32],
    expected: (f64, f32),
) -> anyhow::Result<String> {
    // region: reduce-compute
    let reducer = SharedReducer::new(ctx)?;
    let vec4s: Vec<f32> = values.iter().flat_map(|&v| [v; 4]).collect();
    let buffer = Buffer::from_slice(ctx, &vec4s, BufferUsage::Static)?;
    let n = values.len() as u32;
    let sum = reducer.reduce(&buffer, n, ReduceOp::Sum)?[0];
    let max = reducer.reduce(&buffer, n, ReduceOp::Max)?[0];
    // endregion
    let passes = crate::gl::reduce_shared::passes_for(n);
    run.pass(
        "compute: shared-memory reduction",
        REDUCE_COMPUTE,
        &format!(
            "work groups of 256 invocations combine 512 values each in shared memory: {passes} \
             passes for {n} values"
        ),
        None,
    );
    // Each pass is a tree of 9 additions (2 per invocation, then 8 halvings).
    check_results(run, "compute", (sum, max), expected, values, passes * 9);
    Ok(format!(
        "ran {REDUCE_COMPUTE}, checked against the same CPU sum and maximum"
    ))
}
