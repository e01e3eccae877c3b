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
    chosen_exercise, max_difference, no_compute, Exercise, Grid, Iteration, Lesson, LessonInfo,
    LessonOptions, LessonRun, PaperStep, PassBuffer, Slot,
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
        let mut jacobi = Jacobi::start(ctx, opts)?;
        jacobi.advance(STEPS)?;
        Ok(jacobi.record()?.0)
    }

    fn iteration(
        &self,
        ctx: &Context,
        opts: &LessonOptions,
    ) -> anyhow::Result<Option<Box<dyn Iteration>>> {
        Ok(Some(Box::new(Jacobi::start(ctx, opts)?)))
    }
}

/// Each step adds four values in [0, 1] and scales by 1/4: the fp32 rounding of a step is
/// below 2^-23 (1.2e-7), and a mean does not grow earlier differences, so after k steps the
/// GPU and CPU differ by at most k * 1.2e-7 even if the GPU adds in another order: 1e-5 up
/// to 80 steps (the lesson's run), k * 2^-23 beyond (the viewer's, up to the fixed point).
pub(crate) fn tolerance(steps: u32) -> f64 {
    (steps as f64 * f64::from(f32::EPSILON)).max(1e-5)
}

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

/// The lesson between iterations: the grid `iterations` Jacobi steps from the start, on each
/// path (the ping-pong textures, the one texture read and written in place, the compute
/// counterpart's storage buffers) and on the CPU. `learn ping-pong` advances it [`STEPS`]
/// steps and records the run; the viewer's live loop advances it a step a frame, from where
/// it is.
struct Jacobi {
    ctx: Context,
    opts: LessonOptions,
    program: Program,
    /// Iterate k is in A for even k, in B for odd k.
    fb_a: Framebuffer,
    fb_b: Framebuffer,
    /// One texture read and drawn into by the same steps (undefined, shown for comparison).
    in_place: Framebuffer,
    /// The compute counterpart, or why it cannot run here.
    compute: Result<JacobiCompute, String>,
    start: Vec<f32>,
    /// The CPU's iterate, as many steps from the start as the GPU's.
    cpu: Vec<f32>,
    /// Steps 1 and 2 as read back when they ran: the lesson shows them beside the latest.
    first_steps: Vec<Vec<f32>>,
    iterations: u32,
    /// The CPU's iterate is a fixed point: a step changes none of its values.
    fixed_point: bool,
}

impl Jacobi {
    /// The start grid in texture A (and in the in-place texture and the compute buffers),
    /// the programs compiled: iteration 0.
    fn start(ctx: &Context, opts: &LessonOptions) -> anyhow::Result<Jacobi> {
        chosen_exercise(&INFO, opts)?;
        let start = initial_grid(N);
        let program = Program::rect(ctx, &[shader!("glsl/learn/jacobi.frag")])?;
        // region: ping-pong-setup
        let a = Texture::from_f32(ctx, N, N, TextureFormat::R32F, &start)?;
        let b = Texture::new_2d(ctx, N, N, TextureFormat::R32F)?;
        let fb_a = Framebuffer::new(ctx, "A", &[&a], None)?;
        let fb_b = Framebuffer::new(ctx, "B", &[&b], None)?;
        // endregion
        let one = Texture::from_f32(ctx, N, N, TextureFormat::R32F, &start)?;
        let in_place = Framebuffer::new(ctx, "one texture", &[&one], None)?;
        let compute = match no_compute(ctx) {
            Some(why) => Err(why),
            None => Ok(JacobiCompute::new(ctx, &start)?),
        };
        Ok(Jacobi {
            ctx: ctx.clone(),
            opts: opts.clone(),
            program,
            fb_a,
            fb_b,
            in_place,
            compute,
            cpu: start.clone(),
            start,
            first_steps: Vec::new(),
            iterations: 0,
            fixed_point: false,
        })
    }

    /// The texture that holds iterate `k`.
    fn iterate(&self, k: u32) -> &Texture {
        if k.is_multiple_of(2) {
            self.fb_a.color(0)
        } else {
            self.fb_b.color(0)
        }
    }

