//! Lesson 2, ping-pong: an iterated stencil, Jacobi's method for Laplace's equation on a grid,
//! with two textures that swap roles after each step: the one read holds iterate k, the one
//! drawn into becomes iterate k + 1.
//!
//! Why not one texture: a pass that samples the texture it draws into is a "rendering feedback
//! loop", whose results OpenGL leaves undefined (fragments run in any order, and a neighbour
//! may already hold iterate k + 1, or a half-written cache line). The lesson runs it once on
//! the side and notes what this renderer gave, without checking it: there is nothing right to
//! check it against.

use super::{
    chosen_exercise, max_difference, no_compute, Exercise, Grid, Lesson, LessonInfo, LessonOptions,
    LessonRun, PaperStep, PassBuffer,
};
use crate::gl::{
    memory_barrier, Barrier, Buffer, BufferUsage, ComputeProgram, Context, Framebuffer, Program,
    Texture, TextureFormat,
};
use crate::shader;

const JACOBI: &str = "glsl/learn/jacobi.frag";
const JACOBI_COMPUTE: &str = "glsl/learn/compute/jacobi.comp";

/// The grid is `N x N`, its top row held at 1 and the other edges at 0.
pub(crate) const N: u32 = 16;
/// Steps of the lesson's own run.
pub const STEPS: u32 = 24;

pub struct PingPong;

static INFO: LessonInfo = LessonInfo {
    id: "ping-pong",
    number: 2,
    title: "Ping-pong",
    idea: "An iterative method reads the whole previous iterate to write the next one. A pass \
           may not read the texture it writes, so two textures take turns: read A, write B, \
           then read B, write A. Each Jacobi step replaces every interior value of a grid by \
           the mean of its four neighbours; the boundary stays fixed, and the grid relaxes \
           towards the solution of Laplace's equation.",
    paper_steps: &[
        PaperStep {
            paper: "Paper 3, section 3",
            step: "layer chaining: each layer's output target is the next layer's input",
            file: "src/mlp/chain.rs",
        },
        PaperStep {
            paper: "Lecture 3, random numbers in a texture",
            step: "generator states advanced by one pass per step between two textures",
            file: "src/lecture3/random_texture.rs",
        },
    ],
    shaders: &[JACOBI, JACOBI_COMPUTE],
    exercises: &[Exercise {
        number: 1,
        task: "Write the Jacobi update: an interior value becomes the mean of its four \
               neighbours in the iterate read.",
        shader: JACOBI,
        hints: [
            "A Jacobi step reads only the previous iterate (the texture bound as \
             u_current) and writes the next one: each interior value becomes the mean \
             of its four neighbours.",
            "next(p) = 0.25 * (((left + right) + down) + up), with left = current(p - \
             (1, 0)), right = current(p + (1, 0)), down = current(p - (0, 1)), up = \
             current(p + (0, 1)), added in that order as the CPU does.",
            "float left = texelFetch(u_current, p - ivec2(1, 0), 0).r; (and right, \
             down, up the same way) then o_value = 0.25 * (((left + right) + down) + \
             up);",
        ],
    }],
};

