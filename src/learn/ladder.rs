//! The reduction ladder after Harris ("Optimizing Parallel Reduction in CUDA", NVIDIA 2007):
//! one problem, the sum of n values, solved by a row of kernels that each make one change to
//! the one before, every one checked against the CPU and, with `learn <id> --bench`, timed as
//! he measured it: one clock for the whole table, bandwidth, the speed-up of each step and
//! from the first kernel, and his G80 figures ([`HARRIS`]) beside ours at his size, 2^22.
//!
//! The ladder starts where the fragment pipeline starts (lesson 3): the 2x2 pass, then wider
//! fan-ins per pass. Then seven compute rungs, his kernels 1 to 7 in GLSL: interleaved
//! addressing with a divergent branch, with a strided index, sequential addressing, the first
//! add during the load, the last warp unrolled, the whole tree unrolled, several values per
//! invocation. His kernels 5 and 6 drop the last barriers because a CUDA warp runs in lock
//! step; GLSL promises no lock step, so rungs 5 and 6 keep every barrier (see their shaders).
//! Compute rungs need OpenGL 4.3; on an older context (softpipe is 3.3) they are skipped with
//! the reason, and the fragment rungs still run.
//!
//! The data are small integers (0 to 3) held as floats, as Harris sums integers: every partial
//! sum of at most 2^22 of them is an integer below 2^24, which fp32 holds exactly, so each
//! rung's sum must equal the CPU's f64 sum exactly, whatever order it adds in.

pub use super::kit::Clock;
use super::kit::{self, TableClock, TwoClocks};
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
pub static RUNGS: [Rung; 11] = [
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
        name: "compute 5: last warp unrolled",
        shader: shader!("glsl/learn/ladder/c5_unroll_last_warp.comp"),
        kind: Kind::Compute {
            per_group: 512,
            cascade: false,
        },
        change: "Kernel 5: the loop stops at 32 values left and the last six steps are \
                 written out (no loop counter, compare or jump). Harris also drops their \
                 barriers, trusting a warp's lock step; GLSL promises none, so every step \
                 keeps its barrier here (GL_KHR_shader_subgroup's additions would be the \
                 portable way to drop them).",
    },
    Rung {
        number: 10,
        name: "compute 6: tree unrolled completely",
        shader: shader!("glsl/learn/ladder/c6_unrolled.comp"),
        kind: Kind::Compute {
            per_group: 512,
            cascade: false,
        },
        change: "Kernel 6: the group size is a constant the compiler knows (his template \
                 parameter, a #define here), so every step is written out behind a test the \
                 compiler resolves. GLSL's local_size_x is always a constant, so the \
                 compiler may have unrolled rung 5's loop already: expect little change.",
    },
    Rung {
        number: 11,
        name: "compute 7: several values per invocation",
        shader: shader!("glsl/learn/ladder/c7_cascade.comp"),
        kind: Kind::Compute {
            per_group: CASCADE_PER_GROUP,
            cascade: true,
        },
        change: "Kernel 7, algorithm cascading: one group per 8192 values; each invocation \
                 first adds up to 32 values in a loop striding over the whole dispatch, then \
                 the same tree. Barriers and shared memory are paid once per 8192 values.",
    },
];

/// One row of Harris's table: his kernel, its time and bandwidth on a G80.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Published {
    /// His kernel, 1 to 7: compute rung `kernel` of this ladder.
    pub kernel: u32,
    pub ms: f64,
    pub gb_per_s: f64,
    /// His "step speedup" column: kernel k - 1's time over kernel k's (none for kernel 1).
    pub step: Option<f64>,
}

/// Where [`HARRIS`] comes from and what it measured.
pub const HARRIS_SOURCE: &str = "Harris, \"Optimizing Parallel Reduction in CUDA\" (NVIDIA, \
    2007): 2^22 32-bit integers summed on a G80 (GeForce 8800 GTX, 86.4 GB/s peak)";
/// His problem's size, the size his figures sit beside.
pub const HARRIS_N: u32 = 1 << 22;

