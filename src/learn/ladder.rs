//! The reduction ladder after Harris ("Optimizing Parallel Reduction in CUDA", NVIDIA 2007):
//! one problem, the sum of n values, solved by a row of kernels that each make one change to
//! the one before, every one checked against the CPU and, with `learn <id> --bench`, timed.
//!
//! The ladder starts where the fragment pipeline starts (lesson 3): the 2x2 pass, then wider
//! fan-ins per pass. Then the compute rungs, Harris's steps in GLSL: interleaved addressing
//! with a divergent branch, with a strided index, sequential addressing, the first add during
//! the load, the tree unrolled (keeping its barriers: GLSL has no lock-step warp), several
//! values per invocation. Compute rungs need OpenGL 4.3; on an older context (softpipe is 3.3)
//! they are skipped with the reason, and the fragment rungs still run.
//!
//! The data are small integers (0 to 3) held as floats, as Harris sums integers: every partial
//! sum of at most 2^22 of them is an integer below 2^24, which fp32 holds exactly, so each
//! rung's sum must equal the CPU's f64 sum exactly, whatever order it adds in.

use super::kit;
pub use super::kit::Clock;
use crate::gl::{
    memory_barrier, Barrier, Buffer, BufferUsage, ComputeProgram, Context, Framebuffer, Program,
    Rect, ShaderSource, Texture, TextureFormat,
};
use crate::shader;
use crate::timing::{Load, Runs, Spread};
use serde::Serialize;

/// The ladder's sizes by default: 2^16 to 2^22 values (Harris's problem is 2^22).
pub const SIZES: [u32; 7] = [
    1 << 16,
    1 << 17,
    1 << 18,
    1 << 19,
    1 << 20,
    1 << 21,
    1 << 22,
];
/// The largest size: 3 x 2^22 < 2^24, so every partial sum is exact in fp32.
pub const MAX_SIZE: u32 = 1 << 22;
/// The sum is exact (see the module's note): the tolerance is zero.
pub const TOLERANCE: f64 = 0.0;
/// The tolerance in words, for the checks.
pub const TOLERANCE_IN_WORDS: &str =
    "exact: integers 0-3, every partial sum an integer below 2^24, which fp32 holds";

/// How a rung runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Fragment passes, each output texel adding a `fan x fan` block of the level below.
    Fragment { fan: u32 },
    /// Compute passes of 256 invocations per group, each group reducing `per_group` values;
    /// `cascade`: far fewer groups, each invocation adding its share in a loop first.
    Compute { per_group: u32, cascade: bool },
}

/// One rung: its shader and the one change it makes.
#[derive(Clone, Copy, Debug)]
pub struct Rung {
    /// 1, 2, ... up the ladder.
    pub number: u32,
    /// Short, for tables and the plot's key: "compute 3: sequential addressing".
    pub name: &'static str,
    pub shader: ShaderSource<'static>,
    pub kind: Kind,
    /// The one change, and why it should help.
    pub change: &'static str,
}

/// Values a cascading group covers: 256 invocations, up to 32 values each.
const CASCADE_PER_GROUP: u32 = 256 * 32;

