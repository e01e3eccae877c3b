//! Lesson 5, scatter and blend: a histogram. A fragment writes only its own pixel, but a vertex
//! may go anywhere: one point per value, placed by the vertex shader on the pixel of its bin,
//! and additive blending sums the points that land on the same pixel.

use super::{
    chosen_exercise, no_compute, random_values, Exercise, Grid, Lesson, LessonInfo, LessonOptions,
    LessonRun, PaperStep, PassBuffer,
};
use crate::gl::{
    memory_barrier, Barrier, Blend, Buffer, BufferUsage, ComputeProgram, Context, DrawState,
    Framebuffer, Primitive, Program, Texture, TextureFormat,
};
use crate::shader;

const POINTS: &str = "glsl/learn/scatter_points.vert";
const COUNT: &str = "glsl/learn/count_one.frag";
const HISTOGRAM_COMPUTE: &str = "glsl/learn/compute/histogram.comp";

/// The values are a `W x H` texture; the histogram has `BINS` bins.
const W: u32 = 32;
const H: u32 = 24;
const BINS: u32 = 16;

pub struct ScatterAndBlend;

static INFO: LessonInfo = LessonInfo {
    id: "scatter-and-blend",
    number: 5,
    title: "Scatter and blend",
    idea: "A fragment shader gathers (reads anywhere) but cannot scatter (write anywhere). The \
           vertex shader can: draw one point per element and let it compute where the point \
           lands. Several points on one pixel overwrite each other, unless blending combines \
           them: with additive blending each point adds its value, which makes a histogram.",
    paper_steps: &[
        PaperStep {
            paper: "Lecture 3, simpler code with alpha blending",
            step: "a histogram drawn as one point per value with additive blending",
            file: "src/lecture3/blend_histogram.rs",
        },
        PaperStep {
            paper: "Paper 4, section 3.3",
            step: "each peel's integrand targets added into running sums by a blended pass",
            file: "src/mass/reduce.rs",
        },
    ],
    shaders: &[POINTS, COUNT, HISTOGRAM_COMPUTE],
    exercises: &[Exercise {
        number: 1,
        task: "Place each point on its value's bin (u_bins equal bins over [0, 1)).",
        shader: POINTS,
        hints: [
            "A scatter writes where the data says: the vertex shader moves each point \
             to its value's bin, and additive blending counts the points that land \
             there.",
            "With u_bins bins over [0, 1), a value falls in bin floor(value * \
             u_bins); a value that rounds up to 1 belongs to the last bin, u_bins - \
             1.",
            "float bin = min(floor(value * float(u_bins)), float(u_bins - 1));",
        ],
    }],
};

