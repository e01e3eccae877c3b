//! Lesson 4, several outputs: multiple render targets. One pass computes eight integrands of a
//! height field's volume moments per cell and writes them to two RGBA32F targets at once; the
//! CPU sums them into the volume and centroid.

use super::{
    chosen_exercise, max_difference, no_compute, Exercise, Grid, Lesson, LessonInfo, LessonOptions,
    LessonRun, PaperStep, PassBuffer,
};
use crate::gl::{
    memory_barrier, Barrier, Buffer, BufferUsage, ComputeProgram, Context, Framebuffer, Program,
    Texture, TextureFormat,
};
use crate::shader;

const INTEGRANDS: &str = "glsl/learn/integrands.frag";
const INTEGRANDS_COMPUTE: &str = "glsl/learn/compute/integrands.comp";

/// Cells per side.
const N: u32 = 16;

/// What each channel of the two targets holds.
const TARGET_0: &[&str] = &["z", "x z", "y z", "z^2/2"];
const TARGET_1: &[&str] = &["x^2 z", "y^2 z", "z^3/3", "x y z"];

pub struct SeveralOutputs;

static INFO: LessonInfo = LessonInfo {
    id: "several-outputs",
    number: 4,
    title: "Several outputs (MRT)",
    idea: "A fragment shader may write up to GL_MAX_DRAW_BUFFERS targets in one pass, each an \
           RGBA texel at the same pixel. Results computed from the same inputs are written \
           together instead of recomputed per target: eight integrands of a height field, \
           four in each of two targets.",
    paper_steps: &[
        PaperStep {
            paper: "Paper 4, section 3.1",
            step: "the integrands of the volume integrals, written to three render targets",
            file: "src/mass/integrands.rs",
        },
        PaperStep {
            paper: "Paper 2, section 2",
            step: "pass 1: skinned positions to target 0 and normals to target 1",
            file: "src/crowd/pass1_skinning.rs",
        },
    ],
    shaders: &[INTEGRANDS, INTEGRANDS_COMPUTE],
    exercises: &[Exercise {
        number: 1,
        task: "Write the second target too: x^2 z, y^2 z, z^3 / 3 and x y z.",
        shader: INTEGRANDS,
        hints: [
            "A fragment shader can write several outputs in one pass: o_second \
             (location 1) lands in the framebuffer's second colour attachment, target \
             1.",
            "Target 1 holds the second moments of the column [0, z] over the texel at \
             p: (x^2 z, y^2 z, z^3 / 3, x y z).",
            "o_second = vec4(p.x * p.x * z, p.y * p.y * z, z * z * z / 3.0, p.x * p.y \
             * z);",
        ],
    }],
};

