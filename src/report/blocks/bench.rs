//! The measurement: one RGBA32F buffer per size, summed both ways.

use crate::gl::reduce::{passes_for, ReduceOp, Reducer};
use crate::gl::{query, Framebuffer, Rect, Texture, TextureFormat};
use crate::report::BenchOptions;
use serde::Serialize;
use std::time::Instant;

/// Everything the section measures.
#[derive(Clone, Debug, Serialize)]
pub struct BlocksResults {
    /// One entry per buffer size, smallest first.
    pub reduction: Vec<ReductionRun>,
}

/// One size measured both ways.
#[derive(Clone, Debug, Serialize)]
pub struct ReductionRun {
    pub size: u32,
    pub passes: u32,
    /// GPU time of the reduction passes (timer query).
    pub reduce_gpu_ms: f64,
    /// Wall clock of the reduction including its one-texel readback.
    pub reduce_wall_ms: f64,
    /// Wall clock of reading every texel back and summing on the CPU.
    pub readback_wall_ms: f64,
    pub reduce_bytes: usize,
    pub readback_bytes: usize,
    /// Relative difference of the two sums.
    pub relative_difference: f64,
}

/// Repeats per size, the best time kept: `--runs` when given, else 2 under `--quick` and 5.
pub fn repeats(opts: &BenchOptions) -> usize {
    match opts.runs {
        Some(n) => n,
        None if opts.quick => 2,
        None => 5,
    }
}

pub fn measure(opts: &BenchOptions) -> anyhow::Result<BlocksResults> {
    // region: workload sizes
    let sizes: &[u32] = if opts.quick {
        &[32, 128, 256]
    } else {
        &[32, 128, 512, 1024, 2048]
    };
    // endregion
    let bar = opts
        .progress
        .add(indicatif::ProgressBar::new(sizes.len() as u64));
    bar.set_message("building blocks: reduction vs readback");
    let mut reduction = Vec::new();
    for &size in sizes {
        reduction.push(measure_size(opts, size, repeats(opts))?);
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(BlocksResults { reduction })
}

/// Sum an n x n RGBA32F texture both ways, `repeats` times each, keeping the best time.
pub fn measure_size(
    opts: &BenchOptions,
    size: u32,
    repeats: usize,
) -> anyhow::Result<ReductionRun> {
    let ctx = opts.gl;
    let data: Vec<f32> = (0..size * size * 4)
        .map(|i| ((i * 7919) % 1000) as f32 * 1e-3)
        .collect();
    let texture = Texture::from_f32(ctx, size, size, TextureFormat::Rgba32F, &data)?;
    let reducer = Reducer::new(ctx, size, size)?;
    let framebuffer = Framebuffer::new(ctx, "readback source", &[&texture], None)?;
    let (mut reduce_gpu, mut reduce_wall, mut readback_wall) = (f64::MAX, f64::MAX, f64::MAX);
    let (mut gpu_sum, mut cpu_sum) = (0.0, 0.0);
    for _ in 0..repeats {
        ctx.finish_all();
        let start = Instant::now();
        let (sum, gpu_ms) = query::time_gpu(ctx, || reducer.reduce(&texture, ReduceOp::Sum))?;
        reduce_wall = reduce_wall.min(start.elapsed().as_secs_f64() * 1e3);
        reduce_gpu = reduce_gpu.min(gpu_ms);
        gpu_sum = sum[0] as f64;
        ctx.finish_all();
        let start = Instant::now();
        let texels = framebuffer.read_f32(0, Rect::sized(size, size))?;
        cpu_sum = texels.iter().step_by(4).map(|&v| v as f64).sum::<f64>();
        readback_wall = readback_wall.min(start.elapsed().as_secs_f64() * 1e3);
    }
    Ok(ReductionRun {
        size,
        passes: passes_for(size, size),
        reduce_gpu_ms: reduce_gpu,
        reduce_wall_ms: reduce_wall,
        readback_wall_ms: readback_wall,
        reduce_bytes: 16,
        readback_bytes: (size * size * 16) as usize,
        relative_difference: (gpu_sum - cpu_sum).abs() / cpu_sum.abs().max(1e-30),
    })
}