/// The rungs, bottom to top.
pub static RUNGS: [Rung; 10] = [
    Rung {
        number: 1,
        name: "fragment 2x2",
        shader: shader!("glsl/learn/ladder/f1_2x2.frag"),
        kind: Kind::Fragment { fan: 2 },
        change: "The start: lesson 3's pass, one texel of output per 2x2 block, a texture \
                 written and read again between passes; a quarter as many texels each pass.",
    },
    Rung {
        number: 2,
        name: "fragment 4x4",
        shader: shader!("glsl/learn/ladder/f2_fan.frag"),
        kind: Kind::Fragment { fan: 4 },
        change: "A wider fan-in: each fragment adds a 4x4 block, so half as many passes; \
                 fewer draws and fewer intermediate textures to write and read back in.",
    },
    Rung {
        number: 3,
        name: "fragment 8x8",
        shader: shader!("glsl/learn/ladder/f2_fan.frag"),
        kind: Kind::Fragment { fan: 8 },
        change: "8x8 blocks: a third as many passes as 2x2; each fragment now reads 64 \
                 texels in a loop, so fewer fragments are left to spread over the cores.",
    },
    Rung {
        number: 4,
        name: "fragment 16x16",
        shader: shader!("glsl/learn/ladder/f2_fan.frag"),
        kind: Kind::Fragment { fan: 16 },
        change: "16x16 blocks: a quarter as many passes as 2x2, 256 reads per fragment; the \
                 point where too few fragments are left for a wide GPU.",
    },
    Rung {
        number: 5,
        name: "compute 1: interleaved, divergent",
        shader: shader!("glsl/learn/ladder/c1_interleaved_divergent.comp"),
        kind: Kind::Compute {
            per_group: 256,
            cascade: false,
        },
        change: "Harris's kernel 1: 256 values per work group in shared memory, a tree with a \
                 barrier between steps; at step s the invocations with t % 2s == 0 add. The \
                 workers are scattered over every subgroup (divergence) and % is slow.",
    },
    Rung {
        number: 6,
        name: "compute 2: interleaved, strided index",
        shader: shader!("glsl/learn/ladder/c2_interleaved_strided.comp"),
        kind: Kind::Compute {
            per_group: 256,
            cascade: false,
        },
        change: "Kernel 2: invocation t works on index 2 s t, so the workers are the first \
                 ones, packed: no divergent subgroups, no %. Neighbours now touch shared \
                 memory 2s apart (bank conflicts on a GPU).",
    },
    Rung {
        number: 7,
        name: "compute 3: sequential addressing",
        shader: shader!("glsl/learn/ladder/c3_sequential.comp"),
        kind: Kind::Compute {
            per_group: 256,
            cascade: false,
        },
        change: "Kernel 3: the stride starts at half the group and halves; invocation t adds \
                 the value s up. Neighbours read neighbouring words, no bank conflicts; but \
                 half the invocations idle from the first step.",
    },
    Rung {
        number: 8,
        name: "compute 4: first add during load",
        shader: shader!("glsl/learn/ladder/c4_first_add.comp"),
        kind: Kind::Compute {
            per_group: 512,
            cascade: false,
        },
        change: "Kernel 4: each invocation loads two values and adds them on the way into \
                 shared memory: a group covers 512 values, half the groups, no idle \
                 invocation in the first step.",
    },
    Rung {
        number: 9,
        name: "compute 5: tree unrolled",
        shader: shader!("glsl/learn/ladder/c5_unrolled.comp"),
        kind: Kind::Compute {
            per_group: 512,
            cascade: false,
        },
        change: "Kernels 5 and 6: the group size is a compile-time constant, the eight steps \
                 are written out (no loop counter, compare or jump). Harris also drops the \
                 last six barriers, trusting a warp's lock step; GLSL promises none, so the \
                 barriers stay (subgroup operations would be the portable way, beyond 4.3).",
    },
    Rung {
        number: 10,
        name: "compute 6: several values per invocation",
        shader: shader!("glsl/learn/ladder/c6_cascade.comp"),
        kind: Kind::Compute {
            per_group: CASCADE_PER_GROUP,
            cascade: true,
        },
        change: "Kernel 7, algorithm cascading: one group per 8192 values; each invocation \
                 first adds up to 32 values in a loop striding over the whole dispatch, then \
                 the same tree. Barriers and shared memory are paid once per 8192 values.",
    },
];

impl Rung {
    pub fn is_compute(&self) -> bool {
        matches!(self.kind, Kind::Compute { .. })
    }
}

/// `n` values, integers 0 to 3 held as floats: test data the CPU makes, the same each run.
pub fn values(n: u32) -> Vec<f32> {
    kit::values(n as usize, 39)
        .into_iter()
        .map(|v| (v * 4.0).floor())
        .collect()
}

/// The CPU's sum, in f64.
pub fn cpu_sum(values: &[f32]) -> f64 {
    values.iter().map(|&v| v as f64).sum()
}

/// The texture a fragment rung reads `n` values from: as square as it goes, the last row
/// padded with zeros (the sum's identity).
pub fn shape(n: u32) -> (u32, u32) {
    let w = (n as f64).sqrt().ceil().max(1.0) as u32;
    (w, n.div_ceil(w).max(1))
}

/// The values on the GPU, once per size: a texture for the fragment rungs and, where compute
/// shaders run, a storage buffer for the compute rungs.
pub struct Input {
    pub n: u32,
    texture: Texture,
    buffer: Option<Buffer>,
}

