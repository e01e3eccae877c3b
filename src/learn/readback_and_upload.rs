//! Lesson 8, moving data between the CPU and the GPU: an upload from client memory and one
//! through a pixel unpack buffer (PBO); a readback with glReadPixels, one into a pixel pack
//! buffer, and a compacted readback that reads only the blocks holding data (paper 1's idea of
//! reading less, section 5.3.1, made with the histogram pyramid of Ziegler et al. 2006 in
//! [`super::histogram_pyramid`]: three glReadPixels calls however many blocks hold data).
//! Every path is checked byte for byte, and each step of the compaction against the CPU: the
//! flags block by block, the pyramid node by node, the list slot by slot. Where the pipeline
//! stalls: a glReadPixels into client memory waits for every queued pass; a read into a PBO is
//! queued like a pass and the CPU waits only when it maps the buffer. Each path is timed warm
//! (one untimed run, then the median of [`LESSON_RUNS`]), and the explanation quotes those
//! medians with the renderer (never a check).

use super::histogram_pyramid::{self, Compaction, HistogramPyramid};
use super::kit::{self, Steps, Wait};
use super::{
    Exercise, Grid, Lesson, LessonInfo, LessonOptions, LessonRun, PaperStep, PassBuffer,
    LESSON_RUNS,
};
use crate::gl::{
    AtomicCounters, Buffer, BufferUsage, ComputeProgram, Context, Framebuffer, Program, Texture,
    TextureFormat,
};
use crate::shader;
use crate::timing::{Load, Runs, Spread};
use serde::Serialize;

const SIDE: u32 = 128;
const BLOCK: u32 = 8;
/// The share of blocks that hold data, and of the texels of such a block that are not zero:
/// data in clusters, as paper 1's colliding pairs are, so that reading only those blocks
/// reads a sixteenth of the array.
const BLOCK_SHARE: f32 = 1.0 / 16.0;
const TEXEL_SHARE: f32 = 0.25;

static INFO: LessonInfo = LessonInfo {
    id: "readback-and-upload",
    number: 8,
    title: "Readback and upload: glReadPixels, pixel buffers, and reading less",
    idea: "Data crosses the bus twice: up as texture uploads, down as readbacks. An upload \
           from client memory copies before it returns; through a pixel unpack buffer (PBO) \
           the copy is queued. glReadPixels into client memory stalls the CPU until every \
           queued pass is done; into a pixel pack buffer it is queued too, and the CPU waits \
           only when it maps the buffer. The cheapest readback reads less, in few calls: a \
           pass flags the blocks that hold data, a histogram pyramid sums the flags, each slot \
           of a list walks the pyramid to its flagged block, and a gather pass packs those \
           blocks together, so three reads (the count, the list, the blocks) bring back only \
           what is there.",
    paper_steps: &[
        PaperStep {
            paper: "Paper 1, section 5.3",
            step: "stream reduction: the hierarchical readback of the colliding pairs from P0 \
               through P1-P3",
            file: "src/collide/reduction.rs",
        },
        PaperStep {
            paper: "Paper 1, section 5.3 (the GPU side)",
            step: "the encoding passes and the reads the decoder asks for",
            file: "src/collide/reduction_gpu.rs",
        },
    ],
    shaders: &[
        "glsl/learn/readback-and-upload/block_flags.frag",
        "glsl/learn/readback-and-upload/pyramid_level.frag",
        "glsl/learn/readback-and-upload/pyramid_list.frag",
        "glsl/learn/readback-and-upload/gather_blocks.frag",
        "glsl/learn/readback-and-upload/compact.comp",
    ],
    exercises: &[Exercise {
        number: 1,
        task: "Flag a block when any texel of it is not zero: visit all BLOCK x BLOCK texels.",
        shader: "glsl/learn/readback-and-upload/block_flags.frag",
        hints: [
            "A block's flag says whether any texel of its u_block x u_block block \
             holds data; looking at one texel misses the rest.",
            "flag = 1 when some texel corner + (x, y), x and y in [0, u_block), has a \
             non-zero component; else 0.",
            "for (int y = 0; y < u_block; ++y) { for (int x = 0; x < u_block; ++x) { \
             vec4 v = texelFetch(u_data, corner + ivec2(x, y), 0); if \
             (any(notEqual(v, vec4(0.0)))) any_set = 1.0; } }",
        ],
    }],
};

