//! Lesson 1, a quad is a loop: saxpy (`y = a x + y`) as one rectangle drawn over the target,
//! whose fragment shader is the loop's body; then a gather (`out[k] = values[index[k]]`), the
//! indirect read every fragment may do.

use super::kit::{self, Steps};
use super::{
    chosen_exercise, no_compute, random_values, Exercise, Grid, Lesson, LessonInfo, LessonOptions,
    LessonRun, PaperStep, PassBuffer,
};
use crate::gl::{
    memory_barrier, Barrier, Buffer, BufferUsage, ComputeProgram, Context, Framebuffer, Program,
    Texture, TextureFormat,
};
use crate::shader;
use crate::timing::{Load, Runs, Spread};
use serde::Serialize;

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
        let (x, y) = (ramp(W, H), checkerboard(W, H));
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

/// x: a ramp, element k (rows from the bottom) holding k / 64 - 1.5, so that a read one texel
/// off along a row is off by a / 64 everywhere and one row off by a / 4: a difference picture
/// of one flat colour, not noise.
pub fn ramp(width: u32, height: u32) -> Vec<f32> {
    (0..width * height).map(|k| k as f32 / 64.0 - 1.5).collect()
}

/// y: a checkerboard of +0.5 and -0.5, so that a read one texel off in either direction flips
/// the sign at every texel: a difference picture of stripes or a checkerboard.
pub fn checkerboard(width: u32, height: u32) -> Vec<f32> {
    (0..width * height)
        .map(|k| {
            if (k % width + k / width).is_multiple_of(2) {
                0.5
            } else {
                -0.5
            }
        })
        .collect()
}

/// The CPU loop: `a x[i] + y[i]` in fp32.
pub fn saxpy_cpu(a: f32, x: &[f32], y: &[f32]) -> Vec<f32> {
    x.iter().zip(y).map(|(&x, &y)| a * x + y).collect()
}

/// The lesson's values are multiples of 1/128 below 8 (a = 2.5, x = k/64 - 1.5, y = +-0.5), so
/// a x + y is exact in fp32 with or without a fused multiply-add: the lesson checks exactly.
/// The bench's random values in [-1, 1) give |a x + y| < 3.5, where an fp32 step is 2.4e-7; a
/// fused multiply-add rounds once instead of twice, so the GPU may differ from the CPU by about
/// one step there. 1e-6 allows four.
pub(crate) const SAXPY_TOLERANCE: f64 = 1e-6;

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
            "two arrays of {} floats into {W}x{H} R32F textures: x a ramp (element k holds k/64 \
             - 1.5), y a checkerboard of +-0.5, so a read one texel off shows as a pattern",
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
    run.check_texels("saxpy = the CPU loop", Grid::new(W, H, 1), &gpu, cpu, 0.0);
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
        0.0,
    );
    Ok(format!(
        "ran {SAXPY_COMPUTE}, checked against the same CPU loop"
    ))
}

/// The sizes `learn quad-is-loop --bench` sweeps by default (Göddeke's benchmark mode).
pub const BENCH_SIZES: [u32; 6] = [1 << 12, 1 << 14, 1 << 16, 1 << 18, 1 << 20, 1 << 22];
/// The largest array it takes (4096 x 4096 texels).
pub const BENCH_MAX: u32 = 1 << 24;

/// One size of the saxpy bench.
#[derive(Clone, Debug, Serialize)]
pub struct SaxpyTimed {
    /// Elements computed: the `width x height` texture the size fills.
    pub n: u32,
    pub width: u32,
    pub height: u32,
    /// Upload x and y, the pass, read y back: each step timed in the same runs by the wall
    /// clock, glFinish after each; the whole of a run is the sum of its steps.
    pub steps: Steps,
    /// The CPU loop (one core, wall clock).
    pub cpu_ms: Spread,
    /// Largest |GPU - CPU| (checked within the lesson's tolerance before timing).
    pub error: f64,
}

impl SaxpyTimed {
    /// The pass alone: the second step of the same runs.
    pub fn pass_ms(&self) -> Spread {
        self.steps.steps[PASS_STEP]
    }

    /// The pass with its transfers: the whole of the same runs.
    pub fn with_transfers_ms(&self) -> Spread {
        self.steps.whole
    }
}

/// The steps a bench run times, in order; the pass is [`PASS_STEP`].
pub const SAXPY_STEPS: [&str; 3] = ["upload x and y", "the pass", "read y back"];
const PASS_STEP: usize = 1;

/// Lesson 1's bench: saxpy over sizes against the CPU.
#[derive(Clone, Debug, Serialize)]
pub struct SaxpyBench {
    pub renderer: String,
    pub runs: String,
    pub load: Option<Load>,
    pub rows: Vec<SaxpyTimed>,
}