impl Lesson for SeveralOutputs {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        chosen_exercise(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        let height = height_field(N);
        let (first, second) = integrands_cpu(&height, N);
        let tz = Texture::from_f32(ctx, N, N, TextureFormat::R32F, &height)?;
        run.pass(
            "upload",
            "",
            &format!("a {N}x{N} height field z(x, y) in [0.2, 0.8] into an R32F texture"),
            Some(PassBuffer::floats(N, N, 1, height.clone())),
        );
        // region: mrt-pass
        let t0 = Texture::new_2d(ctx, N, N, TextureFormat::Rgba32F)?;
        let t1 = Texture::new_2d(ctx, N, N, TextureFormat::Rgba32F)?;
        let fb = Framebuffer::new(ctx, "integrands", &[&t0, &t1], None)?;
        let program = Program::rect(ctx, &[shader!("glsl/learn/integrands.frag")])?;
        fb.pass(&program, "integrands")?
            .texture("u_height", &tz)
            .uniform("u_size", glam::Vec2::new(N as f32, N as f32))
            .draw_full()?;
        let gpu0 = t0.download_f32()?;
        let gpu1 = t1.download_f32()?;
        // endregion
        run.pass(
            "integrands: target 0",
            INTEGRANDS,
            "one pass, two targets: target 0 gets z, x z, y z, z^2/2",
            Some(PassBuffer::floats(N, N, 4, gpu0.clone()).named(TARGET_0)),
        );
        run.pass(
            "integrands: target 1",
            INTEGRANDS,
            "the same pass's target 1: x^2 z, y^2 z, z^3/3, x y z",
            Some(PassBuffer::floats(N, N, 4, gpu1.clone()).named(TARGET_1)),
        );
        run.check_texels(
            "target 0 = the CPU's integrands",
            Grid::new(N, N, 4),
            &gpu0,
            &first,
            TOLERANCE,
        );
        run.check_texels(
            "target 1 = the CPU's integrands",
            Grid::new(N, N, 4),
            &gpu1,
            &second,
            TOLERANCE,
        );
        let cell = 1.0 / (N * N) as f64;
        let volume: f64 = gpu0.chunks_exact(4).map(|t| t[0] as f64).sum::<f64>() * cell;
        let mx: f64 = gpu0.chunks_exact(4).map(|t| t[1] as f64).sum::<f64>() * cell;
        let my: f64 = gpu0.chunks_exact(4).map(|t| t[2] as f64).sum::<f64>() * cell;
        let mz: f64 = gpu0.chunks_exact(4).map(|t| t[3] as f64).sum::<f64>() * cell;
        run.note(
            "from the targets",
            format!(
                "volume {volume:.5}, centroid ({:.4}, {:.4}, {:.4})",
                mx / volume,
                my / volume,
                mz / volume
            ),
        );
        run.note(
            "draw buffers",
            format!(
                "this renderer allows {} targets per pass (GL_MAX_DRAW_BUFFERS)",
                ctx.info().limits.max_draw_buffers
            ),
        );
        run.compute = Some(match no_compute(ctx) {
            Some(why) => why,
            None => compute(ctx, &mut run, &tz, (&first, &second))?,
        });
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// Every integrand is a product of at most three values in [0, 1] and one division: at most
/// four fp32 roundings of a value below 1, 4 * 2^-24 = 2.4e-7; 1e-6 leaves room for a
/// compiler that computes z * z * z / 3 as z * z * (z * 0.333...).
const TOLERANCE: f64 = 1e-6;

/// A smooth height field in [0.2, 0.8], sampled at cell centres.
pub fn height_field(n: u32) -> Vec<f32> {
    let mut z = Vec::with_capacity((n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
            z.push(0.5 + 0.3 * (6.0 * x).sin() * (4.0 * y).cos());
        }
    }
    z
}

/// The two targets' integrands on the CPU, in the shader's order of operations.
pub fn integrands_cpu(height: &[f32], n: u32) -> (Vec<f32>, Vec<f32>) {
    let mut first = Vec::with_capacity(height.len() * 4);
    let mut second = Vec::with_capacity(height.len() * 4);
    for (k, &z) in height.iter().enumerate() {
        let (i, j) = (k as u32 % n, k as u32 / n);
        let (x, y) = ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
        first.extend([z, x * z, y * z, z * z * 0.5]);
        second.extend([x * x * z, y * y * z, z * z * z / 3.0, x * y * z]);
    }
    (first, second)
}

fn compute(
    ctx: &Context,
    run: &mut LessonRun,
    height: &Texture,
    (first, second): (&[f32], &[f32]),
) -> anyhow::Result<String> {
    // region: integrands-compute
    let program = ComputeProgram::new(ctx, &[shader!("glsl/learn/compute/integrands.comp")])?;
    let b0 = Buffer::new(ctx, first.len() * 4, BufferUsage::Dynamic)?;
    let b1 = Buffer::new(ctx, second.len() * 4, BufferUsage::Dynamic)?;
    let groups = N.div_ceil(8);
    program
        .dispatch("integrands")
        .texture("u_height", height)
        .uniform("u_size", glam::IVec2::new(N as i32, N as i32))
        .storage(0, &b0)
        .storage(1, &b1)
        .run([groups, groups, 1])?;
    memory_barrier(ctx, &[Barrier::BufferUpdate]);
    let gpu0: Vec<f32> = b0.read()?;
    let gpu1: Vec<f32> = b1.read()?;
    // endregion
    run.pass(
        "compute: integrands",
        INTEGRANDS_COMPUTE,
        "one invocation per cell writes its eight integrands to two storage buffers",
        Some(PassBuffer::floats(N, N, 4, gpu1.clone()).named(TARGET_1)),
    );
    run.check(
        "compute: both buffers = the CPU's integrands",
        max_difference(&gpu0, first).max(max_difference(&gpu1, second)),
        TOLERANCE,
    );
    Ok(format!(
        "ran {INTEGRANDS_COMPUTE}, checked against the same CPU integrands"
    ))
}