impl Input {
    pub fn new(ctx: &Context, values: &[f32]) -> anyhow::Result<Input> {
        let n = values.len() as u32;
        anyhow::ensure!(
            (1..=MAX_SIZE).contains(&n),
            "the ladder sums 1 to {MAX_SIZE} values, not {n}"
        );
        let (w, h) = shape(n);
        let mut padded = values.to_vec();
        padded.resize((w * h) as usize, 0.0);
        let texture = Texture::from_f32(ctx, w, h, TextureFormat::R32F, &padded)?;
        let buffer = if ctx.has_compute() {
            Some(Buffer::from_slice(ctx, values, BufferUsage::Static)?)
        } else {
            None
        };
        Ok(Input { n, texture, buffer })
    }
}

/// A rung made ready for one input: its program and every intermediate target.
pub struct Prepared<'a> {
    input: &'a Input,
    gpu: Gpu,
}

enum Gpu {
    Fragment {
        program: Program,
        fan: u32,
        /// Each level's texture and its framebuffer, down to 1x1.
        levels: Vec<(Texture, Framebuffer)>,
    },
    Compute {
        program: ComputeProgram,
        /// Each pass: (values in, groups dispatched).
        plan: Vec<(u32, u32)>,
        /// Two buffers the passes write in turn.
        scratch: [Buffer; 2],
    },
}

impl<'a> Prepared<'a> {
    /// Compile the rung and make its targets (nothing is timed here).
    pub fn new(ctx: &Context, rung: &Rung, input: &'a Input) -> anyhow::Result<Prepared<'a>> {
        let gpu = match rung.kind {
            Kind::Fragment { fan } => {
                let program = Program::rect(ctx, &[rung.shader])?;
                let (mut w, mut h) = (input.texture.width(), input.texture.height());
                let mut levels = Vec::new();
                while w > 1 || h > 1 || levels.is_empty() {
                    (w, h) = (w.div_ceil(fan), h.div_ceil(fan));
                    let t = Texture::new_2d(ctx, w, h, TextureFormat::R32F)?;
                    let fb = Framebuffer::new(ctx, "ladder level", &[&t], None)?;
                    levels.push((t, fb));
                }
                Gpu::Fragment {
                    program,
                    fan,
                    levels,
                }
            }
            Kind::Compute { per_group, .. } => {
                ctx.require_compute(rung.name)?;
                let program = ComputeProgram::new(ctx, &[rung.shader])?;
                let mut plan = Vec::new();
                let mut count = input.n;
                while count > 1 || plan.is_empty() {
                    let groups = count.div_ceil(per_group);
                    plan.push((count, groups));
                    count = groups;
                }
                let bytes = plan[0].1.max(1) as usize * 4;
                let scratch = [
                    Buffer::new(ctx, bytes, BufferUsage::GpuCopy)?,
                    Buffer::new(ctx, bytes, BufferUsage::GpuCopy)?,
                ];
                Gpu::Compute {
                    program,
                    plan,
                    scratch,
                }
            }
        };
        Ok(Prepared { input, gpu })
    }

    /// The passes that bring the input down to one value (no readback).
    pub fn passes(&self) -> u32 {
        match &self.gpu {
            Gpu::Fragment { levels, .. } => levels.len() as u32,
            Gpu::Compute { plan, .. } => plan.len() as u32,
        }
    }

    /// Run every pass, down to one value (nothing is read back).
    pub fn reduce(&self) -> anyhow::Result<()> {
        match &self.gpu {
            Gpu::Fragment {
                program,
                fan,
                levels,
            } => {
                let mut below = &self.input.texture;
                for (texture, fb) in levels {
                    let size = glam::IVec2::new(below.width() as i32, below.height() as i32);
                    fb.pass(program, "ladder pass")?
                        .texture("u_level", below)
                        .uniform("u_size", size)
                        .uniform_if_used("u_fan", *fan as i32)
                        .draw_full()?;
                    below = texture;
                }
            }
            Gpu::Compute {
                program,
                plan,
                scratch,
            } => {
                let ctx = program.context();
                let mut source = self.input.buffer.as_ref().expect("made where compute runs");
                for (k, &(count, groups)) in plan.iter().enumerate() {
                    let out = &scratch[k % 2];
                    program
                        .dispatch("ladder pass")
                        .storage(0, source)
                        .storage(1, out)
                        .uniform("u_count", count)
                        .run([groups, 1, 1])?;
                    memory_barrier(ctx, &[Barrier::Storage, Barrier::BufferUpdate]);
                    source = out;
                }
            }
        }
        Ok(())
    }

    /// The one value the passes left, read back.
    pub fn result(&self) -> anyhow::Result<f32> {
        Ok(match &self.gpu {
            Gpu::Fragment { levels, .. } => {
                let (_, fb) = levels.last().expect("at least one level");
                fb.read_f32(0, Rect::sized(1, 1))?[0]
            }
            Gpu::Compute { plan, scratch, .. } => {
                let last = &scratch[(plan.len() - 1) % 2];
                last.read_prefix::<f32>(1)?[0]
            }
        })
    }
}

/// A rung run once and read back: the GPU's sum beside the CPU's.
#[derive(Clone, Debug, Serialize)]
pub struct Checked {
    pub rung: u32,
    pub name: &'static str,
    pub shader: &'static str,
    pub n: u32,
    pub passes: u32,
    pub gpu: f64,
    pub cpu: f64,
}

impl Checked {
    pub fn error(&self) -> f64 {
        let e = (self.gpu - self.cpu).abs();
        if e.is_nan() {
            f64::INFINITY
        } else {
            e
        }
    }
    pub fn passed(&self) -> bool {
        self.error() <= TOLERANCE
    }
}

/// Run `rung` once on `input` and compare its sum with `cpu`.
pub fn check(
    ctx: &Context,
    rung: &'static Rung,
    input: &Input,
    cpu: f64,
) -> anyhow::Result<Checked> {
    let prepared = Prepared::new(ctx, rung, input)?;
    prepared.reduce()?;
    Ok(Checked {
        rung: rung.number,
        name: rung.name,
        shader: rung.shader.name,
        n: input.n,
        passes: prepared.passes(),
        gpu: prepared.result()? as f64,
        cpu,
    })
}

/// Why the compute rungs cannot run on `ctx`, or `None`.
pub fn compute_skipped(ctx: &Context) -> Option<String> {
    kit::compute_missing(ctx, "each compute rung of the ladder")
}

/// The rungs `ctx` can run: all of them where compute shaders run, else the fragment ones.
pub fn runnable(ctx: &Context) -> impl Iterator<Item = &'static Rung> {
    let compute = ctx.has_compute();
    RUNGS.iter().filter(move |r| compute || !r.is_compute())
}

