//! Then and now for paper 2: the two-pass method (pixel-shader skinning into a render
//! target, render-to-VBO through a pixel buffer, a draw per character) beside the compute
//! formulation (skinning into a storage buffer, one instanced draw reading it) and linear
//! blend skinning on the CPU, on one crowd of soldiers at full detail.

use super::super::then_and_now::{StageRow, ThenAndNow};
use super::super::BenchOptions;
use crate::crowd::compute::{self, ComputeCrowd};
use crate::crowd::cpu_skinning;
use crate::crowd::renderer::{CrowdRenderer, Method};
use crate::crowd::scene::{self, RunStats};
use crate::crowd::{CharacterModel, ModelKind};
use crate::timing::wall_ms;

const VERDICT: &str = "What compute no longer needs: the n x m render target and its \
    128-characters-per-row cap (the vertex stride limit), batching by texture size, the copy \
    through a pixel buffer object, float-encoded bone indices, and one vertex array and draw \
    call per character: the skinned vertices are written where the drawing pass reads them, \
    and one instanced draw shows every character of a LOD.";

pub fn measure(opts: &BenchOptions) -> anyhow::Result<ThenAndNow> {
    let n = if opts.quick { 16 } else { 128 };
    let frames = if opts.quick { 3 } else { 10 };
    let (w, h) = (320, 240);
    let ctx = opts.gl;
    let kind = ModelKind::Soldier;
    let model = CharacterModel::build(kind)?;

    let target = scene::scene_target(ctx, w, h)?;
    let aspect = w as f32 / h as f32;
    let mut renderer = CrowdRenderer::new(ctx, model.clone())?;
    let mut classic_scene = scene::table1_scene(kind, n, aspect, 1);
    let classic = scene::run(
        ctx,
        &mut renderer,
        &target,
        &mut classic_scene,
        Method::TwoPass,
        frames,
        1.0 / 30.0,
    )?;
    // CPU skinning of the same crowd, every character, per frame.
    let cpu_scene = scene::table1_scene(kind, n, aspect, 1);
    let (models, phases) = scene::placements(&cpu_scene.crowd);
    // The same crowd each run (it does not walk): repeats of one timing, as the report's
    // timing policy says ([`BenchOptions::runs`]).
    let cpu = wall_ms(opts.runs(frames), || {
        for (place, &phase) in models.iter().zip(&phases) {
            let pose = model.clip.sample(&model.skeleton, phase);
            let bones = model.skeleton.skinning_matrices(&pose, *place);
            std::hint::black_box(cpu_skinning::skin(&model.lods[0], &bones));
        }
    });
    let (cpu_runs, cpu_ms) = (cpu.runs, cpu.median);
    let workload = format!(
        "{n} soldiers at full detail (LOD 0, {} vertices each), {w}x{h}, median of {frames} \
         frames (CPU skinning: median of {cpu_runs} runs on one frame's poses)",
        model.lods[0].vertex_count()
    );
    let rows = |c: &RunStats, k: Option<&RunStats>| {
        let (g, kp) = (&c.passes, k.map(|k| &k.passes));
        vec![
            StageRow::new(
                "bone matrices (CPU, both)",
                Some(g.bones_ms),
                kp.map(|p| p.bones_ms),
                None,
            ),
            StageRow::new(
                "bone upload",
                Some(g.upload_ms),
                kp.map(|p| p.upload_ms),
                None,
            ),
            StageRow::new(
                "skinning (pass 1 / compute pass)",
                Some(g.gl_timer.pass1),
                kp.map(|p| p.gl_timer.pass1),
                Some(cpu_ms),
            ),
            StageRow::new(
                "render-to-VBO copy",
                Some(g.gl_timer.copy),
                kp.map(|_| 0.0),
                None,
            ),
            StageRow::new(
                "drawing (pass 2 / one instanced draw)",
                Some(g.gl_timer.pass2),
                kp.map(|p| p.gl_timer.pass2),
                None,
            ),
            StageRow::new("frame", Some(c.frame_ms), k.map(|k| k.frame_ms), None),
        ]
    };
    if let Err(e) = ctx.require_compute("the compute formulation") {
        let mut out = ThenAndNow::unavailable(workload, e.to_string(), VERDICT);
        out.stages = rows(&classic, None);
        return Ok(out);
    }
    let mut crowd = ComputeCrowd::new(ctx, model)?;
    let mut compute_scene = scene::table1_scene(kind, n, aspect, 1);
    let modern = compute::run(
        ctx,
        &mut crowd,
        &target,
        &mut compute_scene,
        frames,
        1.0 / 30.0,
    )?;
    Ok(ThenAndNow {
        workload,
        unavailable: None,
        stages: rows(&classic, Some(&modern)),
        // The vertices and images are compared in tests/crowd_compute.rs; not judged here.
        same_answer: None,
        verdict: VERDICT.into(),
    })
}
