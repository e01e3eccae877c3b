//! Paper 1 on its own GPU, the GeForce 7800 GTX: one frame of a Table III scene (small) run
//! under the chip's limits beside the same frame today, and the pairs of both against the
//! CPU's brute force.

use crate::collide::brute_force::all_pairs;
use crate::collide::compute_pipeline::ComputeCollider;
use crate::collide::pipeline::{Options, StreamingCollider};
use crate::collide::reduction_gpu::ReadbackMode;
use crate::collide::scenes::Scene;
use crate::gl::period;
use crate::report::period::{under, PeriodResults, Verdict};
use crate::report::BenchOptions;

/// The scene and its size: small, so that the brute force and two frames take a second.
const SCENE: &str = "interlocking-tori";
const TRIANGLES: usize = 1500;

pub fn measure(opts: &BenchOptions) -> anyhow::Result<PeriodResults> {
    let ctx = opts.gl;
    let gpu = period::for_paper(1);
    let mut out = PeriodResults::new(gpu);
    let scene = Scene::build(SCENE, Some(TRIANGLES))?;
    let (px, py) = scene.frame(1);
    let (x, y) = (&scene.x.rest, &scene.y.rest);
    let options = Options {
        readback: ReadbackMode::PaperSwitch,
        ..Options::default()
    };
    let frame = |ctx| -> anyhow::Result<Vec<(u32, u32)>> {
        let mut collider = StreamingCollider::new(ctx, x, y, options)?;
        let mut pairs = collider.frame(&px, &py)?.pairs;
        pairs.sort_unstable();
        Ok(pairs)
    };
    let today = frame(ctx)?;
    let period_run = under(ctx, gpu, || frame(ctx));
    out.step_from(
        "the streaming pipeline: AABB and stencil textures, vertex textures, P0 with its \
         stencil mask, MRT stream update, hierarchical readback (Sec. 4-5)",
        &period_run,
        "fits: 1D RGBA32F AABB textures and R8 stencil arrays, RGBA32F vertex textures read \
         by fragment programs, an R32F P0 with a 24-bit depth / 8-bit stencil mask, two \
         render targets, no float blending or filtering; tiles at 4096, the chip's limit",
    );
    out.step(
        "large models: tiles of at most the chip's texture size (Sec. 5.5)",
        Verdict::Fits,
        format!(
            "the paper's own way: tiles of at most {0} x {0}",
            gpu.max_texture_size.value
        ),
    );
    let compute = under(ctx, gpu, || {
        ComputeCollider::new(ctx, x, y, options).map(|_| ())
    });
    out.step_from(
        "today's counterpart: the compute formulation (not the paper's)",
        &compute,
        "fits",
    );
    let cpu = all_pairs(x, &px, y, &py, options.predicate);
    let missed = |pairs: &[(u32, u32)]| {
        cpu.iter()
            .filter(|p| pairs.binary_search(p).is_err())
            .count()
    };
    let period_text = match &period_run {
        Ok(pairs) => format!("{} pairs, {} missed", pairs.len(), missed(pairs)),
        Err(e) => format!("refused: {e:#}"),
    };
    let change = match &period_run {
        Ok(pairs) if *pairs == today => "none: the G70 computed and stored in fp32 as today \
             (paper 1, Sec. 6: 32-bit floats on CPU and GPU), and every step fits its limits"
            .to_string(),
        Ok(pairs) => format!(
            "{} pairs differ from today's run",
            pairs
                .iter()
                .filter(|p| today.binary_search(p).is_err())
                .count()
                + today
                    .iter()
                    .filter(|p| pairs.binary_search(p).is_err())
                    .count()
        ),
        Err(_) => "the period run was refused".into(),
    };
    out.compare(
        &format!(
            "triangle pairs of {SCENE} ({TRIANGLES} triangles a model, frame 1) against the \
             CPU's {} (brute force)",
            cpu.len()
        ),
        format!("{} pairs, {} missed", today.len(), missed(&today)),
        period_text,
        change,
    );
    Ok(out)
}