/// His table, kernels 1 to 7 (time, bandwidth, step speed-up as published; about 30x from
/// the first to the last, 73% of the G80's peak).
pub static HARRIS: [Published; 7] = [
    Published {
        kernel: 1,
        ms: 8.054,
        gb_per_s: 2.083,
        step: None,
    },
    Published {
        kernel: 2,
        ms: 3.456,
        gb_per_s: 4.854,
        step: Some(2.33),
    },
    Published {
        kernel: 3,
        ms: 1.722,
        gb_per_s: 9.741,
        step: Some(2.01),
    },
    Published {
        kernel: 4,
        ms: 0.965,
        gb_per_s: 17.377,
        step: Some(1.78),
    },
    Published {
        kernel: 5,
        ms: 0.536,
        gb_per_s: 31.289,
        step: Some(1.80),
    },
    Published {
        kernel: 6,
        ms: 0.381,
        gb_per_s: 43.996,
        step: Some(1.41),
    },
    Published {
        kernel: 7,
        ms: 0.268,
        gb_per_s: 62.671,
        step: Some(1.42),
    },
];

impl Published {
    /// Kernel 1's time over this kernel's: the cumulative speed-up, from his times.
    pub fn cumulative(&self) -> f64 {
        HARRIS[0].ms / self.ms
    }
}

impl Rung {
    pub fn is_compute(&self) -> bool {
        matches!(self.kind, Kind::Compute { .. })
    }

    /// For a compute rung, Harris's kernel it follows (1 to 7).
    pub fn kernel(&self) -> Option<u32> {
        let first = RUNGS.iter().position(Rung::is_compute)? as u32;
        self.is_compute().then(|| self.number - first)
    }

    /// His row for this rung's kernel.
    pub fn published(&self) -> Option<&'static Published> {
        let k = self.kernel()?;
        HARRIS.iter().find(|p| p.kernel == k)
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

/// The side of the tiles llvmpipe bins a draw into, one thread per tile.
const TILE: u32 = 64;

/// Pieces of work a pass hands out to the renderer's threads or cores.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Spreads {
    pub count: u32,
    /// "work groups", or "64x64 tiles of fragments".
    pub unit: &'static str,
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

    /// What the first pass spreads over the renderer's threads or cores: the work groups it
    /// dispatches, or the 64x64 tiles of fragments it draws (llvmpipe bins a draw into tiles
    /// of that size and gives each tile to one thread).
    pub fn first_pass_spread(&self) -> Spreads {
        match &self.gpu {
            Gpu::Fragment { levels, .. } => {
                let (t, _) = &levels[0];
                Spreads {
                    count: t.width().div_ceil(TILE) * t.height().div_ceil(TILE),
                    unit: "64x64 tiles of fragments",
                }
            }
            Gpu::Compute { plan, .. } => Spreads {
                count: plan[0].1,
                unit: "work groups",
            },
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

/// A rung made ready and checked: its sum is the CPU's, or an error saying why its time would
/// mean nothing.
fn checked<'a>(
    ctx: &Context,
    rung: &Rung,
    input: &'a Input,
    cpu: f64,
) -> anyhow::Result<Prepared<'a>> {
    let prepared = Prepared::new(ctx, rung, input)?;
    prepared.reduce()?;
    let gpu = prepared.result()? as f64;
    let error = (gpu - cpu).abs();
    anyhow::ensure!(
        error <= TOLERANCE,
        "ladder rung {} ({}, {}) summed {} values to {gpu}, the CPU to {cpu}: not timed, a \
         wrong sum has no time worth reporting",
        rung.number,
        rung.name,
        rung.shader.name,
        input.n
    );
    Ok(prepared)
}

/// One rung timed at one size.
#[derive(Clone, Debug, Serialize)]
pub struct Timed {
    pub rung: u32,
    pub name: &'static str,
    pub shader: &'static str,
    pub n: u32,
    pub passes: u32,
    /// What its first pass hands out to the renderer's threads or cores.
    pub first_pass: Spreads,
    /// Both clocks around the same runs; the table shows one ([`LadderBench::clock`]).
    pub clocks: TwoClocks,
    /// Milliseconds on the table's clock: the reduction to one value, readback excluded.
    pub ms: Spread,
    /// Bytes of input read (4 n) / the median time, in GB/s.
    pub gb_per_s: f64,
    /// The median of the rung before it (of the same kind: fragment or compute) over its own:
    /// Harris's "step speedup" (none for the first rung of its kind).
    pub step: Option<f64>,
    /// The median of the first rung of its kind over its own: his "cumulative speedup".
    pub cumulative: f64,
    /// The GPU's sum minus the CPU's (0: checked exact).
    pub error: f64,
}

impl Timed {
    fn rung(&self) -> &'static Rung {
        &RUNGS[self.rung as usize - 1]
    }
}