/// Every rung `ctx` can run, checked at `n` values.
pub fn check_all(ctx: &Context, n: u32) -> anyhow::Result<Vec<Checked>> {
    let values = values(n);
    let cpu = cpu_sum(&values);
    let input = Input::new(ctx, &values)?;
    runnable(ctx)
        .map(|rung| check(ctx, rung, &input, cpu))
        .collect()
}

/// One rung timed at one size.
#[derive(Clone, Debug, Serialize)]
pub struct Timed {
    pub rung: u32,
    pub name: &'static str,
    pub shader: &'static str,
    pub n: u32,
    pub passes: u32,
    /// Milliseconds: the reduction to one value, readback excluded.
    pub ms: Spread,
    pub clock: Clock,
    /// Bytes of input read (4 n) / the median time, in GB/s.
    pub gb_per_s: f64,
    /// The GPU's sum minus the CPU's (0: checked exact).
    pub error: f64,
}

/// The CPU's sum timed at one size.
#[derive(Clone, Debug, Serialize)]
pub struct CpuTimed {
    pub n: u32,
    pub ms: Spread,
    pub gb_per_s: f64,
}

/// The whole ladder timed over its sizes.
#[derive(Clone, Debug, Serialize)]
pub struct LadderBench {
    pub renderer: String,
    pub sizes: Vec<u32>,
    /// The runs policy in words ("3 runs, up to 5 while they took under 1 s in all").
    pub runs: String,
    /// The busier of the load before and after (None where unknown).
    pub load: Option<Load>,
    /// What each time covers.
    pub what_is_timed: &'static str,
    pub rungs: Vec<Timed>,
    pub cpu: Vec<CpuTimed>,
    /// Why the compute rungs did not run, where they did not.
    pub compute_skipped: Option<String>,
}

