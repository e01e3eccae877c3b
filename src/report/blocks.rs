//! The shared building blocks, measured: ping-pong reduction against reading the whole
//! buffer back and summing on the CPU (the trade-off behind paper 4 section 3.3 and paper 1
//! section 5.3), on the renderer at hand.

use super::{BenchOptions, Claim, Fidelity, Figure, Section, Table};
use crate::gl::reduce::{passes_for, ReduceOp, Reducer};
use crate::gl::{query, Framebuffer, Rect, Texture, TextureFormat};
use crate::report::plot::{Plot, Series};
use serde_json::json;
use std::time::Instant;

/// One size measured both ways.
#[derive(Clone, Debug, serde::Serialize)]
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

/// Sum an n x n RGBA32F texture both ways, `repeats` times each, keeping the best time.
pub fn measure(opts: &BenchOptions, size: u32, repeats: usize) -> anyhow::Result<ReductionRun> {
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

pub fn run(opts: &BenchOptions) -> anyhow::Result<Section> {
    let sizes: &[u32] = if opts.quick {
        &[32, 128, 256]
    } else {
        &[32, 128, 512, 1024, 2048]
    };
    let repeats = if opts.quick { 2 } else { 5 };
    let bar = opts
        .progress
        .add(indicatif::ProgressBar::new(sizes.len() as u64));
    bar.set_message("building blocks: reduction vs readback");
    let mut runs = Vec::new();
    for &size in sizes {
        runs.push(measure(opts, size, repeats)?);
        bar.inc(1);
    }
    bar.finish_and_clear();
    let renderer = opts.gl.info().renderer_line();
    let table = Table {
        caption: format!("Sum of an n x n RGBA32F buffer ({renderer}), best of {repeats}"),
        header: [
            "n",
            "passes",
            "reduce GPU ms",
            "reduce wall ms",
            "readback wall ms",
            "readback / reduce",
            "bytes read (reduce)",
            "bytes read (readback)",
            "rel. diff",
        ]
        .map(String::from)
        .to_vec(),
        rows: runs
            .iter()
            .map(|r| {
                vec![
                    r.size.to_string(),
                    r.passes.to_string(),
                    format!("{:.3}", r.reduce_gpu_ms),
                    format!("{:.3}", r.reduce_wall_ms),
                    format!("{:.3}", r.readback_wall_ms),
                    format!("{:.2}", r.readback_wall_ms / r.reduce_wall_ms),
                    r.reduce_bytes.to_string(),
                    r.readback_bytes.to_string(),
                    format!("{:.1e}", r.relative_difference),
                ]
            })
            .collect(),
    };
    let figure = "blocks_reduction.png";
    Plot {
        title: format!(
            "Sum reduction vs full readback ({})",
            opts.gl.info().renderer
        ),
        x_label: "n (n x n RGBA32F texels)".into(),
        y_label: "wall clock ms".into(),
        log_x: true,
        log_y: true,
        series: vec![
            Series::new(
                "ping-pong reduction",
                runs.iter()
                    .map(|r| (r.size as f64, r.reduce_wall_ms))
                    .collect(),
            ),
            Series::new(
                "readback + CPU sum",
                runs.iter()
                    .map(|r| (r.size as f64, r.readback_wall_ms))
                    .collect(),
            ),
        ],
    }
    .write_png(&opts.out_dir.join(figure))?;
    let largest = runs.last().expect("at least one size");
    Ok(Section {
        id: "blocks".into(),
        title: "Shared building blocks: ping-pong reduction".into(),
        summary: format!(
            "Reducing an n x n buffer to one value on the GPU in log2 n passes, against reading \
             every texel back and summing on the CPU. On a discrete GPU the readback crosses a \
             bus; on a software renderer it is a memory copy, so the time ratio says which \
             side of that trade-off this machine is on. Renderer: {renderer}."
        ),
        tables: vec![table],
        claims: vec![Claim {
            claim: "Reduction reads back a single texel instead of the whole buffer".into(),
            paper: "paper 4, section 3.3 (readback latency motivates buffer reduction)".into(),
            measured: format!(
                "{} bytes instead of {} at n = {}; time ratio readback/reduce {:.2}",
                largest.reduce_bytes,
                largest.readback_bytes,
                largest.size,
                largest.readback_wall_ms / largest.reduce_wall_ms
            ),
            holds: Some(largest.relative_difference < 1e-4),
        }],
        figures: vec![Figure {
            file: figure.into(),
            caption: "Wall clock of the two ways to sum a buffer, by size".into(),
        }],
        fidelity: vec![
            Fidelity {
                feature: "ping-pong render-to-texture reduction, 2x2 per pass".into(),
                paper: "paper 4 section 3.3, Fig. 2; paper 1 section 5.3".into(),
                code: "src/gl/reduce.rs, glsl/gl/reduce.frag".into(),
            },
            Fidelity {
                feature: "GL timer query (TIME_ELAPSED) for GPU pass time".into(),
                paper: "(measurement)".into(),
                code: "src/gl/query.rs".into(),
            },
        ],
        results: json!({ "reduction": runs }),
    })
}
