//! Then and now for paper 4: the classic peeling path (integrand fragments, depth peels,
//! ping-pong reduction) beside the compute path (one pass over the triangles, shared-memory
//! reduction) and Mirtich's analytic method on the CPU, on the paper's torus.

use super::super::then_and_now::{median, StageRow, ThenAndNow};
use super::super::BenchOptions;
use crate::mass::compute::ComputeMass;
use crate::mass::gpu::GpuMass;
use crate::mass::{analytic, models, MassProperties};
use std::time::Instant;

const VERDICT: &str = "What compute no longer needs: the orthographic framing, the \
    resolution, the depth peeling with its occlusion query per layer and the per-pixel fp32 \
    integrands; the divergence theorem is summed per triangle, exactly, and the reduction \
    keeps 512 values per work group in shared memory instead of one 8x8 pass per level. What \
    the peeling bought in 2006 (a scatter-free way to visit every layer of a non-convex body) \
    is worth nothing here: the compute sum is exact where the peeled one carries resolution \
    error.";

/// Measure the torus at the section's middle resolution.
pub fn measure(opts: &BenchOptions) -> anyhow::Result<ThenAndNow> {
    let resolution = if opts.quick { 64 } else { 128 };
    let runs = if opts.quick { 3 } else { 7 };
    let mesh = models::paper_object("torus")
        .ok_or_else(|| anyhow::anyhow!("the paper's torus is missing"))?;
    let workload = format!(
        "the paper's torus ({} triangles), classic at {resolution}x{resolution}, median of {runs} \
         runs",
        mesh.triangles.len()
    );
    let ctx = opts.gl;
    let classic = GpuMass::new(ctx, resolution)?;
    classic.integrate(&mesh, None, None)?;
    let (mut classic_gpu, mut classic_wall, mut cpu) = (Vec::new(), Vec::new(), Vec::new());
    let mut classic_result = None;
    for _ in 0..runs {
        ctx.finish_all();
        let t = Instant::now();
        let r = classic.integrate(&mesh, None, None)?;
        classic_wall.push(t.elapsed().as_secs_f64() * 1e3);
        classic_gpu.push(r.gpu_ms);
        classic_result = Some(r);
        let t = Instant::now();
        let exact = analytic::volume_integrals(&mesh);
        cpu.push(t.elapsed().as_secs_f64() * 1e3);
        std::hint::black_box(exact);
    }
    if let Err(e) = ctx.require_compute("the compute formulation") {
        let mut out = ThenAndNow::unavailable(workload, e.to_string(), VERDICT);
        out.stages = vec![
            StageRow::new(
                "integrands + peels + reduction",
                Some(median(classic_gpu)),
                None,
                None,
            ),
            StageRow::new(
                "frame (one body)",
                Some(median(classic_wall)),
                None,
                Some(median(cpu)),
            ),
        ];
        return Ok(out);
    }
    let compute = ComputeMass::new(ctx)?;
    compute.integrate(&[&mesh])?;
    let (mut compute_gpu, mut compute_wall) = (Vec::new(), Vec::new());
    let mut compute_result = None;
    for _ in 0..runs {
        ctx.finish_all();
        let t = Instant::now();
        let r = compute.integrate(&[&mesh])?;
        compute_wall.push(t.elapsed().as_secs_f64() * 1e3);
        compute_gpu.push(r.gpu_ms);
        compute_result = Some(r);
    }
    // The same mass properties: the classic path within its resolution error (Fig. 4's 5%
    // bound at 32x32, far less here), the compute path within fp32 of Mirtich.
    let exact = MassProperties::from_integrals(&analytic::volume_integrals(&mesh), 1.0);
    let worst = |m: MassProperties| {
        m.relative_errors(&exact)
            .iter()
            .cloned()
            .fold(0.0, f64::max)
    };
    let classic_err = classic_result.map_or(1.0, |r| {
        worst(MassProperties::from_integrals(&r.integrals, 1.0))
    });
    let compute_err = compute_result.map_or(1.0, |r| {
        worst(MassProperties::from_integrals(&r.integrals[0], 1.0))
    });
    Ok(ThenAndNow {
        workload: format!(
            "{workload}; worst relative error against Mirtich: classic {classic_err:.1e}, \
             compute {compute_err:.1e}"
        ),
        unavailable: None,
        stages: vec![
            StageRow::new(
                "integrals (peels + 8x8 reduction / triangle terms + shared-memory reduction)",
                Some(median(classic_gpu)),
                Some(median(compute_gpu)),
                Some(median(cpu.clone())),
            ),
            StageRow::new(
                "frame (one body)",
                Some(median(classic_wall)),
                Some(median(compute_wall)),
                Some(median(cpu)),
            ),
        ],
        same_answer: Some(classic_err < 0.05 && compute_err < 1e-4),
        verdict: VERDICT.into(),
    })
}