/// The CPU's sum timed at one size.
#[derive(Clone, Debug, Serialize)]
pub struct CpuTimed {
    pub n: u32,
    pub ms: Spread,
    pub gb_per_s: f64,
}

/// A rung slower in the table than the rung before it, rerun to see whether that is beyond
/// the spread of the runs, and what the measurement says of why.
#[derive(Clone, Debug, Serialize)]
pub struct Slower {
    pub n: u32,
    pub rung: u32,
    pub before: u32,
    /// Both rerun at that size, one run of each in turn, on the table's clock: this rung's
    /// times, then the rung before's.
    pub rerun: (Spread, Spread),
    /// Every rerun of this rung took longer than every rerun of the one before.
    pub beyond_spread: bool,
    /// The verdict and, where the difference is real, its likely cause.
    pub why: String,
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
    /// The one clock of every rung's time, and why.
    pub clock: TableClock,
    /// What each time covers.
    pub what_is_timed: &'static str,
    pub rungs: Vec<Timed>,
    pub cpu: Vec<CpuTimed>,
    /// The rungs slower than the one before them, rerun.
    pub slower: Vec<Slower>,
    /// Harris's figures, shown beside the compute rungs at [`HARRIS_N`].
    pub harris_source: &'static str,
    pub harris: &'static [Published],
    /// Why the compute rungs did not run, where they did not.
    pub compute_skipped: Option<String>,
}

/// What a ladder time covers, in words.
pub const WHAT_IS_TIMED: &str = "every pass of the reduction down to one value, the input \
    already on the GPU; the readback of that value is excluded (one untimed run first checks \
    the sum exactly, and one more warms the rung up before its timed runs)";

fn gb_per_s(n: u32, ms: f64) -> f64 {
    if ms > 0.0 {
        n as f64 * 4.0 / (ms * 1e-3) / 1e9
    } else {
        f64::INFINITY
    }
}

/// Check and time every rung `ctx` can run at each of `sizes`, and the CPU's sum beside
/// them; choose the table's one clock; rerun every rung slower than the one before it. A rung
/// whose sum is wrong stops the bench: its time would mean nothing.
pub fn bench(ctx: &Context, sizes: &[u32], runs: Runs) -> anyhow::Result<LadderBench> {
    let before = Load::now();
    let mut timed = Vec::new();
    let mut cpu_times = Vec::new();
    for &n in sizes {
        let values = values(n);
        let input = Input::new(ctx, &values)?;
        let cpu = cpu_sum(&values);
        for rung in runnable(ctx) {
            let prepared = checked(ctx, rung, &input, cpu)?;
            let clocks = kit::time_two_clocks(ctx, runs, || prepared.reduce())?;
            timed.push(Timed {
                rung: rung.number,
                name: rung.name,
                shader: rung.shader.name,
                n,
                passes: prepared.passes(),
                first_pass: prepared.first_pass_spread(),
                clocks,
                ms: Spread::default(),
                gb_per_s: 0.0,
                step: None,
                cumulative: 1.0,
                error: 0.0,
            });
        }
        let ms = crate::timing::wall_ms(runs, || cpu_sum(&values));
        cpu_times.push(CpuTimed {
            n,
            gb_per_s: gb_per_s(n, ms.median),
            ms,
        });
    }
    let rows: Vec<(String, TwoClocks)> = timed
        .iter()
        .map(|t| (format!("rung {} at n = {}", t.rung, t.n), t.clocks))
        .collect();
    let clock = kit::table_clock(ctx, &rows);
    on_clock(&mut timed, clock.clock);
    let slower = rerun_slower(ctx, &timed, clock.clock, runs)?;
    Ok(LadderBench {
        renderer: ctx.info().renderer_line(),
        sizes: sizes.to_vec(),
        runs: runs.in_words(),
        load: Load::worst(before, Load::now()),
        clock,
        what_is_timed: WHAT_IS_TIMED,
        rungs: timed,
        cpu: cpu_times,
        slower,
        harris_source: HARRIS_SOURCE,
        harris: &HARRIS,
        compute_skipped: compute_skipped(ctx),
    })
}

