//! Lesson 10, the bridge to CUDA: the reduction of the fragment pipeline (ping-pong passes,
//! 2x2 blocks per pass: lesson 3, and the GL layer's [`crate::gl::reduce`]) written as a
//! compute shader with work-group shared memory and barriers, sum and maximum at once. Both
//! are checked against the CPU, side by side, with the passes each needs; the compute
//! reduction's first pass also work group by work group, so that a wrong step of the tree is
//! named by the groups it spoils, and its partials are a picture under `--png`.
//!
//! On a context without OpenGL 4.3 (softpipe is 3.3) the compute shader cannot run: the
//! lesson runs and checks the fragment reduction it starts from, sets `compute` to the
//! reason, and has no compute check at all. `passed` then says that every check that ran
//! passed, and the checks listed are the fragment ones: nothing compute is counted as
//! checked. Its exercise (a compute shader) is refused there with that reason.

use super::kit;
use super::ladder;
use super::{Exercise, Grid, Lesson, LessonInfo, LessonOptions, LessonRun, PaperStep, PassBuffer};
use crate::gl::reduce::{passes_for, ReduceOp, Reducer};
use crate::gl::{Barrier, Buffer, BufferUsage, ComputeProgram, Context, Texture, TextureFormat};
use crate::shader;

/// The array: 100 x 100 values (not a power of two: the edges are part of the lesson).
const WIDTH: u32 = 100;
const HEIGHT: u32 = 100;
/// Values a work group reduces per pass (as in `reduce.comp`).
const PER_GROUP: u32 = 256;
/// fp32 sums of values in [0, 1): the longest chain of additions is under 100 (a block of a
/// fragment pass, a tree of 8 levels per compute pass), each off by at most 2^-24 of the
/// running sum: relative error under 100 * 6e-8 = 6e-6, so 1e-5. The maximum is exact.
const SUM_TOLERANCE: f64 = 1e-5;
/// A work group's partial sums 256 values in [0, 1), so it is below 256, where an fp32 step
/// is 2^-24 x 256 = 1.5e-5: the load's add and the tree's seven levels round eight times on
/// the way (1.2e-4 at most), the CPU's f64 sum once when rounded to fp32. 2e-4 allows both;
/// a partner missed or taken twice moves a partial by a whole value, about 0.5. The partial
/// maxima are exact and are held to the same bound here (the lesson's final maximum: exact).
const PARTIAL_TOLERANCE: f64 = 2e-4;

static INFO: LessonInfo = LessonInfo {
    id: "compute-reduction",
    number: 10,
    title: "The same reduction as a compute shader with shared memory (the bridge to CUDA)",
    idea: "A fragment pass can only write its own pixel, so a reduction takes a pass per \
           level, 2x2 (or a few more) values per output, with a texture between passes. A \
           compute shader's work group shares fast on-chip memory and can wait at a barrier: \
           256 values are folded to one inside the group, in a tree of halving strides, and \
           one pass shrinks the data 256-fold. This is how CUDA reductions are written; the \
           tree and the passes are the same idea as the ping-pong. Then the ladder after \
           Harris: the same sum by four fragment rungs and his seven kernels, each making one \
           change to the one before (wider fan-ins, then divergence, bank conflicts, idle \
           invocations, loop overhead and too little work per invocation removed one at a \
           time), every one checked \
           here and timed by `learn compute-reduction --bench`.",
    paper_steps: &[
        PaperStep {
            paper: "Paper 4, section 3.3",
            step: "the integrals as sums by buffer reduction (the fragment formulation)",
            file: "src/mass/reduce.rs",
        },
        PaperStep {
            paper: "Paper 4, then and now",
            step: "the same sums in work-group shared memory",
            file: "src/gl/reduce_shared.rs",
        },
    ],
    shaders: &[
        "glsl/gl/reduce.frag",
        "glsl/learn/compute-reduction/reduce.comp",
        "glsl/learn/ladder/f1_2x2.frag",
        "glsl/learn/ladder/f2_fan.frag",
        "glsl/learn/ladder/c1_interleaved_divergent.comp",
        "glsl/learn/ladder/c2_interleaved_strided.comp",
        "glsl/learn/ladder/c3_sequential.comp",
        "glsl/learn/ladder/c4_first_add.comp",
        "glsl/learn/ladder/c5_unroll_last_warp.comp",
        "glsl/learn/ladder/c6_unrolled.comp",
        "glsl/learn/ladder/c7_cascade.comp",
    ],
    exercises: &[Exercise {
        number: 1,
        task: "Write the step of the tree: fold the partner `stride` places up onto this \
               invocation's value (needs OpenGL 4.3).",
        shader: "glsl/learn/compute-reduction/reduce.comp",
        hints: [
            "In a tree reduction in shared memory, each step folds the upper half of \
             the active invocations onto the lower half, with a barrier between \
             steps.",
            "At step `stride`, invocation `local` < stride keeps combine(its value, \
             the value stride places up): s[local] = combine(s[local], s[local + \
             stride]).",
            "s_partial[local] = combine(s_partial[local], s_partial[local + stride]);",
        ],
    }],
};