    // region: ping-pong-step
    /// Step k + 1: read the texture holding iterate k and draw iterate k + 1 into the other,
    /// A -> B on even steps, B -> A on odd ones; the roles swap after every step.
    fn ping_pong_step(&self, k: u32) -> anyhow::Result<()> {
        let (read, write) = if k.is_multiple_of(2) {
            (&self.fb_a, &self.fb_b)
        } else {
            (&self.fb_b, &self.fb_a)
        };
        write
            .pass(&self.program, "jacobi step")?
            .texture("u_current", read.color(0))
            .uniform("u_size", glam::IVec2::new(N as i32, N as i32))
            .draw_full()?;
        Ok(())
    }
    // endregion

    /// The same step reading and drawing into one texture: a feedback loop.
    fn in_place_step(&self) -> anyhow::Result<()> {
        self.in_place
            .pass(&self.program, "jacobi in place")?
            .texture("u_current", self.in_place.color(0))
            .uniform("u_size", glam::IVec2::new(N as i32, N as i32))
            .draw_full()?;
        Ok(())
    }

    /// The pass that made step `s` (1, 2, ...), in a sentence.
    fn step_what(s: u32) -> String {
        let (from, to) = if s % 2 == 1 { ("A", "B") } else { ("B", "A") };
        format!(
            "read {from}, draw into {to}: every interior texel becomes the mean of its four \
             neighbours in {from}; then {to} is read and {from} written"
        )
    }
}

impl Iteration for Jacobi {
    fn iterations(&self) -> u32 {
        self.iterations
    }

    /// Each path `steps` steps further, one after the other (so a trace reads path by path).
    /// The CPU's iterate goes first: once a step changes none of its values (in fp32 the
    /// relaxation ends on a fixed point), every path stops there, so that no run, and no
    /// replay of the viewer's frames after a reload, takes more steps than that.
    fn advance(&mut self, steps: u32) -> anyhow::Result<()> {
        let mut taken = 0;
        while taken < steps && !self.fixed_point {
            let next = jacobi_cpu(&self.cpu, N, 1);
            self.fixed_point = next == self.cpu;
            if !self.fixed_point {
                self.cpu = next;
                taken += 1;
            }
        }
        let first = self.iterations;
        for k in first..first + taken {
            self.ping_pong_step(k)?;
            // Steps 1 and 2 are shown; the ones after are alike until the latest.
            if k < 2 {
                self.first_steps.push(self.iterate(k + 1).download_f32()?);
            }
        }
        for _ in 0..taken {
            self.in_place_step()?;
        }
        if let Ok(compute) = &self.compute {
            compute.advance(first, taken)?;
        }
        self.iterations += taken;
        Ok(())
    }

    fn stopped(&self) -> Option<String> {
        self.fixed_point.then(|| {
            "a fixed point: one more Jacobi step changes no value of the CPU's iterate (fp32)"
                .to_string()
        })
    }

    fn record(&self) -> anyhow::Result<(LessonRun, Vec<Slot>)> {
        let (ctx, k) = (&self.ctx, self.iterations);
        let grid = |values: Vec<f32>| Some(PassBuffer::floats(N, N, 1, values).in_set("grid"));
        let mut run = LessonRun::new(&INFO, ctx);
        run.pass(
            "start",
            "",
            &format!("a {N}x{N} grid into texture A: zero inside, the top row held at 1"),
            grid(self.start.clone()),
        );
        let mut first_steps = [None, None];
        for (s, values) in (1..).zip(&self.first_steps) {
            run.pass(
                &format!("step {s}"),
                JACOBI,
                &Jacobi::step_what(s),
                grid(values.clone()),
            );
            first_steps[s as usize - 1] = Some(run.buffers.len() - 1);
        }
        if k >= 4 {
            run.pass(
                &format!("steps 3 to {}", k - 1),
                JACOBI,
                "the same pass, the textures swapping roles after each",
                None,
            );
        }
        let gpu = self.iterate(k).download_f32()?;
        if k >= 3 {
            run.pass(
                &format!("step {k}"),
                JACOBI,
                &Jacobi::step_what(k),
                grid(gpu.clone()),
            );
        }
        // The latest iterate: step k's buffer (the start's before any step).
        let latest = run.buffers.len() - 1;
        run.check_texels(
            &format!("after {k} steps the grid = the CPU's Jacobi iterate"),
            Grid::new(N, N, 1),
            &gpu,
            &self.cpu,
            tolerance(k),
        );
        run.check(
            "the boundary kept its values (exact)",
            max_difference(&boundary(&gpu, N), &boundary(&self.start, N)),
            0.0,
        );
        let in_place = self.in_place.color(0).download_f32()?;
        record_in_place(&mut run, &in_place, &gpu, k);
        let mut slots = vec![
            slot("start", Some(0), false),
            slot("step 1", first_steps[0], false),
            slot("step 2", first_steps[1], false),
            slot(&format!("step {k} (the latest)"), Some(latest), true),
            slot("in place (undefined)", Some(run.buffers.len() - 1), true),
        ];
        run.compute = Some(match &self.compute {
            Err(why) => why.clone(),
            Ok(compute) => {
                let why = compute.record(&mut run, &self.cpu, k)?;
                slots.push(slot("compute: jacobi", Some(run.buffers.len() - 1), true));
                why
            }
        });
        run.finish(&INFO, ctx, &self.opts)?;
        Ok((run, slots))
    }
}