/// Each row's times on the table's `clock`, its bandwidth, and its speed-ups over the rung
/// before it and over the first rung of its kind at the same size.
pub fn on_clock(timed: &mut [Timed], clock: Clock) {
    for t in timed.iter_mut() {
        t.ms = t.clocks.on(clock);
        t.gb_per_s = gb_per_s(t.n, t.ms.median);
    }
    let medians: Vec<(u32, u32, bool, f64)> = timed
        .iter()
        .map(|t| (t.n, t.rung, t.rung().is_compute(), t.ms.median))
        .collect();
    for t in timed.iter_mut() {
        let kind = t.rung().is_compute();
        let same = |&&(n, _, k, _): &&(u32, u32, bool, f64)| n == t.n && k == kind;
        let before = medians
            .iter()
            .filter(same)
            .filter(|m| m.1 < t.rung)
            .max_by_key(|m| m.1);
        let first = medians.iter().filter(same).min_by_key(|m| m.1);
        let over = |m: f64| m / t.ms.median.max(1e-12);
        t.step = before.map(|m| over(m.3));
        t.cumulative = first.map_or(1.0, |m| over(m.3));
    }
}

/// Rerun each rung slower than the one before it (same size, same kind) against that one, a
/// run of each in turn, and judge whether the difference is beyond the spread.
fn rerun_slower(
    ctx: &Context,
    timed: &[Timed],
    clock: Clock,
    runs: Runs,
) -> anyhow::Result<Vec<Slower>> {
    let mut out = Vec::new();
    let mut input: Option<(Input, f64)> = None;
    for t in timed.iter().filter(|t| t.step.is_some_and(|s| s < 1.0)) {
        let Some(before) = timed
            .iter()
            .filter(|b| b.n == t.n && b.rung < t.rung)
            .filter(|b| b.rung().is_compute() == t.rung().is_compute())
            .max_by_key(|b| b.rung)
        else {
            continue;
        };
        if input.as_ref().is_none_or(|(i, _)| i.n != t.n) {
            let values = values(t.n);
            input = Some((Input::new(ctx, &values)?, cpu_sum(&values)));
        }
        let (data, cpu) = input.as_ref().expect("made above");
        let this = checked(ctx, t.rung(), data, *cpu)?;
        let that = checked(ctx, before.rung(), data, *cpu)?;
        let rerun = kit::time_alternating(ctx, clock, runs, || this.reduce(), || that.reduce())?;
        let beyond_spread = rerun.0.min > rerun.1.max;
        let why = if beyond_spread {
            format!(
                "beyond the spread: every rerun of rung {} took longer than every rerun of \
                 rung {}. {}",
                t.rung,
                before.rung,
                likely_cause(ctx, t, before)
            )
        } else if rerun.0.max < rerun.1.min {
            format!(
                "not so on a rerun: run in turn, every run of rung {} was the faster, so the \
                 table's order of the two is the machine's noise, not rung {}'s change",
                t.rung, t.rung
            )
        } else {
            format!(
                "within the spread: run in turn, the two overlap, so their order in the table \
                 is the machine's noise, not rung {}'s change",
                t.rung
            )
        };
        out.push(Slower {
            n: t.n,
            rung: t.rung,
            before: before.rung,
            rerun,
            beyond_spread,
            why,
        });
    }
    Ok(out)
}

