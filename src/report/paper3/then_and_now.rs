//! Then and now for paper 3: the faithful render passes (one inner product per fragment, a
//! separate bias + sigmoid pass, layers chained through render-target textures) beside the
//! compute formulation (a tiled shared-memory product per layer, bias and sigmoid fused) and
//! the CPU forward pass, on the text detector's shape (121-30-1).

use super::super::then_and_now::{median, StageRow, ThenAndNow};
use super::super::BenchOptions;
use crate::mlp::compute::ComputeMlp;
use crate::mlp::cpu::{error_bound, forward, CpuProduct};
use crate::mlp::{Activation, Formulation, GpuMlp, Layer, Network};
use ndarray::{s, Array1, Array2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

const VERDICT: &str = "What compute no longer needs: a render target per product, the \
    separate bias + sigmoid pass (fused here), the texture-size bound on the batch with its \
    tiling, and the split of long inner products into passes; the product reuses each loaded \
    value 16 times from shared memory instead of fetching it again per fragment.";

/// A 121-30-1 sigmoid network and a batch of `l` windows.
fn workload(l: usize) -> (Network, Array2<f32>) {
    let mut rng = ChaCha8Rng::seed_from_u64(0x15);
    let layer = |rng: &mut ChaCha8Rng, n: usize, m: usize| Layer {
        weights: Array2::from_shape_simple_fn((m, n), || rng.gen_range(-0.2..0.2)),
        bias: Array1::from_shape_simple_fn(m, || rng.gen_range(-0.5..0.5)),
        activation: Activation::Sigmoid,
    };
    let net = Network::new(vec![layer(&mut rng, 121, 30), layer(&mut rng, 30, 1)])
        .expect("a valid network");
    let batch = Array2::from_shape_simple_fn((l, 121), || rng.gen_range(0.0..1.0));
    (net, batch)
}

pub fn measure(opts: &BenchOptions) -> anyhow::Result<ThenAndNow> {
    let l = if opts.quick { 1024 } else { 8192 };
    let rules = opts.runs(3);
    let (net, batch) = workload(l);
    let ctx = opts.gl;
    let gpu = GpuMlp::new(ctx)?;
    // warm-ups on the first vectors: they compile the shader variants and take llvmpipe's
    // first timer query, which need the same passes, not the whole batch
    let head = batch.slice(s![..l.min(256), ..]);
    let classic = gpu.load(&net, Formulation::Faithful)?;
    classic.forward(head, None)?;
    let mut c = (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut cpu = (Vec::new(), Vec::new(), Vec::new());
    let mut classic_out = None;
    rules.run(|_| -> anyhow::Result<()> {
        ctx.finish_all();
        let t = Instant::now();
        let r = classic.forward(batch.view(), None)?;
        c.4.push(t.elapsed().as_secs_f64() * 1e3);
        c.0.push(r.times.texture_creation);
        c.1.push(r.times.matmul);
        c.2.push(r.times.activation);
        c.3.push(r.times.readback);
        classic_out = Some(r.outputs);
        let t = Instant::now();
        let f = forward(CpuProduct::Plain, &net, batch.view());
        cpu.2.push(t.elapsed().as_secs_f64() * 1e3);
        cpu.0.push(f.product.as_secs_f64() * 1e3);
        cpu.1.push(f.activation.as_secs_f64() * 1e3);
        Ok(())
    })?;
    let runs = c.4.len();
    let workload_text = |compute_runs: Option<usize>| {
        format!(
            "a 121-30-1 sigmoid network on {l} input vectors (the detector's shape), median of \
             {runs} runs{}",
            compute_runs.map_or(String::new(), |k| format!(" ({k} of compute)"))
        )
    };
    let classic_rows = |compute: [Option<f64>; 5]| {
        vec![
            StageRow::new(
                "upload (texture creation)",
                Some(median(c.0.clone())),
                compute[0],
                None,
            ),
            StageRow::new(
                "matrix product",
                Some(median(c.1.clone())),
                compute[1],
                Some(median(cpu.0.clone())),
            ),
            StageRow::new(
                "bias + sigmoid (fused in compute)",
                Some(median(c.2.clone())),
                compute[2],
                Some(median(cpu.1.clone())),
            ),
            StageRow::new("readback", Some(median(c.3.clone())), compute[3], None),
            StageRow::new(
                "frame (the whole batch)",
                Some(median(c.4.clone())),
                compute[4],
                Some(median(cpu.2.clone())),
            ),
        ]
    };
    if let Err(e) = ctx.require_compute("the compute formulation") {
        let mut out = ThenAndNow::unavailable(workload_text(None), e.to_string(), VERDICT);
        out.stages = classic_rows([None; 5]);
        return Ok(out);
    }
    let mlp = ComputeMlp::new(ctx)?;
    let loaded = mlp.load(&net)?;
    loaded.forward(head)?;
    let mut k = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut compute_out = None;
    rules.run(|_| -> anyhow::Result<()> {
        ctx.finish_all();
        let t = Instant::now();
        let r = loaded.forward(batch.view())?;
        k.3.push(t.elapsed().as_secs_f64() * 1e3);
        k.0.push(r.times.texture_creation);
        k.1.push(r.times.matmul);
        k.2.push(r.times.readback);
        compute_out = Some(r.outputs);
        Ok(())
    })?;
    let compute_runs = k.3.len();
    let bound = error_bound(&net, batch.view());
    let same = match (classic_out, compute_out) {
        (Some(a), Some(b)) => a
            .iter()
            .zip(b.iter())
            .zip(bound.iter())
            .all(|((x, y), e)| (x - y).abs() <= 2.0 * e),
        _ => false,
    };
    Ok(ThenAndNow {
        workload: workload_text((compute_runs != runs).then_some(compute_runs)),
        unavailable: None,
        stages: classic_rows([
            Some(median(k.0)),
            Some(median(k.1)),
            None,
            Some(median(k.2)),
            Some(median(k.3)),
        ]),
        same_answer: Some(same),
        verdict: VERDICT.into(),
    })
}
