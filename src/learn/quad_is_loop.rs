//! Lesson 1, a quad is a loop: saxpy (`y = a x + y`) as one rectangle drawn over the target,
//! whose fragment shader is the loop's body; then a gather (`out[k] = values[index[k]]`), the
//! indirect read every fragment may do.

use super::{
    chosen_exercise, no_compute, random_values, Exercise, Grid, Lesson, LessonInfo, LessonOptions,
    LessonRun, PaperStep, PassBuffer,
};
use crate::gl::{
    memory_barrier, Barrier, Buffer, BufferUsage, ComputeProgram, Context, Framebuffer, Program,
    Texture, TextureFormat,
};
use crate::shader;

const SAXPY: &str = "glsl/learn/saxpy.frag";
const GATHER: &str = "glsl/learn/gather.frag";
const SAXPY_COMPUTE: &str = "glsl/learn/compute/saxpy.comp";

/// The arrays are `W x H`.
const W: u32 = 16;
const H: u32 = 12;
const A: f32 = 2.5;

pub struct QuadIsLoop;

static INFO: LessonInfo = LessonInfo {
    id: "quad-is-loop",
    number: 1,
    title: "A quad is a loop",
    idea: "Drawing a rectangle that covers the target runs the fragment shader once per \
           pixel: the rectangle is the loop over the output array, the shader its body, the \
           pixel its index. The body reads any texel it likes (gather) but writes only its own \
           element, so the iterations are independent and run in parallel.",
    paper_steps: &[
        PaperStep {
            paper: "Paper 3, section 3",
            step: "the matrix product of a layer as passes over the output texture",
            file: "src/mlp/matmul.rs",
        },
        PaperStep {
            paper: "Paper 2, section 2",
            step: "pass 1: one rectangle over n characters x m vertices, one vertex per texel",
            file: "src/crowd/pass1_skinning.rs",
        },
    ],
    shaders: &[SAXPY, GATHER, SAXPY_COMPUTE],
    exercises: &[Exercise {
        number: 1,
        task: "Write the loop body of saxpy: the new y is a x + y.",
        shader: SAXPY,
        hints: [
            "The rectangle is the loop; the shader is its body, run once per element \
             with x and y already read at that element's index.",
            "The body of `for i: y[i] = a x[i] + y[i]` with the uniform u_a as a: one \
             multiply and one add.",
            "o_y = u_a * x + y;",
        ],
    }],
};

