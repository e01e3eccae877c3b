//! Lesson 8, moving data between the CPU and the GPU: an upload from client memory and one
//! through a pixel unpack buffer (PBO); a readback with glReadPixels, one into a pixel pack
//! buffer, and a small reduced readback that reads only the blocks holding data (paper 1's
//! hierarchical readback, section 5.3.1). Every path is checked byte for byte. Where the
//! pipeline stalls: a glReadPixels into client memory waits for every queued pass; a read
//! into a PBO is queued like a pass and the CPU waits only when it maps the buffer. The
//! times of each path go into the notes with the renderer (never into a check).

use super::kit;
use super::{Exercise, Lesson, LessonInfo, LessonOptions, LessonRun, PaperStep};
use crate::gl::{
    AtomicCounters, Buffer, BufferUsage, ComputeProgram, Context, Framebuffer, Program, Rect,
    Texture, TextureFormat, TimerQuery,
};
use crate::shader;
use crate::timing::{Load, Runs, Spread};
use serde::Serialize;
use std::time::Instant;

const SIDE: u32 = 128;
const BLOCK: u32 = 8;
/// The share of texels that hold data.
const DENSITY: f32 = 0.01;

static INFO: LessonInfo = LessonInfo {
    id: "readback-and-upload",
    number: 8,
    title: "Readback and upload: glReadPixels, pixel buffers, and reading less",
    idea: "Data crosses the bus twice: up as texture uploads, down as readbacks. An upload \
           from client memory copies before it returns; through a pixel unpack buffer (PBO) \
           the copy is queued. glReadPixels into client memory stalls the CPU until every \
           queued pass is done; into a pixel pack buffer it is queued too, and the CPU waits \
           only when it maps the buffer. The cheapest readback reads less: a pass reduces the \
           array to one flag per block, the CPU reads the flags and then only the blocks \
           that hold data.",
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
        let source = sparse_data(SIDE);
        let bytes = source.len() * 4;
        let renderer = run.renderer.clone();
        let timed = |run: &mut LessonRun, what: &str, ms: f64| {
            run.notes
                .push((format!("{what} (ms, {renderer})"), format!("{ms:.3}")));
        };

        // Uploads.
        let direct = Texture::new_2d(ctx, SIDE, SIDE, TextureFormat::Rgba32F)?;
        let start = Instant::now();
        direct.upload_f32(&source)?;
        timed(
            &mut run,
            "upload from client memory: the call",
            wall_ms(start),
        );
        let picture = Some(kit::buffer(&direct)?);
        run.pass(
            "upload (client memory)",
            "",
            "glTexSubImage2D from the CPU's array",
            picture,
        );
        run.check(
            "upload from client memory: bytes differing after download (exact)",
            kit::bytes_differing(&direct.download_f32()?, &source),
            0.0,
        );
        // region: upload-pbo
        let through_pbo = Texture::new_2d(ctx, SIDE, SIDE, TextureFormat::Rgba32F)?;
        let unpack = Buffer::from_slice(ctx, &source, BufferUsage::Dynamic)?;
        let start = Instant::now();
        through_pbo.upload_from_buffer(&unpack, 0)?;
        // endregion
        timed(
            &mut run,
            "upload from a PBO: the call (queued)",
            wall_ms(start),
        );
        run.pass(
            "upload (PBO)",
            "",
            "glTexSubImage2D from a pixel unpack buffer",
            None,
        );
        run.check(
            "upload through a PBO: bytes differing after download (exact)",
            kit::bytes_differing(&through_pbo.download_f32()?, &source),
            0.0,
        );

        // Readbacks of the whole array.
        // region: full-readback
        let target = Framebuffer::new(ctx, "data", &[&direct], None)?;
        ctx.finish_all();
        let start = Instant::now();
        let full = target.read_f32(0, target.rect())?;
        // endregion
        let full_ms = wall_ms(start);
        timed(
            &mut run,
            "glReadPixels into client memory, whole array",
            full_ms,
        );
        run.pass(
            "glReadPixels",
            "",
            "the whole array into client memory: the CPU waits",
            None,
        );
        run.check(
            "glReadPixels: bytes differing from the uploaded array (exact)",
            kit::bytes_differing(&full, &source),
            0.0,
        );
        let pack = Buffer::new(ctx, bytes, BufferUsage::GpuCopy)?;
        let start = Instant::now();
        target.read_into_buffer(0, target.rect(), &pack, 0)?;
        timed(
            &mut run,
            "glReadPixels into a PBO: the call (queued)",
            wall_ms(start),
        );
        let start = Instant::now();
        let from_pbo: Vec<f32> = pack.read()?;
        timed(
            &mut run,
            "reading the PBO: where the CPU waits",
            wall_ms(start),
        );
        run.pass(
            "glReadPixels into a PBO",
            "",
            "queued; the CPU waits only when it reads the buffer",
            None,
        );
        run.check(
            "PBO readback: bytes differing from the uploaded array (exact)",
            kit::bytes_differing(&from_pbo, &source),
            0.0,
        );

        // The reduced readback: flags per block, then only the flagged blocks.
        let flags_program = Program::rect(
            ctx,
            &[shader!("glsl/learn/readback-and-upload/block_flags.frag")],
        )?;
        ctx.finish_all();
        let start = Instant::now();
        let (flags_texture, read_back, bytes_read, flag_ms) =
            reduced_readback(ctx, &flags_program, &direct, SIDE)?;
        let reduced_ms = wall_ms(start);
        timed(
            &mut run,
            "reduced readback: flags pass, flags and flagged blocks read",
            reduced_ms,
        );
        let picture = Some(kit::buffer(&flags_texture)?);
        run.pass(
            "block flags",
            "glsl/learn/readback-and-upload/block_flags.frag",
            "one texel per 8x8 block: 1 where the block holds data",
            picture,
        );
        run.pass(
            "read the flagged blocks",
            "",
            "the flags, then glReadPixels of each flagged block",
            None,
        );
        if let Some(ms) = flag_ms {
            timed(&mut run, "block-flag pass, GL timer query", ms);
        }
        run.notes.push((
            "bytes read: whole array / flags and flagged blocks".into(),
            format!("{bytes} / {bytes_read}"),
        ));
        let measured = Measured {
            software: is_software(&run.renderer),
            side: SIDE,
            full_ms: full_ms.max(0.0),
            reduced_ms,
            flags_ms: flag_ms,
            bytes_full: bytes,
            bytes_reduced: bytes_read,
        };
        run.note("why these numbers", measured.explain());
        run.check(
            "reduced readback: bytes differing from the whole array (exact)",
            kit::bytes_differing(&read_back, &source),
            0.0,
        );

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

fn wall_ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}