/// What a ladder time covers, in words.
pub const WHAT_IS_TIMED: &str = "every pass of the reduction down to one value, the input \
    already on the GPU; the readback of that value is excluded (one untimed run first checks \
    the sum exactly and warms the shader)";

fn gb_per_s(n: u32, ms: f64) -> f64 {
    if ms > 0.0 {
        n as f64 * 4.0 / (ms * 1e-3) / 1e9
    } else {
        f64::INFINITY
    }
}

/// Check and time every rung `ctx` can run at each of `sizes`, and the CPU's sum beside
/// them. A rung whose sum is wrong stops the bench: its time would mean nothing.
pub fn bench(ctx: &Context, sizes: &[u32], runs: Runs) -> anyhow::Result<LadderBench> {
    let before = Load::now();
    let mut timed = Vec::new();
    let mut cpu_times = Vec::new();
    for &n in sizes {
        let values = values(n);
        let input = Input::new(ctx, &values)?;
        let cpu = cpu_sum(&values);
        for rung in runnable(ctx) {
            let prepared = Prepared::new(ctx, rung, &input)?;
            prepared.reduce()?;
            let gpu = prepared.result()? as f64;
            let error = (gpu - cpu).abs();
            anyhow::ensure!(
                error <= TOLERANCE,
                "ladder rung {} ({}, {}) summed {n} values to {gpu}, the CPU to {cpu}: not \
                 timed, a wrong sum has no time worth reporting",
                rung.number,
                rung.name,
                rung.shader.name
            );
            let (ms, clock) = kit::time_passes(ctx, runs, || prepared.reduce())?;
            timed.push(Timed {
                rung: rung.number,
                name: rung.name,
                shader: rung.shader.name,
                n,
                passes: prepared.passes(),
                gb_per_s: gb_per_s(n, ms.median),
                ms,
                clock,
                error,
            });
        }
        let ms = crate::timing::wall_ms(runs, || cpu_sum(&values));
        cpu_times.push(CpuTimed {
            n,
            gb_per_s: gb_per_s(n, ms.median),
            ms,
        });
    }
    Ok(LadderBench {
        renderer: ctx.info().renderer_line(),
        sizes: sizes.to_vec(),
        runs: runs.in_words(),
        load: Load::worst(before, Load::now()),
        what_is_timed: WHAT_IS_TIMED,
        rungs: timed,
        cpu: cpu_times,
        compute_skipped: compute_skipped(ctx),
    })
}

impl LadderBench {
    /// The bench as a plain-text table: one row per rung and size, the CPU's rows after.
    pub fn table(&self) -> String {
        let mut out = format!(
            "reduction ladder on {}\n{}\ntimed: {}\nruns: {}\n",
            self.renderer,
            self.load.map_or("load: unknown".into(), |l| format!(
                "load: {}",
                l.in_words()
            )),
            self.what_is_timed,
            self.runs
        );
        if let Some(why) = &self.compute_skipped {
            out.push_str(&format!("compute rungs: {why}\n"));
        }
        out.push_str(&format!(
            "{:>8}  {:<46} {:>6} {:>10} {:>21} {:>9}  {}\n",
            "n", "rung", "passes", "median ms", "range ms", "GB/s", "clock"
        ));
        for &n in &self.sizes {
            for t in self.rungs.iter().filter(|t| t.n == n) {
                out.push_str(&format!(
                    "{:>8}  {:<46} {:>6} {:>10.3} {:>10.3}-{:<10.3} {:>9.3}  {}\n",
                    n,
                    format!("{}. {}", t.rung, t.name),
                    t.passes,
                    t.ms.median,
                    t.ms.min,
                    t.ms.max,
                    t.gb_per_s,
                    t.clock.in_words()
                ));
            }
            if let Some(c) = self.cpu.iter().find(|c| c.n == n) {
                out.push_str(&format!(
                    "{:>8}  {:<46} {:>6} {:>10.3} {:>10.3}-{:<10.3} {:>9.3}  {}\n",
                    n,
                    "CPU: f64 sum, one core",
                    "-",
                    c.ms.median,
                    c.ms.min,
                    c.ms.max,
                    c.gb_per_s,
                    "wall clock"
                ));
            }
        }
        out.push_str(
            "GB/s: bytes of input read (4 n) / the median time; every rung's sum was checked \
             equal to the CPU's before it was timed\n",
        );
        out
    }
}