pub struct ReadbackAndUpload;

impl Lesson for ReadbackAndUpload {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        kit::exercise_asked(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        let runs = Runs::exactly(LESSON_RUNS);
        let source = sparse_data(SIDE);
        let data = uploads(ctx, &mut run, &source, runs)?;
        let (whole_ms, pbo) = whole_readbacks(ctx, &mut run, &data, &source, runs)?;
        let compacted = compacted_readback(ctx, &mut run, &data, &source, runs)?;
        if let Some(compacted) = compacted {
            let measured = Measured {
                software: ctx.info().is_software(),
                side: SIDE,
                runs: LESSON_RUNS,
                whole_ms: whole_ms.median,
                pbo_ms: pbo.whole.median,
                compacted,
                bytes_full: source.len() * 4,
            };
            run.note("why these numbers", measured.explain());
        }
        run.compute = Some(match kit::compute_missing(ctx, "the compute compaction") {
            Some(why) => why,
            None => {
                run.pass(
                    "compute compaction",
                    "glsl/learn/readback-and-upload/compact.comp",
                    "every non-zero element appended through an atomic counter",
                    None,
                );
                let wrong = compact_mismatches(ctx, &source)?;
                run.check(
                    "compute: compacted elements differing from the CPU's list (exact)",
                    wrong as f64,
                    0.0,
                );
                "ran: the non-zero elements compacted into a list, its length read first".into()
            }
        });
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// Record a time the lesson took warm: its median, the runs and the renderer in the name.
fn timed_note(run: &mut LessonRun, what: &str, ms: &Spread) {
    let name = format!(
        "{what} (ms: median of {} runs after a warm-up, range {:.3}-{:.3}; {})",
        ms.runs, ms.min, ms.max, run.renderer
    );
    run.note(&name, format!("{:.3}", ms.median));
}

/// The two uploads, each checked byte for byte and its call timed warm: the array as a
/// texture, the one the readbacks read.
fn uploads(
    ctx: &Context,
    run: &mut LessonRun,
    source: &[f32],
    runs: Runs,
) -> anyhow::Result<Texture> {
    let direct = Texture::new_2d(ctx, SIDE, SIDE, TextureFormat::Rgba32F)?;
    let call = kit::time_call(ctx, runs, || Ok(direct.upload_f32(source)?))?;
    timed_note(run, "upload from client memory: the call", &call);
    let picture = Some(kit::buffer(&direct)?);
    run.pass(
        "upload (client memory)",
        "",
        "glTexSubImage2D from the CPU's array",
        picture,
    );
    run.check(
        "upload from client memory: bytes differing after download (exact)",
        kit::bytes_differing(&direct.download_f32()?, source),
        0.0,
    );
    // region: upload-pbo
    let through_pbo = Texture::new_2d(ctx, SIDE, SIDE, TextureFormat::Rgba32F)?;
    let unpack = Buffer::from_slice(ctx, source, BufferUsage::Dynamic)?;
    through_pbo.upload_from_buffer(&unpack, 0)?;
    // endregion
    let call = kit::time_call(
        ctx,
        runs,
        || Ok(through_pbo.upload_from_buffer(&unpack, 0)?),
    )?;
    timed_note(run, "upload from a PBO: the call (queued)", &call);
    run.pass(
        "upload (PBO)",
        "",
        "glTexSubImage2D from a pixel unpack buffer",
        None,
    );
    run.check(
        "upload through a PBO: bytes differing after download (exact)",
        kit::bytes_differing(&through_pbo.download_f32()?, source),
        0.0,
    );
    Ok(direct)
}

/// The whole array read back into client memory and through a PBO, each checked byte for
/// byte and timed warm: the first's times, and the PBO's two steps (the queued call, the
/// wait when the buffer is read).
fn whole_readbacks(
    ctx: &Context,
    run: &mut LessonRun,
    data: &Texture,
    source: &[f32],
    runs: Runs,
) -> anyhow::Result<(Spread, Steps)> {
    // region: full-readback
    let target = Framebuffer::new(ctx, "data", &[data], None)?;
    let full = target.read_f32(0, target.rect())?;
    // endregion
    let whole_ms = kit::time_finished(ctx, runs, || {
        target.read_f32(0, target.rect())?;
        Ok(())
    })?;
    timed_note(
        run,
        "glReadPixels into client memory, whole array",
        &whole_ms,
    );
    run.pass(
        "glReadPixels",
        "",
        "the whole array into client memory: the CPU waits",
        None,
    );
    run.check(
        "glReadPixels: bytes differing from the uploaded array (exact)",
        kit::bytes_differing(&full, source),
        0.0,
    );
    let pack = Buffer::new(ctx, source.len() * 4, BufferUsage::GpuCopy)?;
    target.read_into_buffer(0, target.rect(), &pack, 0)?;
    let from_pbo: Vec<f32> = pack.read()?;
    let pbo = kit::time_steps_with(ctx, runs, 2, Wait::AtTheEnd, |step| {
        if step == 0 {
            target.read_into_buffer(0, target.rect(), &pack, 0)?;
        } else {
            pack.read::<f32>()?;
        }
        Ok(())
    })?;
    timed_note(
        run,
        "glReadPixels into a PBO: the call (queued)",
        &pbo.steps[0],
    );
    timed_note(run, "reading the PBO: where the CPU waits", &pbo.steps[1]);
    run.pass(
        "glReadPixels into a PBO",
        "",
        "queued; the CPU waits only when it reads the buffer",
        None,
    );
    run.check(
        "PBO readback: bytes differing from the uploaded array (exact)",
        kit::bytes_differing(&from_pbo, source),
        0.0,
    );
    Ok((whole_ms, pbo))
}

/// `side x side` RGBA texels in clusters: about [`BLOCK_SHARE`] of the blocks hold data, in
/// about [`TEXEL_SHARE`] of their texels; every other texel is zero.
fn sparse_data(side: u32) -> Vec<f32> {
    let blocks = side / BLOCK;
    let n = (side * side) as usize;
    let block_pick = kit::values((blocks * blocks) as usize, 8);
    let texel_pick = kit::values(n, 80);
    let content = kit::values(3 * n, 81);
    (0..n)
        .flat_map(|i| {
            let (x, y) = (i as u32 % side, i as u32 / side);
            let block = (y / BLOCK * blocks + x / BLOCK) as usize;
            if block_pick[block] < BLOCK_SHARE && texel_pick[i] < TEXEL_SHARE {
                [
                    i as f32,
                    content[3 * i],
                    content[3 * i + 1],
                    content[3 * i + 2],
                ]
            } else {
                [0.0; 4]
            }
        })
        .collect()
}

/// The CPU's flags: 1 for each `BLOCK x BLOCK` block of the `side x side` RGBA array that
/// holds a non-zero component, rows of blocks from the bottom.
fn cpu_flags(source: &[f32], side: u32) -> Vec<f32> {
    let blocks = side / BLOCK;
    (0..blocks * blocks)
        .map(|b| {
            let (bx, by) = (b % blocks * BLOCK, b / blocks * BLOCK);
            let holds = (0..BLOCK * BLOCK).any(|t| {
                let at = (((by + t / BLOCK) * side + bx + t % BLOCK) * 4) as usize;
                source[at..at + 4].iter().any(|&v| v != 0.0)
            });
            if holds {
                1.0
            } else {
                0.0
            }
        })
        .collect()
}

/// The steps of a compacted readback, in the order they run ([`Compacted::timed`]).
pub const COMPACT_STEPS: [&str; 4] = [
    "the flags pass and the pyramid",
    "read the count",
    "the list and gather passes",
    "read the list and the blocks",
];
/// Which of [`COMPACT_STEPS`] are passes, and which are reads.
const PASS_STEPS: [usize; 2] = [0, 2];
const READ_STEPS: [usize; 2] = [1, 3];

/// A compacted readback of one array made ready: the flags program, the pyramid over its
/// blocks, and the list and gather targets for the count a first run found.
struct Compacted<'a> {
    data: &'a Texture,
    side: u32,
    flags_program: Program,
    pyramid: HistogramPyramid,
    compaction: Option<Compaction>,
}

impl<'a> Compacted<'a> {
    fn new(ctx: &Context, data: &'a Texture) -> anyhow::Result<Compacted<'a>> {
        let side = data.width();
        let flags_program = Program::rect(
            ctx,
            &[shader!("glsl/learn/readback-and-upload/block_flags.frag")],
        )?;
        let pyramid = HistogramPyramid::new(ctx, (side / BLOCK, side / BLOCK))?;
        let mut compacted = Compacted {
            data,
            side,
            flags_program,
            pyramid,
            compaction: None,
        };
        compacted.flags_and_pyramid()?;
        let count = compacted.pyramid.count()?;
        if count > 0 {
            compacted.compaction = Some(Compaction::new(ctx, count, BLOCK)?);
        }
        Ok(compacted)
    }

    /// The flags pass into the pyramid's level 0 (the lesson's exercise), then the pyramid.
    fn flags_and_pyramid(&self) -> anyhow::Result<()> {
        // region: block-flags
        self.pyramid
            .base()?
            .pass(&self.flags_program, "block flags")?
            .texture("u_data", self.data)
            .uniform("u_block", BLOCK as i32)
            .draw_rect(self.pyramid.flags_rect())?;
        self.pyramid.build()?;
        // endregion
        Ok(())
    }

    /// The count at the pyramid's top, read back: the one the targets were made for.
    fn count(&self) -> anyhow::Result<u32> {
        let count = self.pyramid.count()?;
        let made_for = self.compaction.as_ref().map_or(0, Compaction::count);
        anyhow::ensure!(
            count == made_for,
            "the pyramid counted {count} flagged blocks, {made_for} in its first run"
        );
        Ok(count)
    }

    fn list_and_gather(&self) -> anyhow::Result<()> {
        match &self.compaction {
            Some(c) => c.draw(&self.pyramid, self.data),
            None => Ok(()),
        }
    }

    /// The list and the gathered blocks, read back (empty when no block is flagged).
    fn read(&self) -> anyhow::Result<(Vec<f32>, Vec<f32>)> {
        match &self.compaction {
            // region: read-compacted
            Some(c) => Ok((c.read_list()?, c.read_blocks()?)),
            // endregion
            None => Ok((Vec::new(), Vec::new())),
        }
    }

    /// Every step once: the whole array put together from what was read.
    fn array(&self) -> anyhow::Result<Vec<f32>> {
        self.flags_and_pyramid()?;
        self.count()?;
        self.list_and_gather()?;
        let (list, blocks) = self.read()?;
        Ok(match &self.compaction {
            Some(c) => c.place(&list, &blocks, self.side),
            None => vec![0.0; (self.side * self.side * 4) as usize],
        })
    }

    /// Bytes the reads move (none when no block is flagged, but the count).
    fn bytes_read(&self) -> usize {
        self.compaction.as_ref().map_or(4, Compaction::bytes_read)
    }

    /// The steps of [`COMPACT_STEPS`] timed warm, in the same runs.
    fn timed(&self, ctx: &Context, runs: Runs) -> anyhow::Result<Steps> {
        kit::time_steps(ctx, runs, COMPACT_STEPS.len(), |step| {
            match step {
                0 => self.flags_and_pyramid()?,
                1 => {
                    self.count()?;
                }
                2 => self.list_and_gather()?,
                _ => {
                    self.read()?;
                }
            }
            Ok(())
        })
    }

    /// What a timed run measured, for the explanation.
    fn measured(&self, steps: Steps) -> CompactTimed {
        let blocks = self.side / BLOCK;
        CompactTimed {
            whole: steps.whole,
            passes: steps.part(&PASS_STEPS),
            reads: steps.part(&READ_STEPS),
            steps,
            count: self.compaction.as_ref().map_or(0, Compaction::count),
            blocks: blocks * blocks,
            levels: self.pyramid.levels(),
            bytes: self.bytes_read(),
        }
    }
}

/// A compacted readback timed: the whole, its passes and its reads (parts of the same runs),
/// and what it read.
#[derive(Clone, Debug, Serialize)]
pub struct CompactTimed {
    pub whole: Spread,
    /// The flags pass, the pyramid, the list and the gather.
    pub passes: Spread,
    /// The three reads: the count, the list, the blocks.
    pub reads: Spread,
    pub steps: Steps,
    /// Flagged blocks, of `blocks`.
    pub count: u32,
    pub blocks: u32,
    /// The pyramid's levels, the flags included.
    pub levels: u32,
    /// Bytes the three reads moved.
    pub bytes: usize,
}

/// The compacted readback, step by step, each step checked against the CPU on the GPU's own
/// input: the flags block by block (against the array), the pyramid node by node and the list
/// slot by slot (against the GPU's flags), the array put together byte for byte; then timed.
fn compacted_readback(
    ctx: &Context,
    run: &mut LessonRun,
    data: &Texture,
    source: &[f32],
    runs: Runs,
) -> anyhow::Result<Option<CompactTimed>> {
    let compacted = Compacted::new(ctx, data)?;
    let blocks = (SIDE / BLOCK, SIDE / BLOCK);
    let pyramid = &compacted.pyramid;
    let side = histogram_pyramid::pyramid_side(blocks);
    let base = pyramid.level(0)?;
    let gpu_flags: Vec<f32> = (0..blocks.1)
        .flat_map(|y| (0..blocks.0).map(move |x| (y * side + x) as usize))
        .map(|at| base[at])
        .collect();
    let expected = cpu_flags(source, SIDE);
    run.pass(
        "block flags",
        "glsl/learn/readback-and-upload/block_flags.frag",
        "one texel per 8x8 block, 1 where the block holds data: level 0 of the pyramid",
        Some(
            PassBuffer::floats(blocks.0, blocks.1, 1, gpu_flags.clone())
                .with_reference(expected.clone()),
        ),
    );
    run.check_texels(
        "block flags: 1 where the block holds data, as the CPU finds (exact)",
        Grid::new(blocks.0, blocks.1, 1).of("block"),
        &gpu_flags,
        &expected,
        0.0,
    );
    let cpu_levels = histogram_pyramid::cpu_levels(&gpu_flags, blocks);
    for level in 1..pyramid.levels() {
        let s = side >> level;
        let gpu = pyramid.level(level)?;
        let cpu = &cpu_levels[level as usize];
        run.pass(
            &format!("pyramid level {level}"),
            "glsl/learn/readback-and-upload/pyramid_level.frag",
            "each texel the sum of the 2x2 below it: the flagged blocks under it",
            Some(
                PassBuffer::floats(s, s, 1, gpu.clone())
                    .in_set("pyramid")
                    .with_reference(cpu.clone()),
            ),
        );
        run.check_texels(
            &format!("pyramid level {level}: each node counts the flagged blocks under it (exact)"),
            Grid::new(s, s, 1).of("node"),
            &gpu,
            cpu,
            0.0,
        );
    }
    let Some(compaction) = &compacted.compaction else {
        run.note(
            "compacted readback",
            "no block is flagged: the pyramid's top reads 0, and nothing is listed or read",
        );
        run.check(
            "compacted readback: bytes differing from the whole array (exact)",
            kit::bytes_differing(&compacted.array()?, source),
            0.0,
        );
        return Ok(None);
    };
    let array = compacted.array()?;
    let (list, gathered) = compacted.read()?;
    let (w, h) = compaction.list_size();
    let mut cpu_list: Vec<f32> = histogram_pyramid::cpu_list(&gpu_flags, blocks)
        .into_iter()
        .map(|b| b as f32)
        .collect();
    cpu_list.resize((w * h) as usize, -1.0);
    run.pass(
        "the list",
        "glsl/learn/readback-and-upload/pyramid_list.frag",
        &format!(
            "slot k walks the pyramid down to the k-th flagged block: {} slots in {w}x{h}, -1 \
             past the last; read back in one call",
            compaction.count()
        ),
        Some(PassBuffer::floats(w, h, 1, list.clone()).with_reference(cpu_list.clone())),
    );
    run.check_texels(
        "the list: slot k holds the k-th flagged block in the pyramid's order, as the CPU \
         compacts the same flags (exact)",
        Grid::new(w, h, 1).of("slot"),
        &list,
        &cpu_list,
        0.0,
    );
    run.pass(
        "gather the flagged blocks",
        "glsl/learn/readback-and-upload/gather_blocks.frag",
        "each slot's block copied into its tile of one small texture; read back in one call",
        Some(PassBuffer::floats(w * BLOCK, h * BLOCK, 4, gathered)),
    );
    run.check(
        "compacted readback: bytes differing from the whole array (exact)",
        kit::bytes_differing(&array, source),
        0.0,
    );
    let timed = compacted.measured(compacted.timed(ctx, runs)?);
    timed_note(run, "compacted readback: every pass and read", &timed.whole);
    timed_note(run, "compacted readback: its passes", &timed.passes);
    timed_note(run, "compacted readback: its three reads", &timed.reads);
    run.note(
        "bytes read: whole array / compacted",
        format!("{} / {}", source.len() * 4, timed.bytes),
    );
    Ok(Some(timed))
}

/// Compact the non-zero texels on the GPU; how many entries differ from the CPU's list.
fn compact_mismatches(ctx: &Context, source: &[f32]) -> anyhow::Result<usize> {
    let program = ComputeProgram::new(
        ctx,
        &[shader!("glsl/learn/readback-and-upload/compact.comp")],
    )?;
    let n = source.len() / 4;
    // region: compact
    let data = Buffer::from_slice(ctx, source, BufferUsage::Static)?;
    let indices = Buffer::new(ctx, n * 4, BufferUsage::GpuCopy)?;
    let values = Buffer::new(ctx, n * 16, BufferUsage::GpuCopy)?;
    let counter = AtomicCounters::new(ctx, 1)?;
    counter.reset()?;
    program
        .dispatch("compact")
        .storage(0, &data)
        .storage(1, &indices)
        .storage(2, &values)
        .counters(0, counter.buffer())
        .uniform("u_count", n as u32)
        .run_over(n as u32)?;
    // endregion
    crate::gl::memory_barrier(
        ctx,
        &[
            crate::gl::Barrier::BufferUpdate,
            crate::gl::Barrier::AtomicCounter,
        ],
    );
    let found = counter.read()?[0] as usize;
    let expected: Vec<(u32, [f32; 4])> = source
        .chunks_exact(4)
        .enumerate()
        .filter(|(_, v)| v.iter().any(|&x| x != 0.0))
        .map(|(i, v)| (i as u32, [v[0], v[1], v[2], v[3]]))
        .collect();
    if found > n {
        return Ok(expected.len().max(found));
    }
    let gpu_indices: Vec<u32> = indices.read_prefix(found)?;
    let gpu_values: Vec<[f32; 4]> = values.read_prefix(found)?;
    // The order of the list is the atomics' order: sort before comparing.
    let mut gpu: Vec<(u32, [f32; 4])> = gpu_indices.into_iter().zip(gpu_values).collect();
    gpu.sort_by_key(|e| e.0);
    let matching = gpu
        .iter()
        .zip(&expected)
        .filter(|(g, c)| g.0 == c.0 && bytemuck::bytes_of(&g.1) == bytemuck::bytes_of(&c.1))
        .count();
    Ok(expected.len().max(gpu.len()) - matching)
}

/// Paper 1, section 5.3: a 2048 x 2048 float colour buffer read back in 96.97 ms on a GeForce
/// 6800 over PCI Express (its reference [41]); taken as RGBA32F, 16 bytes a texel.
const PAPER1_READBACK: (f64, f64) = (2048.0 * 2048.0 * 16.0, 96.97);

/// What the readbacks measured warm, for [`Measured::explain`].
#[derive(Clone, Debug)]
struct Measured {
    software: bool,
    side: u32,
    /// Timed runs behind each median.
    runs: usize,
    whole_ms: f64,
    pbo_ms: f64,
    compacted: CompactTimed,
    bytes_full: usize,
}

impl Measured {
    /// The run's own medians explained: what the compacted readback cost against the whole
    /// one here and why, and what the same bytes would have cost on the bus of paper 1's GPU.
    fn explain(&self) -> String {
        let gb_s = |bytes: usize, ms: f64| bytes as f64 / (ms.max(1e-9) * 1e-3) / 1e9;
        let c = &self.compacted;
        let ratio = c.whole.median / self.whole_ms.max(1e-9);
        let mut out = format!(
            "This run, medians of {runs} runs after a warm-up: the whole {s}x{s} glReadPixels \
             moved {} bytes in {:.3} ms ({:.2} GB/s), through a PBO {:.3} ms. Compacted on the \
             GPU it took {:.3} ms, {ratio:.2}x the whole read: {:.3} ms of passes (the flags, \
             a pyramid of {} levels, the list of the {} flagged blocks of {}, the gather) and \
             {:.3} ms for three reads of {} bytes (the count, the list, the blocks' texels), \
             three calls however many blocks are flagged. Reading less {} here. ",
            self.bytes_full,
            self.whole_ms,
            gb_s(self.bytes_full, self.whole_ms),
            self.pbo_ms,
            c.whole.median,
            c.passes.median,
            c.levels,
            c.count,
            c.blocks,
            c.reads.median,
            c.bytes,
            if ratio < 1.0 { "won" } else { "lost" },
            runs = self.runs,
            s = self.side
        );
        out.push_str(if self.software {
            "On a software rasterizer the GPU's memory is the CPU's own: a readback is a \
             memcpy at memory speed with no bus to cross, so the bytes saved are cheap, while \
             every pass of the compaction is one more rasterization on the same CPU cores. "
        } else {
            "On a GPU the passes run in the GPU's own memory at its bandwidth, and what reading \
             less saves is bus time: the bytes that do not cross, and the calls, three whatever \
             the number of blocks (a read per flagged block would pay a call's fixed cost each). "
        });
        let (paper_bytes, paper_ms) = PAPER1_READBACK;
        let bus = paper_bytes / (paper_ms * 1e-3);
        let at_bus = |bytes: usize| bytes as f64 / bus * 1e3;
        let saved = self.bytes_full.saturating_sub(c.bytes);
        out.push_str(&format!(
            "Where reading less wins: on the buses of 2004-2007 (AGP, first PCI Express) a \
             readback was slow and stalled the pipeline until every queued pass had finished; \
             paper 1 (section 5.3) measured 96.97 ms for a 2048x2048 float colour buffer on a \
             GeForce 6800, about {:.2} GB/s. At that rate this run's whole array takes {:.3} \
             ms to cross the bus and the compacted reads {:.3} ms: the {saved} bytes saved are \
             worth {:.3} ms, against {:.3} ms of passes here. The sparser the data and the \
             larger the array, the more it saves: paper 1 reads its colliding pairs this way.",
            bus / 1e9,
            at_bus(self.bytes_full),
            at_bus(c.bytes),
            at_bus(saved),
            c.passes.median,
        ));
        out
    }
}

/// The sides `learn readback-and-upload --bench` times by default (square RGBA32F arrays).
pub const BENCH_SIDES: [u32; 4] = [128, 256, 512, 1024];
/// The largest side it takes.
pub const BENCH_MAX_SIDE: u32 = 4096;

/// One size of the readback bench.
#[derive(Clone, Debug, Serialize)]
pub struct ReadbackTimed {
    pub side: u32,
    pub bytes_full: usize,
    /// glReadPixels of the whole array into client memory (wall clock, glFinish before).
    pub full_ms: Spread,
    /// glReadPixels into a PBO, then reading the buffer (wall clock).
    pub pbo_ms: Spread,
    /// The compacted readback: its whole, its passes and its reads, in the same runs.
    pub compacted: CompactTimed,
    /// What the run's own numbers say (as the lesson's note "why these numbers").
    pub explanation: String,
}

/// Lesson 8's bench: the whole, the PBO and the compacted readback of sparse arrays.
#[derive(Clone, Debug, Serialize)]
pub struct ReadbackBench {
    pub renderer: String,
    pub runs: String,
    pub load: Option<Load>,
    pub block_share: f32,
    pub texel_share: f32,
    pub rows: Vec<ReadbackTimed>,
}

/// Time the whole readback, the PBO readback and the compacted readback of a `side x side`
/// sparse array for each of `sides`, each checked byte for byte first.
pub fn bench(ctx: &Context, sides: &[u32], runs: Runs) -> anyhow::Result<ReadbackBench> {
    for &side in sides {
        anyhow::ensure!(
            side % BLOCK == 0 && (BLOCK..=BENCH_MAX_SIDE).contains(&side),
            "--size {side}: lesson 8's bench takes the side of a square array, a multiple of \
             {BLOCK} from {BLOCK} to {BENCH_MAX_SIDE}"
        );
    }
    let before = Load::now();
    let mut rows = Vec::new();
    for &side in sides {
        let source = sparse_data(side);
        let bytes_full = source.len() * 4;
        let data = Texture::from_f32(ctx, side, side, TextureFormat::Rgba32F, &source)?;
        let target = Framebuffer::new(ctx, "data", &[&data], None)?;
        let pack = Buffer::new(ctx, bytes_full, BufferUsage::GpuCopy)?;
        let compacted = Compacted::new(ctx, &data)?;
        // Each path checked once before it is timed.
        let full = target.read_f32(0, target.rect())?;
        target.read_into_buffer(0, target.rect(), &pack, 0)?;
        let from_pbo: Vec<f32> = pack.read()?;
        let array = compacted.array()?;
        for (what, got) in [("whole", &full), ("PBO", &from_pbo), ("compacted", &array)] {
            let wrong = kit::bytes_differing(got, &source);
            anyhow::ensure!(
                wrong == 0.0,
                "the {what} readback of {side}x{side} differs from the array in {wrong} bytes"
            );
        }
        let full_ms = kit::time_finished(ctx, runs, || {
            target.read_f32(0, target.rect())?;
            Ok(())
        })?;
        let pbo_ms = kit::time_finished(ctx, runs, || {
            target.read_into_buffer(0, target.rect(), &pack, 0)?;
            pack.read::<f32>()?;
            Ok(())
        })?;
        let timed = compacted.measured(compacted.timed(ctx, runs)?);
        let measured = Measured {
            software: ctx.info().is_software(),
            side,
            runs: timed.whole.runs,
            whole_ms: full_ms.median,
            pbo_ms: pbo_ms.median,
            compacted: timed.clone(),
            bytes_full,
        };
        rows.push(ReadbackTimed {
            side,
            bytes_full,
            full_ms,
            pbo_ms,
            compacted: timed,
            explanation: measured.explain(),
        });
    }
    Ok(ReadbackBench {
        renderer: ctx.info().renderer_line(),
        runs: runs.in_words(),
        load: Load::worst(before, Load::now()),
        block_share: BLOCK_SHARE,
        texel_share: TEXEL_SHARE,
        rows,
    })
}

impl ReadbackBench {
    /// Plain text: a row per size, then what the largest size's numbers say.
    pub fn table(&self) -> String {
        let mut out = format!(
            "readback bench (lesson 8) on {}\n{}\nruns: {}, each path after one warm-up \
             run\ndata: square RGBA32F arrays, about {:.0}% of the {BLOCK}x{BLOCK} blocks \
             holding data in about {:.0}% of their texels; every path checked byte for byte \
             first; wall clock between glFinish calls. The compacted readback's passes and \
             reads are steps of its own runs, so neither is ever timed longer than it\n",
            self.renderer,
            self.load.map_or("load: unknown".into(), |l| format!(
                "load: {}",
                l.in_words()
            )),
            self.runs,
            self.block_share * 100.0,
            self.texel_share * 100.0
        );
        out.push_str(&format!(
            "{:>9} {:>10} {:>9} {:>13} {:>19} {:>19} {:>19} {:>19} {:>19}\n",
            "array",
            "bytes",
            "compacted",
            "blocks",
            "whole read ms",
            "PBO read ms",
            "compacted read ms",
            "of which passes",
            "of which reads"
        ));
        let cell = |s: &Spread| format!("{:.3} ({:.3}-{:.3})", s.median, s.min, s.max);
        for r in &self.rows {
            let c = &r.compacted;
            out.push_str(&format!(
                "{:>9} {:>10} {:>9} {:>13} {:>19} {:>19} {:>19} {:>19} {:>19}\n",
                format!("{0}x{0}", r.side),
                r.bytes_full,
                c.bytes,
                format!("{} of {}", c.count, c.blocks),
                cell(&r.full_ms),
                cell(&r.pbo_ms),
                cell(&c.whole),
                cell(&c.passes),
                cell(&c.reads)
            ));
        }
        out.push_str(
            "times: median (range) in ms; compacted: three reads (the count, the list, the \
             flagged blocks), however many blocks are flagged\n",
        );
        if let Some(last) = self.rows.last() {
            out.push_str("why these numbers (the largest array):\n");
            for line in crate::gl::picture::wrap(&last.explanation, 90) {
                out.push_str(&format!("  {line}\n"));
            }
        }
        out
    }
}