impl Lesson for PingPong {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        self.run_iterations(ctx, opts, STEPS)
    }

    fn iterates(&self) -> bool {
        true
    }

    fn run_iterations(
        &self,
        ctx: &Context,
        opts: &LessonOptions,
        steps: u32,
    ) -> anyhow::Result<LessonRun> {
        chosen_exercise(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        let start = initial_grid(N);
        let cpu = jacobi_cpu(&start, N, steps);
        let gpu = jacobi_gpu(ctx, &mut run, &start, steps)?;
        run.check_texels(
            &format!("after {steps} steps the grid = the CPU's Jacobi iterate"),
            Grid::new(N, N, 1),
            &gpu,
            &cpu,
            TOLERANCE,
        );
        run.check(
            "the boundary kept its values (exact)",
            max_difference(&boundary(&gpu, N), &boundary(&start, N)),
            0.0,
        );
        in_place(ctx, &mut run, &start, &gpu, steps)?;
        run.compute = Some(match no_compute(ctx) {
            Some(why) => why,
            None => jacobi_compute(ctx, &mut run, &start, &cpu, steps)?,
        });
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// Each step adds four values in [0, 1] and scales by 1/4: the fp32 rounding of a step is
/// below 2^-23 (1.2e-7), and a mean does not grow earlier differences, so after k steps the
/// GPU and CPU differ by at most k * 1.2e-7 even if the GPU adds in another order; 1e-5
/// covers 80 steps.
pub(crate) const TOLERANCE: f64 = 1e-5;

/// The start: zero inside, the top row at 1 (a hot edge), the other edges at 0.
pub fn initial_grid(n: u32) -> Vec<f32> {
    let n = n as usize;
    let mut grid = vec![0f32; n * n];
    grid[(n - 1) * n..].fill(1.0);
    grid
}

/// The values on the grid's edge, row by row.
fn boundary(grid: &[f32], n: u32) -> Vec<f32> {
    let n = n as usize;
    (0..n * n)
        .filter(|k| {
            let (x, y) = (k % n, k / n);
            x == 0 || y == 0 || x == n - 1 || y == n - 1
        })
        .map(|k| grid[k])
        .collect()
}

/// `steps` Jacobi steps on the CPU, in the shader's order of additions.
pub fn jacobi_cpu(start: &[f32], n: u32, steps: u32) -> Vec<f32> {
    let n = n as usize;
    let mut current = start.to_vec();
    let mut next = current.clone();
    for _ in 0..steps {
        for y in 1..n - 1 {
            for x in 1..n - 1 {
                let at = |x: usize, y: usize| current[y * n + x];
                next[y * n + x] =
                    0.25 * (((at(x - 1, y) + at(x + 1, y)) + at(x, y - 1)) + at(x, y + 1));
            }
        }
        std::mem::swap(&mut current, &mut next);
    }
    current
}

/// The ping-pong: textures A and B, `steps` passes, the roles swapped after each.
fn jacobi_gpu(
    ctx: &Context,
    run: &mut LessonRun,
    start: &[f32],
    steps: u32,
) -> anyhow::Result<Vec<f32>> {
    let program = Program::rect(ctx, &[shader!("glsl/learn/jacobi.frag")])?;
    // region: ping-pong-setup
    let a = Texture::from_f32(ctx, N, N, TextureFormat::R32F, start)?;
    let b = Texture::new_2d(ctx, N, N, TextureFormat::R32F)?;
    let fb_a = Framebuffer::new(ctx, "A", &[&a], None)?;
    let fb_b = Framebuffer::new(ctx, "B", &[&b], None)?;
    // endregion
    run.pass(
        "start",
        "",
        &format!("a {N}x{N} grid into texture A: zero inside, the top row held at 1"),
        Some(PassBuffer::floats(N, N, 1, start.to_vec()).in_set("grid")),
    );
    // region: ping-pong-step
    // (read, write) for step k: A -> B on even steps, B -> A on odd ones.
    let roles = [(&a, &fb_b, "A", "B"), (&b, &fb_a, "B", "A")];
    for k in 0..steps {
        let (read, write, from, to) = roles[(k % 2) as usize];
        write
            .pass(&program, "jacobi step")?
            .texture("u_current", read)
            .uniform("u_size", glam::IVec2::new(N as i32, N as i32))
            .draw_full()?;
        // endregion
        // Steps 1, 2 and the last are shown; the ones between are alike.
        let shown = k < 2 || k + 1 == steps;
        if shown {
            let values = write.color(0).download_f32()?;
            run.pass(
                &format!("step {}", k + 1),
                JACOBI,
                &format!(
                    "read {from}, draw into {to}: every interior texel becomes the mean of \
                     its four neighbours in {from}; then {to} is read and {from} written"
                ),
                Some(PassBuffer::floats(N, N, 1, values).in_set("grid")),
            );
        } else if k == 2 {
            run.pass(
                &format!("steps 3 to {}", steps - 1),
                JACOBI,
                "the same pass, the textures swapping roles after each",
                None,
            );
        }
    }
    let last = if steps % 2 == 1 { &b } else { &a };
    Ok(last.download_f32()?)
}

/// What reading and writing one texture gave here: noted, not checked (undefined in GL).
fn in_place(
    ctx: &Context,
    run: &mut LessonRun,
    start: &[f32],
    ping_pong: &[f32],
    steps: u32,
) -> anyhow::Result<()> {
    let program = Program::rect(ctx, &[shader!("glsl/learn/jacobi.frag")])?;
    let one = Texture::from_f32(ctx, N, N, TextureFormat::R32F, start)?;
    let fb = Framebuffer::new(ctx, "one texture", &[&one], None)?;
    for _ in 0..steps {
        fb.pass(&program, "jacobi in place")?
            .texture("u_current", &one)
            .uniform("u_size", glam::IVec2::new(N as i32, N as i32))
            .draw_full()?;
    }
    let values = one.download_f32()?;
    run.pass(
        "in place (undefined)",
        JACOBI,
        "the same steps reading and drawing into one texture: a feedback loop whose result GL \
         leaves undefined, shown for comparison only",
        Some(PassBuffer::floats(N, N, 1, values.clone()).in_set("grid")),
    );
    run.note(
        "one texture read and written",
        format!(
            "undefined in OpenGL (a rendering feedback loop); on this renderer {steps} steps in \
             place differ from ping-pong by up to {:.3e}: another renderer, or another grid \
             size, may give anything",
            max_difference(&values, ping_pong)
        ),
    );
    Ok(())
}

fn jacobi_compute(
    ctx: &Context,
    run: &mut LessonRun,
    start: &[f32],
    cpu: &[f32],
    steps: u32,
) -> anyhow::Result<String> {
    let program = ComputeProgram::new(ctx, &[shader!("glsl/learn/compute/jacobi.comp")])?;
    // region: jacobi-compute
    let a = Buffer::from_slice(ctx, start, BufferUsage::Dynamic)?;
    let b = Buffer::from_slice(ctx, start, BufferUsage::Dynamic)?;
    let groups = N.div_ceil(8);
    for k in 0..steps {
        let (read, write) = if k % 2 == 0 { (&a, &b) } else { (&b, &a) };
        program
            .dispatch("jacobi step")
            .uniform("u_size", glam::IVec2::new(N as i32, N as i32))
            .storage(0, read)
            .storage(1, write)
            .run([groups, groups, 1])?;
        memory_barrier(ctx, &[Barrier::Storage]);
    }
    memory_barrier(ctx, &[Barrier::BufferUpdate]);
    // endregion
    let last = if steps % 2 == 1 { &b } else { &a };
    let gpu: Vec<f32> = last.read()?;
    run.pass(
        "compute: jacobi",
        JACOBI_COMPUTE,
        "the same steps between two storage buffers, a barrier between dispatches",
        Some(PassBuffer::floats(N, N, 1, gpu.clone()).in_set("grid")),
    );
    run.check_texels(
        &format!("compute: after {steps} steps the grid = the CPU's iterate"),
        Grid::new(N, N, 1),
        &gpu,
        cpu,
        TOLERANCE,
    );
    Ok(format!(
        "ran {JACOBI_COMPUTE}, checked against the same CPU iterate"
    ))
}