/// The threads a software renderer spreads its work over: `LP_NUM_THREADS` where set (as
/// llvmpipe reads it), else the cores this process may use.
fn renderer_threads() -> u32 {
    std::env::var("LP_NUM_THREADS")
        .ok()
        .and_then(|v| v.trim().parse::<u32>().ok())
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get() as u32))
        .max(1)
}

/// What the measurement says of why rung `t` is slower than `before`, from the work each
/// hands out and the passes each takes.
fn likely_cause(ctx: &Context, t: &Timed, before: &Timed) -> String {
    let (mine, theirs) = (t.first_pass, before.first_pass);
    let threads = renderer_threads();
    if ctx.info().is_software() && mine.count < theirs.count && mine.count < 2 * threads {
        return format!(
            "Likely cause: its first pass hands out {} {} (rung {}: {}) to {threads} CPU \
             threads. This software renderer runs each work group, and each tile of fragments, \
             on one CPU thread, so so few of them leave threads idle while the last ones \
             finish; on a GPU of thousands of lanes the same change pays off only at larger n.",
            mine.count, mine.unit, before.rung, theirs.count
        );
    }
    if !ctx.info().is_software() && mine.count < theirs.count && mine.count < 64 {
        return format!(
            "Likely cause: its first pass hands out only {} {} (rung {}: {}), too few to fill \
             the GPU's multiprocessors at this size.",
            mine.count, mine.unit, before.rung, theirs.count
        );
    }
    if let (Kind::Fragment { fan }, Kind::Fragment { fan: was }) =
        (t.rung().kind, before.rung().kind)
    {
        return format!(
            "Likely cause: each fragment now adds a {fan}x{fan} block in a loop ({} texel \
             fetches from {fan} rows) where rung {} added {was}x{was} ({}): one fragment's reads \
             lie further apart and its loop is longer, and the passes saved ({} against {}) no \
             longer pay for that at this size.",
            fan * fan,
            before.rung,
            was * was,
            t.passes,
            before.passes
        );
    }
    if t.passes > before.passes {
        return format!(
            "Likely cause: it takes {} passes against {}, and each pass is one more draw or \
             dispatch with its own fixed cost, which matters at this size.",
            t.passes, before.passes
        );
    }
    if matches!(t.rung().kernel(), Some(5 | 6)) {
        return "Likely cause: the change is an unrolling the compiler may have made by itself \
                (the group size is a constant in GLSL), so the two run nearly the same \
                instructions and what differs is the code the compiler laid out, which a time \
                cannot show."
            .into();
    }
    format!(
        "This measurement does not say why: both hand out {} and {} {} in {} and {} passes; \
         the two differ only in rung {}'s change.",
        mine.count, theirs.count, mine.unit, t.passes, before.passes, t.rung
    )
}