pub struct ComputeReduction;

impl Lesson for ComputeReduction {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        kit::exercise_asked(&INFO, opts)?;
        if opts.exercise.is_some() {
            ctx.require_compute("exercise 1 of compute-reduction (a compute shader)")?;
        }
        let mut run = LessonRun::new(&INFO, ctx);
        let values = kit::values((WIDTH * HEIGHT) as usize, 10);
        let cpu_sum: f64 = values.iter().map(|&v| v as f64).sum();
        let cpu_max = values.iter().copied().fold(f32::MIN, f32::max);

        // The fragment reduction it starts from.
        let texture = Texture::from_f32(ctx, WIDTH, HEIGHT, TextureFormat::R32F, &values)?;
        let reducer = Reducer::new(ctx, WIDTH, HEIGHT)?;
        let sum = reducer.reduce(&texture, ReduceOp::Sum)?[0];
        let max = reducer.reduce(&texture, ReduceOp::Max)?[0];
        let picture = Some(kit::buffer(&texture)?);
        run.pass(
            "fragment ping-pong",
            "glsl/gl/reduce.frag",
            &format!(
                "{} passes of 2x2 blocks, a texture between passes",
                passes_for(WIDTH, HEIGHT)
            ),
            picture,
        );
        run.check(
            "fragment reduction: sum, relative to the CPU's (fp64) sum (1e-5)",
            relative(sum as f64, cpu_sum),
            SUM_TOLERANCE,
        );
        run.check(
            "fragment reduction: maximum (exact)",
            (max as f64 - cpu_max as f64).abs(),
            0.0,
        );

