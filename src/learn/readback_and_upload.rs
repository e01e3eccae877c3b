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
        let source = sparse_data();
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
        timed(
            &mut run,
            "glReadPixels into client memory, whole array",
            wall_ms(start),
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
        let (flags_texture, read_back, bytes_read, flag_ms) = reduced_readback(ctx, &direct)?;
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

/// `SIDE x SIDE` RGBA texels, about [`DENSITY`] of them not zero.
fn sparse_data() -> Vec<f32> {
    let n = (SIDE * SIDE) as usize;
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
    data: &Texture,
) -> anyhow::Result<(Texture, Vec<f32>, usize, Option<f64>)> {
    let program = Program::rect(
        ctx,
        &[shader!("glsl/learn/readback-and-upload/block_flags.frag")],
    )?;
    // region: block-flags
    let side = SIDE / BLOCK;
    let flags = Texture::new_2d(ctx, side, side, TextureFormat::R32F)?;
    let flags_target = Framebuffer::new(ctx, "block flags", &[&flags], None)?;
    let timer = TimerQuery::new(ctx)?;
    timer.begin();
    flags_target
        .pass(&program, "block flags")?
        .texture("u_data", data)
        .uniform("u_block", BLOCK as i32)
        .draw_full()?;
    timer.end();
    let flag_values = flags_target.read_f32(0, flags_target.rect())?;
    // endregion
    let mut bytes_read = flag_values.len() * 4;
    let source = Framebuffer::new(ctx, "data", &[data], None)?;
    let mut out = vec![0f32; (SIDE * SIDE * 4) as usize];
    // region: read-blocks
    for (b, _) in flag_values.iter().enumerate().filter(|(_, &f)| f > 0.5) {
        let (bx, by) = (b as u32 % side * BLOCK, b as u32 / side * BLOCK);
        let block = source.read_f32(0, Rect::new(bx, by, BLOCK, BLOCK))?;
        // endregion
        bytes_read += block.len() * 4;
        for (row, texels) in block.chunks_exact((BLOCK * 4) as usize).enumerate() {
            let at = (((by + row as u32) * SIDE + bx) * 4) as usize;
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