impl LadderBench {
    /// The bench as plain text: the clock and why, a block per size (Harris's G80 figures
    /// beside the compute rungs at his size), then the rungs slower than the one before them.
    pub fn table(&self) -> String {
        let mut out = format!(
            "reduction ladder on {}\n{}\ntimed: {}\nruns: {}, each rung after one warm-up \
             run\nclock: {} for every rung: {}\n",
            self.renderer,
            self.load.map_or("load: unknown".into(), |l| format!(
                "load: {}",
                l.in_words()
            )),
            self.what_is_timed,
            self.runs,
            self.clock.clock.in_words(),
            self.clock.why,
        );
        if let Some(why) = &self.compute_skipped {
            out.push_str(&format!("compute rungs: {why}\n"));
        }
        for &n in &self.sizes {
            out.push_str(&self.block(n));
        }
        out.push_str(
            "median and range: ms over the runs; GB/s: bytes of input read (4 n) / the median; \
             step: the median of the rung before (of the same kind) / this one's; total: the \
             first fragment or first compute rung's median / this one's (Harris's step and \
             cumulative speed-ups). Every rung's sum was checked equal to the CPU's before it \
             was timed.\n",
        );
        out.push_str(&format!("G80: {}", self.harris_source));
        if self.sizes.contains(&HARRIS_N) {
            out.push_str(
                "; his times, bandwidths and step speed-ups as published, the totals \
                          from his times.\n",
            );
        } else {
            out.push_str(&format!(
                "; beside ours at n = {HARRIS_N} only (run without --size, or --size \
                 {HARRIS_N}): kernel 1 {:.3} ms, {:.3} GB/s; kernel 7 {:.3} ms, {:.3} GB/s, \
                 {:.0}x.\n",
                HARRIS[0].ms,
                HARRIS[0].gb_per_s,
                HARRIS[6].ms,
                HARRIS[6].gb_per_s,
                HARRIS[6].cumulative()
            ));
        }
        if !self.slower.is_empty() {
            out.push_str(
                "rungs slower than the rung before them, both rerun at that size one run of \
                 each in turn:\n",
            );
            for s in &self.slower {
                let text = format!(
                    "n = {}: rung {} {} vs rung {} {}: {}",
                    s.n,
                    s.rung,
                    s.rerun.0.in_words(" ms"),
                    s.before,
                    s.rerun.1.in_words(" ms"),
                    s.why
                );
                for (k, line) in crate::gl::picture::wrap(&text, 96).iter().enumerate() {
                    out.push_str(if k == 0 { "  " } else { "    " });
                    out.push_str(line);
                    out.push('\n');
                }
            }
        }
        out
    }

