//! Then and now for the pairwise tests: the pair quad over triangle textures with its
//! occlusion count and hierarchical readback (OpenGL 3.3) beside one compute dispatch with an
//! atomic-append pair list (OpenGL 4.3) and CPU brute force, on the swelling knot.

use super::pairwise::thick_knot;
use super::{Block, Setting};
use crate::lecture1::pairwise::{PairwiseTester, DEFAULT_TILE};
use crate::lecture1::pairwise_compute::ComputePairwiseTester;
use crate::lecture1::reference::self_pairs;
use crate::lecture1::weld::weld;
use crate::report::then_and_now::{median, StageRow, ThenAndNow};
use crate::timing::Load;
use std::time::Instant;

const VERDICT: &str = "What compute no longer needs: the triangles as texels of a float \
    texture (storage buffers instead), the pair quad cut into tiles no larger than a render \
    target, the occlusion query per tile and the hierarchical readback that locates the set \
    texels of P0: the atomic counter hands back the pairs themselves, 8 bytes each. Both \
    formulations run the same filter, and the CPU confirms what either reports with the exact \
    predicate.";

pub fn block(setting: &Setting) -> anyhow::Result<Block> {
    let ctx = setting.opts.gl;
    let bar = setting.stage("pairwise tests, then and now");
    let n = if setting.opts.quick { 600 } else { 2000 };
    let mesh = thick_knot(n);
    let workload = format!(
        "one self-intersection query on the swelling knot at its thickest ({} triangles), \
         {}",
        mesh.triangles.len(),
        setting.runs.in_words()
    );
    let classic = PairwiseTester::new(ctx, DEFAULT_TILE)?;
    let mut compute = ComputePairwiseTester::new(ctx).ok();
    let welded = weld(&mesh);
    // Untimed first runs (shader compilation); their answers are compared.
    let then = classic.run(&mesh, None)?;
    let now = compute.as_mut().map(|c| c.run(&mesh, None)).transpose()?;
    let brute = self_pairs(&welded, &mesh.positions);
    let (mut passes, mut frames) = (Vec::new(), Vec::new());
    let (mut dispatch, mut compute_frames) = (Vec::new(), Vec::new());
    let mut cpu = Vec::new();
    setting.runs.run(|_| -> anyhow::Result<()> {
        let t = Instant::now();
        passes.push(classic.run(&mesh, None)?.test_ms);
        frames.push(t.elapsed().as_secs_f64() * 1e3);
        if let Some(c) = compute.as_mut() {
            let t = Instant::now();
            dispatch.push(c.run(&mesh, None)?.test_ms);
            compute_frames.push(t.elapsed().as_secs_f64() * 1e3);
        }
        let t = Instant::now();
        std::hint::black_box(self_pairs(&welded, &mesh.positions));
        cpu.push(t.elapsed().as_secs_f64() * 1e3);
        Ok(())
    })?;
    let load = Load::now();
    bar.finish_and_clear();
    let some = |v: Vec<f64>| (!v.is_empty()).then(|| median(v));
    let stages = vec![
        StageRow::new(
            "pair test (classic: quad tiles with occlusion count; compute: dispatch, count and \
             list read back)",
            Some(median(passes)),
            some(dispatch),
            None,
        ),
        StageRow::new(
            "query (upload, pair test, readback, exact confirmation)",
            Some(median(frames)),
            some(compute_frames),
            Some(median(cpu)),
        ),
    ];
    let result = match (&now, ctx.require_compute("the compute formulation")) {
        (Some(now), _) => ThenAndNow {
            workload,
            unavailable: None,
            stages,
            same_answer: Some(now.pairs == then.pairs && then.pairs == brute),
            verdict: VERDICT.into(),
        },
        (None, Err(e)) => ThenAndNow {
            stages,
            ..ThenAndNow::unavailable(workload, e.to_string(), VERDICT)
        },
        (None, Ok(())) => anyhow::bail!("the compute pair test could not be built"),
    };
    let compared = result.same_answer.is_some();
    Ok(Block {
        summary: String::new(),
        checks_made: if compared {
            vec!["pairwise compute vs classic"]
        } else {
            Vec::new()
        },
        paths: if compared {
            vec![super::paths::PAIRWISE_COMPUTE]
        } else {
            Vec::new()
        },
        tables: vec![result.table(&setting.renderer)],
        results: serde_json::to_value(&result)?,
        load,
        ..Block::default()
    })
}