impl Lesson for ScatterAndBlend {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        chosen_exercise(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        // A skewed distribution (the square of a uniform value), so the bins differ.
        let values: Vec<f32> = random_values((W * H) as usize, 5, 0.0, 1.0)
            .into_iter()
            .map(|v| v * v)
            .collect();
        let cpu = histogram_cpu(&values, BINS);
        let tv = Texture::from_f32(ctx, W, H, TextureFormat::R32F, &values)?;
        run.pass(
            "upload",
            "",
            &format!(
                "{} values in [0, 1) into a {W}x{H} R32F texture",
                values.len()
            ),
            Some(PassBuffer::floats(W, H, 1, values.clone())),
        );
        // region: scatter-program
        let program = Program::new(
            ctx,
            &[shader!("glsl/learn/scatter_points.vert")],
            &[shader!("glsl/learn/count_one.frag")],
        )?;
        // endregion
        let mut blended = Vec::new();
        for blend in [Some(Blend::Add), None] {
            // region: scatter-pass
            let bins = Texture::new_2d(ctx, BINS, 1, TextureFormat::R32F)?;
            let fb = Framebuffer::new(ctx, "histogram", &[&bins], None)?;
            fb.pass(&program, "scatter points")?
                .state(DrawState {
                    blend,
                    ..DrawState::default()
                })
                .texture("u_values", &tv)
                .uniform("u_width", W as i32)
                .uniform("u_bins", BINS as i32)
                .draw_attributeless(Primitive::Points, values.len(), 1)?;
            let gpu = bins.download_f32()?;
            // endregion
            if blend.is_some() {
                run.pass(
                    "scatter with additive blending",
                    POINTS,
                    &format!(
                        "{} points, each placed by the vertex shader on its bin's pixel of a \
                         {BINS}x1 R32F target; each fragment writes 1 and blending adds it",
                        values.len()
                    ),
                    Some(
                        PassBuffer::floats(BINS, 1, 1, gpu.clone())
                            .in_set("bins")
                            .with_reference(cpu.clone()),
                    ),
                );
                // Counts are sums of 1.0, exact in fp32 up to 2^24.
                run.check_texels(
                    "the blended bins = the CPU's histogram (exact counts)",
                    Grid::new(BINS, 1, 1),
                    &gpu,
                    &cpu,
                    0.0,
                );
                let total: f64 = gpu.iter().map(|&c| c as f64).sum();
                run.check(
                    "every point landed in a bin: the counts add up to the values (exact)",
                    (total - values.len() as f64).abs(),
                    0.0,
                );
                blended = gpu;
            } else {
                run.pass(
                    "scatter without blending",
                    POINTS,
                    "the same points without blending: each fragment overwrites the bin",
                    Some(
                        PassBuffer::floats(BINS, 1, 1, gpu.clone())
                            .in_set("bins")
                            .with_reference(cpu.clone()),
                    ),
                );
                run.note(
                    "without blending",
                    format!(
                        "without blending the GPU's bins held {:?}, with additive blending {:?} \
                         (the CPU's histogram: {:?}): a point overwrites what the bin held",
                        gpu, blended, cpu
                    ),
                );
            }
        }
        run.shaders.push(COUNT.to_string());
        run.compute = Some(match no_compute(ctx) {
            Some(why) => why,
            None => compute(ctx, &mut run, &values, &cpu)?,
        });
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// The CPU histogram of values in [0, 1): bin floor(v * bins) in fp32, as the shader has it.
pub fn histogram_cpu(values: &[f32], bins: u32) -> Vec<f32> {
    let mut counts = vec![0f32; bins as usize];
    for &v in values {
        let bin = (v * bins as f32).floor().min((bins - 1) as f32) as usize;
        counts[bin] += 1.0;
    }
    counts
}

fn compute(
    ctx: &Context,
    run: &mut LessonRun,
    values: &[f32],
    cpu: &[f32],
) -> anyhow::Result<String> {
    let program = ComputeProgram::new(ctx, &[shader!("glsl/learn/compute/histogram.comp")])?;
    // region: histogram-compute
    let bv = Buffer::from_slice(ctx, values, BufferUsage::Static)?;
    let bc = Buffer::from_slice(ctx, &vec![0u32; BINS as usize], BufferUsage::Dynamic)?;
    program
        .dispatch("histogram")
        .uniform("u_count", values.len() as u32)
        .uniform("u_bins", BINS as i32)
        .storage(0, &bv)
        .storage(1, &bc)
        .run_over(values.len() as u32)?;
    memory_barrier(ctx, &[Barrier::BufferUpdate]);
    let counts: Vec<u32> = bc.read()?;
    // endregion
    let counts: Vec<f32> = counts.into_iter().map(|c| c as f32).collect();
    run.pass(
        "compute: atomic histogram",
        HISTOGRAM_COMPUTE,
        "one invocation per value adds 1 to its bin with atomicAdd",
        Some(
            PassBuffer::floats(BINS, 1, 1, counts.clone())
                .in_set("bins")
                .with_reference(cpu.to_vec()),
        ),
    );
    run.check_texels(
        "compute: the atomic counts = the CPU's histogram (exact)",
        Grid::new(BINS, 1, 1),
        &counts,
        cpu,
        0.0,
    );
    Ok(format!(
        "ran {HISTOGRAM_COMPUTE}, checked against the same CPU histogram"
    ))
}