        run.compute = Some(match kit::compute_missing(ctx, "the compute reduction") {
            Some(why) => why,
            None => {
                let reduced = reduce_shared(ctx, &values)?;
                let (sum, max, passes) = (reduced.sum, reduced.max, reduced.passes);
                let groups = reduced.partials.len() as u32;
                let cpu_partials = partials_cpu(&values);
                let gpu_partials: Vec<f32> = reduced.partials.iter().flatten().copied().collect();
                run.pass(
                    "compute pass 1: a partial per work group",
                    "glsl/learn/compute-reduction/reduce.comp",
                    &format!(
                        "{groups} work groups, each folding its {PER_GROUP} values to one (sum, \
                         max) in shared memory: the partials the next pass reduces"
                    ),
                    Some(
                        PassBuffer::floats(groups, 1, 2, gpu_partials.clone())
                            .named(&["sum", "max"])
                            .with_reference(cpu_partials.clone()),
                    ),
                );
                run.check_texels(
                    "compute pass 1: each work group's partial (channel 0 its sum, 1 its \
                     maximum) = the CPU's over the group's 256 values (2e-4)",
                    Grid::new(groups, 1, 2).of("work group"),
                    &gpu_partials,
                    &cpu_partials,
                    PARTIAL_TOLERANCE,
                );
                run.pass(
                    "compute, shared memory",
                    "glsl/learn/compute-reduction/reduce.comp",
                    &format!("{passes} passes of {PER_GROUP} values per work group"),
                    None,
                );
                run.check(
                    "compute: sum, relative to the CPU's (1e-5)",
                    relative(sum as f64, cpu_sum),
                    SUM_TOLERANCE,
                );
                run.check(
                    "compute: maximum (exact)",
                    (max as f64 - cpu_max as f64).abs(),
                    0.0,
                );
                run.notes.push((
                    "passes: fragment 2x2 / compute shared memory".into(),
                    format!("{} / {passes}", passes_for(WIDTH, HEIGHT)),
                ));
                "ran: the tree in shared memory, 256 values per work group and pass".into()
            }
        });
        ladder_checks(ctx, &mut run)?;
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// The ladder's size in the lesson: not a power of two, and more than one cascading group.
const LADDER_N: u32 = 20_011;

/// The ladder after Harris ([`super::ladder`]): every rung this context runs, one pass each,
/// its sum checked against the CPU's; the compute rungs' absence noted where they cannot run.
fn ladder_checks(ctx: &Context, run: &mut LessonRun) -> anyhow::Result<()> {
    for c in ladder::check_all(ctx, LADDER_N)? {
        let rung = &ladder::RUNGS[c.rung as usize - 1];
        run.pass(
            &format!("ladder rung {}: {}", c.rung, c.name),
            c.shader,
            &format!(
                "{} values to one in {} passes. {}",
                c.n, c.passes, rung.change
            ),
            None,
        );
        run.check(
            &format!(
                "ladder rung {} ({}): sum = the CPU's f64 sum ({})",
                c.rung,
                c.name,
                ladder::TOLERANCE_IN_WORDS
            ),
            c.error(),
            ladder::TOLERANCE,
        );
    }
    if let Some(why) = ladder::compute_skipped(ctx) {
        run.note("ladder: compute rungs", why);
    }
    Ok(())
}

fn relative(gpu: f64, cpu: f64) -> f64 {
    (gpu - cpu).abs() / cpu.abs().max(f64::MIN_POSITIVE)
}

/// Each work group's partial of the first pass as the CPU computes it: (sum, max) of its
/// [`PER_GROUP`] values, the sum in f64 rounded once.
fn partials_cpu(values: &[f32]) -> Vec<f32> {
    values
        .chunks(PER_GROUP as usize)
        .flat_map(|group| {
            let sum: f64 = group.iter().map(|&v| v as f64).sum();
            let max = group.iter().copied().fold(f32::MIN, f32::max);
            [sum as f32, max]
        })
        .collect()
}

/// What the passes on the GPU gave: the one (sum, max) left, the passes, and the first pass's
/// partial per work group.
struct Reduced {
    sum: f32,
    max: f32,
    passes: u32,
    partials: Vec<[f32; 2]>,
}

/// Reduce on the GPU in passes until one (sum, max) is left, keeping the first pass's partials.
fn reduce_shared(ctx: &Context, values: &[f32]) -> anyhow::Result<Reduced> {
    let program = ComputeProgram::new(ctx, &[shader!("glsl/learn/compute-reduction/reduce.comp")])?;
    let pairs: Vec<[f32; 2]> = values.iter().map(|&v| [v, v]).collect();
    let mut input = Buffer::from_slice(ctx, &pairs, BufferUsage::Static)?;
    let mut count = values.len() as u32;
    let mut passes = 0;
    let mut partials = Vec::new();
    // region: reduce-passes
    while count > 1 || passes == 0 {
        let groups = count.div_ceil(PER_GROUP);
        let output = Buffer::new(ctx, groups as usize * 8, BufferUsage::GpuCopy)?;
        program
            .dispatch("shared-memory reduction")
            .storage(0, &input)
            .storage(1, &output)
            .uniform("u_count", count)
            .run([groups, 1, 1])?;
        crate::gl::memory_barrier(ctx, &[Barrier::Storage, Barrier::BufferUpdate]);
        input = output;
        count = groups;
        passes += 1;
        // endregion
        if passes == 1 {
            partials = input.read()?;
        }
    }
    let result: Vec<[f32; 2]> = input.read()?;
    Ok(Reduced {
        sum: result[0][0],
        max: result[0][1],
        passes,
        partials,
    })
}