/// Time saxpy at each of `sizes` (elements; each rounded up to a texture as square as it goes):
/// its upload, pass and readback in the same runs, and the CPU loop, each size checked first.
pub fn bench(ctx: &Context, sizes: &[u32], runs: Runs) -> anyhow::Result<SaxpyBench> {
    for &n in sizes {
        anyhow::ensure!(
            (1..=BENCH_MAX).contains(&n),
            "--size {n}: lesson 1's bench takes 1 to {BENCH_MAX} elements"
        );
    }
    let before = Load::now();
    let program = Program::rect(ctx, &[shader!("glsl/learn/saxpy.frag")])?;
    let mut rows = Vec::new();
    for &size in sizes {
        let (w, h) = super::ladder::shape(size);
        let n = (w * h) as usize;
        let x = random_values(n, 1, -1.0, 1.0);
        let y = random_values(n, 2, -1.0, 1.0);
        let cpu = saxpy_cpu(A, &x, &y);
        let tx = Texture::from_f32(ctx, w, h, TextureFormat::R32F, &x)?;
        let ty = Texture::from_f32(ctx, w, h, TextureFormat::R32F, &y)?;
        let out = Texture::new_2d(ctx, w, h, TextureFormat::R32F)?;
        let fb = Framebuffer::new(ctx, "saxpy", &[&out], None)?;
        let pass = || -> anyhow::Result<()> {
            fb.pass(&program, "saxpy")?
                .texture("u_x", &tx)
                .texture("u_y", &ty)
                .uniform("u_a", A)
                .draw_full()?;
            Ok(())
        };
        pass()?;
        let error = super::max_difference(&out.download_f32()?, &cpu);
        anyhow::ensure!(
            error <= SAXPY_TOLERANCE,
            "saxpy of {n} elements differs from the CPU loop by {error:e} (tolerance \
             {SAXPY_TOLERANCE:e}): not timed"
        );
        let steps = kit::time_steps(ctx, runs, SAXPY_STEPS.len(), |step| {
            match step {
                0 => {
                    tx.upload_f32(&x)?;
                    ty.upload_f32(&y)?;
                }
                PASS_STEP => pass()?,
                _ => {
                    out.download_f32()?;
                }
            }
            Ok(())
        })?;
        let cpu_ms = crate::timing::wall_ms(runs, || saxpy_cpu(A, &x, &y));
        rows.push(SaxpyTimed {
            n: n as u32,
            width: w,
            height: h,
            steps,
            cpu_ms,
            error,
        });
    }
    Ok(SaxpyBench {
        renderer: ctx.info().renderer_line(),
        runs: runs.in_words(),
        load: Load::worst(before, Load::now()),
        rows,
    })
}

impl SaxpyBench {
    /// Plain text: a row per size.
    pub fn table(&self) -> String {
        let mut out = format!(
            "saxpy bench (lesson 1, y = a x + y) on {}\n{}\nruns: {}, after one warm-up run\n\
             clock: the wall clock, glFinish after each step; the upload, the pass and the \
             readback are steps of the same runs, and each run's whole is the sum of its \
             steps, so the pass is never timed longer than the pass with its transfers\nGB/s: \
             12 bytes per element (read x and y, write y) / the median time; each size \
             checked against the CPU first\n",
            self.renderer,
            self.load.map_or("load: unknown".into(), |l| format!(
                "load: {}",
                l.in_words()
            )),
            self.runs
        );
        out.push_str(&format!(
            "{:>9} {:>10} {:>21} {:>8} {:>21} {:>21} {:>21} {:>8} {:>9}\n",
            "n",
            "texture",
            "pass ms",
            "GB/s",
            "with transfers ms",
            "of which upload ms",
            "CPU ms",
            "CPU GB/s",
            "CPU/pass",
        ));
        let cell = |s: &Spread| format!("{:.3} ({:.3}-{:.3})", s.median, s.min, s.max);
        let gb_s = |n: u32, ms: f64| 12.0 * n as f64 / (ms.max(1e-9) * 1e-3) / 1e9;
        for r in &self.rows {
            let pass = r.pass_ms();
            out.push_str(&format!(
                "{:>9} {:>10} {:>21} {:>8.3} {:>21} {:>21} {:>21} {:>8.3} {:>9.2}\n",
                r.n,
                format!("{}x{}", r.width, r.height),
                cell(&pass),
                gb_s(r.n, pass.median),
                cell(&r.with_transfers_ms()),
                cell(&r.steps.steps[0]),
                cell(&r.cpu_ms),
                gb_s(r.n, r.cpu_ms.median),
                r.cpu_ms.median / pass.median.max(1e-9),
            ));
        }
        out.push_str(
            "times: median (range) in ms. The pass alone against the CPU loop is the kernel's \
             speed; with its transfers it is what a single saxpy costs the program, and why \
             Göddeke keeps data on the GPU across many passes.\n",
        );
        out
    }
}