    /// The rows of one size.
    fn block(&self, n: u32) -> String {
        let harris = n == HARRIS_N;
        let mut out = format!(
            "\nn = {n}{}\n",
            if harris {
                " (Harris's size: his G80 figures beside the compute rungs)"
            } else {
                ""
            }
        );
        out.push_str(&format!(
            "  {:<44} {:>6} {:>10} {:>19} {:>9} {:>7} {:>8}",
            "rung", "passes", "median ms", "range ms", "GB/s", "step", "total"
        ));
        if harris {
            out.push_str(&format!(
                " | {:>8} {:>8} {:>6} {:>7}",
                "G80 ms", "GB/s", "step", "total"
            ));
        }
        out.push('\n');
        let speedup = |x: Option<f64>| x.map_or("-".to_string(), |x| format!("{x:.2}x"));
        for t in self.rungs.iter().filter(|t| t.n == n) {
            out.push_str(&format!(
                "  {:<44} {:>6} {:>10.3} {:>19} {:>9.3} {:>7} {:>8}",
                format!("{}. {}", t.rung, t.name),
                t.passes,
                t.ms.median,
                format!("{:.3}-{:.3}", t.ms.min, t.ms.max),
                t.gb_per_s,
                speedup(t.step),
                speedup(Some(t.cumulative)),
            ));
            if let Some(p) = t.rung().published().filter(|_| harris) {
                out.push_str(&format!(
                    " | {:>8.3} {:>8.3} {:>6} {:>7}",
                    p.ms,
                    p.gb_per_s,
                    speedup(p.step),
                    speedup(Some(p.cumulative()))
                ));
            }
            out.push('\n');
        }
        if let Some(c) = self.cpu.iter().find(|c| c.n == n) {
            out.push_str(&format!(
                "  {:<44} {:>6} {:>10.3} {:>19} {:>9.3}  (wall clock)\n",
                "CPU: f64 sum, one core",
                "-",
                c.ms.median,
                format!("{:.3}-{:.3}", c.ms.min, c.ms.max),
                c.gb_per_s,
            ));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(rung: u32, n: u32, ms: f64) -> Timed {
        let spread = Spread {
            runs: 3,
            median: ms,
            min: ms * 0.9,
            max: ms * 1.1,
        };
        Timed {
            rung,
            name: RUNGS[rung as usize - 1].name,
            shader: RUNGS[rung as usize - 1].shader.name,
            n,
            passes: 2,
            first_pass: Spreads {
                count: 8,
                unit: "work groups",
            },
            clocks: TwoClocks {
                query: Spread::default(),
                wall: spread,
            },
            ms: Spread::default(),
            gb_per_s: 0.0,
            step: None,
            cumulative: 1.0,
            error: 0.0,
        }
    }

    #[test]
    fn harris_table_is_his_seven_kernels_and_thirty_fold() {
        assert_eq!(HARRIS.len(), 7);
        let compute: Vec<&Rung> = RUNGS.iter().filter(|r| r.is_compute()).collect();
        assert_eq!(compute.len(), 7, "a compute rung per kernel");
        for (k, r) in compute.iter().enumerate() {
            assert_eq!(r.kernel(), Some(k as u32 + 1));
            assert_eq!(r.published().unwrap().kernel, k as u32 + 1);
        }
        // His bandwidths are 4 x 2^22 bytes over his times (to his rounding), and his step
        // speed-ups the ratio of consecutive times.
        for (k, p) in HARRIS.iter().enumerate() {
            let derived = gb_per_s(HARRIS_N, p.ms);
            assert!(
                (derived / p.gb_per_s - 1.0).abs() < 0.002,
                "{p:?}: {derived}"
            );
            if k > 0 {
                let step = HARRIS[k - 1].ms / p.ms;
                assert!((step - p.step.unwrap()).abs() < 0.01, "{p:?}: {step}");
            }
        }
        assert!((HARRIS[6].cumulative() - 30.0).abs() < 0.1);
        assert_eq!((HARRIS[0].ms, HARRIS[0].gb_per_s), (8.054, 2.083));
        assert_eq!((HARRIS[6].ms, HARRIS[6].gb_per_s), (0.268, 62.671));
    }

    #[test]
    fn speedups_are_over_the_rung_before_and_the_first_of_its_kind() {
        let n = HARRIS_N;
        // Fragment rungs 1-2, compute rungs 5-7 (kernels 1-3): kernel 3 slower than kernel 2.
        let mut timed = vec![
            row(1, n, 8.0),
            row(2, n, 4.0),
            row(5, n, 6.0),
            row(6, n, 2.0),
            row(7, n, 3.0),
        ];
        on_clock(&mut timed, Clock::FinishedWall);
        let by = |r: u32| timed.iter().find(|t| t.rung == r).unwrap();
        assert_eq!(by(1).step, None);
        assert_eq!(by(2).step, Some(2.0));
        assert_eq!(by(2).cumulative, 2.0);
        // The first compute rung starts its own count, not the fragment rungs'.
        assert_eq!(by(5).step, None);
        assert_eq!(by(5).cumulative, 1.0);
        assert_eq!(by(6).step, Some(3.0));
        assert_eq!(by(7).step, Some(2.0 / 3.0));
        assert_eq!(by(7).cumulative, 2.0);
        assert!((by(5).gb_per_s - gb_per_s(n, 6.0)).abs() < 1e-12);
        let bench = LadderBench {
            renderer: "test".into(),
            sizes: vec![n],
            runs: "exactly 3 runs".into(),
            load: None,
            clock: TableClock {
                clock: Clock::FinishedWall,
                why: "a test".into(),
            },
            what_is_timed: WHAT_IS_TIMED,
            rungs: timed,
            cpu: Vec::new(),
            slower: Vec::new(),
            harris_source: HARRIS_SOURCE,
            harris: &HARRIS,
            compute_skipped: None,
        };
        let text = bench.table();
        println!("{text}");
        assert!(text.contains("clock: glFinish wall clock for every rung: a test"));
        // Harris's row for kernel 1 beside compute 1, his kernel 3 beside compute 3.
        let line = |rung: u32| {
            text.lines()
                .find(|l| l.trim_start().starts_with(&format!("{rung}. ")))
                .unwrap()
                .to_string()
        };
        assert!(
            line(5).contains("8.054") && line(5).contains("2.083"),
            "{}",
            line(5)
        );
        assert!(
            line(7).contains("1.722") && line(7).contains("0.67x"),
            "{}",
            line(7)
        );
        assert!(!line(1).contains('|'), "{}", line(1));
    }
}