/// `side x side` RGBA texels, about [`DENSITY`] of them not zero.
fn sparse_data(side: u32) -> Vec<f32> {
    let n = (side * side) as usize;
    let pick = kit::values(n, 8);
    let content = kit::values(3 * n, 80);
    (0..n)
        .flat_map(|i| {
            if pick[i] < DENSITY {
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

/// The flags pass, then a read of the flags and of each flagged block: the flags texture, the
/// array put together from the blocks read (zeros elsewhere), the bytes read, the pass's time.
fn reduced_readback(
    ctx: &Context,
    program: &Program,
    data: &Texture,
    data_side: u32,
) -> anyhow::Result<(Texture, Vec<f32>, usize, Option<f64>)> {
    // region: block-flags
    let side = data_side / BLOCK;
    let flags = Texture::new_2d(ctx, side, side, TextureFormat::R32F)?;
    let flags_target = Framebuffer::new(ctx, "block flags", &[&flags], None)?;
    let timer = TimerQuery::new(ctx)?;
    timer.begin();
    flags_target
        .pass(program, "block flags")?
        .texture("u_data", data)
        .uniform("u_block", BLOCK as i32)
        .draw_full()?;
    timer.end();
    let flag_values = flags_target.read_f32(0, flags_target.rect())?;
    // endregion
    let mut bytes_read = flag_values.len() * 4;
    let source = Framebuffer::new(ctx, "data", &[data], None)?;
    let mut out = vec![0f32; (data_side * data_side * 4) as usize];
    // region: read-blocks
    for (b, _) in flag_values.iter().enumerate().filter(|(_, &f)| f > 0.5) {
        let (bx, by) = (b as u32 % side * BLOCK, b as u32 / side * BLOCK);
        let block = source.read_f32(0, Rect::new(bx, by, BLOCK, BLOCK))?;
        // endregion
        bytes_read += block.len() * 4;
        for (row, texels) in block.chunks_exact((BLOCK * 4) as usize).enumerate() {
            let at = (((by + row as u32) * data_side + bx) * 4) as usize;
            out[at..at + texels.len()].copy_from_slice(texels);
        }
    }
    Ok((flags, out, bytes_read, timer.milliseconds().ok()))
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

/// Whether `renderer` is one of Mesa's software rasterizers (the "GPU" is the CPU).
fn is_software(renderer: &str) -> bool {
    let r = renderer.to_lowercase();
    ["llvmpipe", "softpipe", "swrast"]
        .iter()
        .any(|s| r.contains(s))
}

/// Paper 1, section 5.3: a 2048 x 2048 float colour buffer read back in 96.97 ms on a GeForce
/// 6800 over PCI Express (its reference [41]); taken as RGBA32F, 16 bytes a texel.
const PAPER1_READBACK: (f64, f64) = (2048.0 * 2048.0 * 16.0, 96.97);

/// What one run of the readbacks measured, for [`Measured::explain`].
#[derive(Clone, Copy, Debug)]
struct Measured {
    software: bool,
    side: u32,
    full_ms: f64,
    reduced_ms: f64,
    flags_ms: Option<f64>,
    bytes_full: usize,
    bytes_reduced: usize,
}

impl Measured {
    /// The run's own numbers explained: why the reduced readback cost what it did here, and
    /// what the same bytes would have cost on the bus of paper 1's GPU.
    fn explain(&self) -> String {
        let gb_s = |bytes: usize, ms: f64| bytes as f64 / (ms.max(1e-9) * 1e-3) / 1e9;
        let flag_bytes = (self.side / BLOCK).pow(2) as usize * 4;
        let blocks = self.bytes_reduced.saturating_sub(flag_bytes) / (BLOCK * BLOCK * 16) as usize;
        let flags = self.flags_ms.map_or(String::new(), |f| {
            format!(", of which the flags pass alone took {f:.3} ms (timer query)")
        });
        let mut out = format!(
            "This run: the whole {s}x{s} glReadPixels moved {} bytes in {:.3} ms ({:.2} GB/s); \
             the reduced readback read {} bytes (the flags and {blocks} flagged blocks) in \
             {:.3} ms, {:.1}x the whole read{flags}. ",
            self.bytes_full,
            self.full_ms,
            gb_s(self.bytes_full, self.full_ms),
            self.bytes_reduced,
            self.reduced_ms,
            self.reduced_ms / self.full_ms.max(1e-9),
            s = self.side
        );
        out.push_str(if self.software {
            "On a software rasterizer the GPU's memory is the CPU's own: a readback is a \
             memcpy at memory speed, with no bus and no pipeline to wait for, while the flags \
             pass is one more full rasterization run on the CPU cores (a draw, a fragment per \
             block, its texel fetches through the shader) and every flagged block is one more \
             glReadPixels call with its own fixed cost. The extra pass and the extra calls \
             cost more than the bytes they save. "
        } else {
            "On a GPU the flags pass runs on the GPU's own memory, and what reading less saves \
             is bus time and the wait for the pipeline to drain, once per glReadPixels call. "
        });
        let (paper_bytes, paper_ms) = PAPER1_READBACK;
        let bus = paper_bytes / (paper_ms * 1e-3);
        let at_bus = |bytes: usize| bytes as f64 / bus * 1e3;
        let saved = self.bytes_full.saturating_sub(self.bytes_reduced);
        out.push_str(&format!(
            "Where reading less wins: on the buses of 2004-2007 (AGP, first PCI Express) a \
             readback was slow and stalled the pipeline until every queued pass had finished; \
             paper 1 (section 5.3) measured 96.97 ms for a 2048x2048 float colour buffer on a \
             GeForce 6800, about {:.2} GB/s. At that rate this run's whole array takes {:.3} \
             ms to cross the bus and the flags and flagged blocks {:.3} ms: the {saved} bytes \
             saved are worth {:.3} ms, and reading less wins when the flags pass and the \
             {blocks} extra reads cost less than that. The sparser the data and the larger \
             the array, the more it saves: paper 1 reads its colliding pairs this way.",
            bus / 1e9,
            at_bus(self.bytes_full),
            at_bus(self.bytes_reduced),
            at_bus(saved),
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
    pub bytes_reduced: usize,
    /// glReadPixels of the whole array into client memory (wall clock, glFinish before).
    pub full_ms: Spread,
    /// glReadPixels into a PBO, then mapping it (wall clock).
    pub pbo_ms: Spread,
    /// The flags pass, the flags read, each flagged block read (wall clock).
    pub reduced_ms: Spread,
    /// The flags pass alone (its timer query).
    pub flags_pass_ms: Spread,
    /// What the run's own numbers say (see the lesson's note "why these numbers").
    pub explanation: String,
}

/// Lesson 8's bench: the three readbacks of sparse arrays over sizes.
#[derive(Clone, Debug, Serialize)]
pub struct ReadbackBench {
    pub renderer: String,
    pub runs: String,
    pub load: Option<Load>,
    pub density: f32,
    pub rows: Vec<ReadbackTimed>,
}

/// Time the whole readback, the PBO readback and the reduced readback of a `side x side`
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
    let program = Program::rect(
        ctx,
        &[shader!("glsl/learn/readback-and-upload/block_flags.frag")],
    )?;
    let renderer = ctx.info().renderer_line();
    let mut rows = Vec::new();
    for &side in sides {
        let source = sparse_data(side);
        let bytes_full = source.len() * 4;
        let data = Texture::from_f32(ctx, side, side, TextureFormat::Rgba32F, &source)?;
        let target = Framebuffer::new(ctx, "data", &[&data], None)?;
        let pack = Buffer::new(ctx, bytes_full, BufferUsage::GpuCopy)?;
        // Each path checked once before it is timed.
        let full = target.read_f32(0, target.rect())?;
        target.read_into_buffer(0, target.rect(), &pack, 0)?;
        let from_pbo: Vec<f32> = pack.read()?;
        let (_, reduced, bytes_reduced, _) = reduced_readback(ctx, &program, &data, side)?;
        for (what, got) in [("whole", &full), ("PBO", &from_pbo), ("reduced", &reduced)] {
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
        let mut flags = Vec::new();
        let reduced_ms = kit::time_finished(ctx, runs, || {
            let (_, _, _, ms) = reduced_readback(ctx, &program, &data, side)?;
            flags.extend(ms);
            Ok(())
        })?;
        let flags_pass_ms = Spread::of(&flags);
        let measured = Measured {
            software: is_software(&renderer),
            side,
            full_ms: full_ms.median,
            reduced_ms: reduced_ms.median,
            flags_ms: (flags_pass_ms.runs > 0).then_some(flags_pass_ms.median),
            bytes_full,
            bytes_reduced,
        };
        rows.push(ReadbackTimed {
            side,
            bytes_full,
            bytes_reduced,
            full_ms,
            pbo_ms,
            reduced_ms,
            flags_pass_ms,
            explanation: measured.explain(),
        });
    }
    Ok(ReadbackBench {
        renderer,
        runs: runs.in_words(),
        load: Load::worst(before, Load::now()),
        density: DENSITY,
        rows,
    })
}

impl ReadbackBench {
    /// Plain text: a row per size, then what the largest size's numbers say.
    pub fn table(&self) -> String {
        let mut out = format!(
            "readback bench (lesson 8) on {}\n{}\nruns: {}\ndata: square RGBA32F arrays, \
             about {:.0}% of texels not zero; every path checked byte for byte first; wall \
             clock between glFinish calls, the flags pass by its timer query\n",
            self.renderer,
            self.load.map_or("load: unknown".into(), |l| format!(
                "load: {}",
                l.in_words()
            )),
            self.runs,
            self.density * 100.0
        );
        out.push_str(&format!(
            "{:>9} {:>10} {:>10} {:>19} {:>19} {:>19} {:>19}\n",
            "array",
            "bytes",
            "reduced",
            "whole read ms",
            "PBO read ms",
            "reduced read ms",
            "flags pass ms"
        ));
        let cell = |s: &Spread| format!("{:.3} ({:.3}-{:.3})", s.median, s.min, s.max);
        for r in &self.rows {
            out.push_str(&format!(
                "{:>9} {:>10} {:>10} {:>19} {:>19} {:>19} {:>19}\n",
                format!("{0}x{0}", r.side),
                r.bytes_full,
                r.bytes_reduced,
                cell(&r.full_ms),
                cell(&r.pbo_ms),
                cell(&r.reduced_ms),
                cell(&r.flags_pass_ms)
            ));
        }
        out.push_str("times: median (range) in ms\n");
        if let Some(last) = self.rows.last() {
            out.push_str("why these numbers (the largest array):\n");
            for line in crate::gl::picture::wrap(&last.explanation, 90) {
                out.push_str(&format!("  {line}\n"));
            }
        }
        out
    }
}