fn slot(name: &str, buffer: Option<usize>, changes: bool) -> Slot {
    Slot {
        name: name.to_string(),
        buffer,
        changes,
    }
}

/// What reading and writing one texture gave here: noted, not checked (undefined in GL).
fn record_in_place(run: &mut LessonRun, values: &[f32], ping_pong: &[f32], steps: u32) {
    run.pass(
        "in place (undefined)",
        JACOBI,
        "the same steps reading and drawing into one texture: a feedback loop whose result GL \
         leaves undefined, shown for comparison only",
        Some(PassBuffer::floats(N, N, 1, values.to_vec()).in_set("grid")),
    );
    run.note(
        "one texture read and written",
        format!(
            "undefined in OpenGL (a rendering feedback loop); on this renderer {steps} steps in \
             place differ from ping-pong by up to {:.3e}: another renderer, or another grid \
             size, may give anything",
            max_difference(values, ping_pong)
        ),
    );
}

/// The compute counterpart: the same steps between two storage buffers.
struct JacobiCompute {
    ctx: Context,
    program: ComputeProgram,
    /// Iterate k is in A for even k, in B for odd k.
    a: Buffer,
    b: Buffer,
}

impl JacobiCompute {
    fn new(ctx: &Context, start: &[f32]) -> anyhow::Result<JacobiCompute> {
        Ok(JacobiCompute {
            ctx: ctx.clone(),
            program: ComputeProgram::new(ctx, &[shader!("glsl/learn/compute/jacobi.comp")])?,
            a: Buffer::from_slice(ctx, start, BufferUsage::Dynamic)?,
            b: Buffer::from_slice(ctx, start, BufferUsage::Dynamic)?,
        })
    }

    /// Steps `first + 1` to `first + steps`.
    fn advance(&self, first: u32, steps: u32) -> anyhow::Result<()> {
        // region: jacobi-compute
        let groups = N.div_ceil(8);
        for k in first..first + steps {
            let (read, write) = if k.is_multiple_of(2) {
                (&self.a, &self.b)
            } else {
                (&self.b, &self.a)
            };
            self.program
                .dispatch("jacobi step")
                .uniform("u_size", glam::IVec2::new(N as i32, N as i32))
                .storage(0, read)
                .storage(1, write)
                .run([groups, groups, 1])?;
            memory_barrier(&self.ctx, &[Barrier::Storage]);
        }
        memory_barrier(&self.ctx, &[Barrier::BufferUpdate]);
        // endregion
        Ok(())
    }

    /// Its iterate after `k` steps, recorded and checked against the CPU's.
    fn record(&self, run: &mut LessonRun, cpu: &[f32], k: u32) -> anyhow::Result<String> {
        let last = if k % 2 == 1 { &self.b } else { &self.a };
        let gpu: Vec<f32> = last.read()?;
        run.pass(
            "compute: jacobi",
            JACOBI_COMPUTE,
            "the same steps between two storage buffers, a barrier between dispatches",
            Some(PassBuffer::floats(N, N, 1, gpu.clone()).in_set("grid")),
        );
        run.check_texels(
            &format!("compute: after {k} steps the grid = the CPU's iterate"),
            Grid::new(N, N, 1),
            &gpu,
            cpu,
            tolerance(k),
        );
        Ok(format!(
            "ran {JACOBI_COMPUTE}, checked against the same CPU iterate"
        ))
    }
}