impl Lesson for QuadIsLoop {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        chosen_exercise(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        let n = (W * H) as usize;
        let x = random_values(n, 1, -1.0, 1.0);
        let y = random_values(n, 2, -1.0, 1.0);
        let cpu = saxpy_cpu(A, &x, &y);
        saxpy(ctx, &mut run, &x, &y, &cpu)?;
        gather(ctx, &mut run, &x)?;
        run.compute = Some(match no_compute(ctx) {
            Some(why) => why,
            None => saxpy_compute(ctx, &mut run, &x, &y, &cpu)?,
        });
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// The CPU loop: `a x[i] + y[i]` in fp32.
pub fn saxpy_cpu(a: f32, x: &[f32], y: &[f32]) -> Vec<f32> {
    x.iter().zip(y).map(|(&x, &y)| a * x + y).collect()
}

/// |a x + y| < 3.5 here, where an fp32 step is 2.4e-7; a fused multiply-add rounds once
/// instead of twice, so the GPU may differ from the CPU by about one step. 1e-6 allows four.
const SAXPY_TOLERANCE: f64 = 1e-6;

fn saxpy(
    ctx: &Context,
    run: &mut LessonRun,
    x: &[f32],
    y: &[f32],
    cpu: &[f32],
) -> anyhow::Result<()> {
    // region: saxpy-upload
    let tx = Texture::from_f32(ctx, W, H, TextureFormat::R32F, x)?;
    let ty = Texture::from_f32(ctx, W, H, TextureFormat::R32F, y)?;
    // endregion
    run.pass(
        "upload x and y",
        "",
        &format!(
            "two arrays of {} floats into {W}x{H} R32F textures",
            x.len()
        ),
        Some(PassBuffer::floats(W, H, 1, x.to_vec())),
    );
    // region: saxpy-pass
    let out = Texture::new_2d(ctx, W, H, TextureFormat::R32F)?;
    let fb = Framebuffer::new(ctx, "saxpy", &[&out], None)?;
    let program = Program::rect(ctx, &[shader!("glsl/learn/saxpy.frag")])?;
    fb.pass(&program, "saxpy")?
        .texture("u_x", &tx)
        .texture("u_y", &ty)
        .uniform("u_a", A)
        .draw_full()?;
    let gpu = out.download_f32()?;
    // endregion
    run.pass(
        "saxpy",
        SAXPY,
        &format!(
            "one {W}x{H} rectangle: {} fragments, each computing a x + y (a = {A}) at its \
             own pixel into a third texture",
            x.len()
        ),
        Some(PassBuffer::floats(W, H, 1, gpu.clone()).with_reference(cpu.to_vec())),
    );
    run.check_texels(
        "saxpy = the CPU loop",
        Grid::new(W, H, 1),
        &gpu,
        cpu,
        SAXPY_TOLERANCE,
    );
    Ok(())
}

/// Gather through a random permutation: each element reads the value its index names.
fn gather(ctx: &Context, run: &mut LessonRun, values: &[f32]) -> anyhow::Result<()> {
    use rand::{seq::SliceRandom, SeedableRng};
    let mut index: Vec<u32> = (0..values.len() as u32).collect();
    index.shuffle(&mut rand_chacha::ChaCha8Rng::seed_from_u64(3));
    let index_f: Vec<f32> = index.iter().map(|&k| k as f32).collect();
    let cpu: Vec<f32> = index.iter().map(|&k| values[k as usize]).collect();
    // region: gather-pass
    let tv = Texture::from_f32(ctx, W, H, TextureFormat::R32F, values)?;
    let ti = Texture::from_f32(ctx, W, H, TextureFormat::R32F, &index_f)?;
    let out = Texture::new_2d(ctx, W, H, TextureFormat::R32F)?;
    let fb = Framebuffer::new(ctx, "gather", &[&out], None)?;
    let program = Program::rect(ctx, &[shader!("glsl/learn/gather.frag")])?;
    fb.pass(&program, "gather")?
        .texture("u_values", &tv)
        .texture("u_index", &ti)
        .uniform("u_width", W as i32)
        .draw_full()?;
    let gpu = out.download_f32()?;
    // endregion
    run.pass(
        "gather",
        GATHER,
        "each fragment reads its index from one texture and the value it names from another \
         (a random permutation of x)",
        Some(PassBuffer::floats(W, H, 1, gpu.clone())),
    );
    // A copy of values through exact integer indices: nothing is rounded.
    run.check_texels(
        "gather = values[index] on the CPU (exact)",
        Grid::new(W, H, 1),
        &gpu,
        &cpu,
        0.0,
    );
    Ok(())
}

fn saxpy_compute(
    ctx: &Context,
    run: &mut LessonRun,
    x: &[f32],
    y: &[f32],
    cpu: &[f32],
) -> anyhow::Result<String> {
    // region: saxpy-compute
    let program = ComputeProgram::new(ctx, &[shader!("glsl/learn/compute/saxpy.comp")])?;
    let bx = Buffer::from_slice(ctx, x, BufferUsage::Static)?;
    let by = Buffer::from_slice(ctx, y, BufferUsage::Dynamic)?;
    program
        .dispatch("saxpy")
        .uniform("u_a", A)
        .uniform("u_count", x.len() as u32)
        .storage(0, &bx)
        .storage(1, &by)
        .run_over(x.len() as u32)?;
    memory_barrier(ctx, &[Barrier::BufferUpdate]);
    let gpu: Vec<f32> = by.read()?;
    // endregion
    run.pass(
        "compute: saxpy",
        SAXPY_COMPUTE,
        "one invocation per element updates y in place in a storage buffer",
        Some(PassBuffer::floats(W, H, 1, gpu.clone())),
    );
    run.check_texels(
        "compute: saxpy = the CPU loop",
        Grid::new(W, H, 1),
        &gpu,
        cpu,
        SAXPY_TOLERANCE,
    );
    Ok(format!(
        "ran {SAXPY_COMPUTE}, checked against the same CPU loop"
    ))
}
