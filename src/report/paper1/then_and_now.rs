//! Then and now for paper 1: the streaming pipeline (vertex textures, MRT stream update,
//! stencil-masked `P0` with occlusion count, hierarchical readback) beside the compute
//! formulation (leaf-box pass, all-pairs overlap with atomic-counter compaction) and SOLID's
//! CPU refit and tree traversal, frame by frame on a deforming scene of Table III.

use super::super::then_and_now::{median, StageRow, ThenAndNow};
use super::super::BenchOptions;
use crate::collide::compute_pipeline::ComputeCollider;
use crate::collide::pipeline::{Options, StreamingCollider};
use crate::collide::scenes::Scene;
use crate::collide::solid;
use crate::collide::stream_setup::{auto_leaf_size_for_pair, AabbStream};
use crate::collide::tri_test::{test_caps, ModelView, Predicate};
use std::time::Instant;

const VERDICT: &str = "What compute no longer needs: the complete binary tree with virtual \
    nodes and the stencil array (each leaf is tested once as it is), the 2^d x n_max vertex \
    texture, the P0 render target with its occlusion query, and the hierarchical readback \
    that locates set pixels: the atomic counter hands back the pairs themselves, 8 bytes each. \
    The leaf pairs and the triangle pairs are identical in every frame.";

#[derive(Default)]
struct Columns {
    download: Vec<f64>,
    update: Vec<f64>,
    overlap: Vec<f64>,
    readback: Vec<f64>,
    tri_test: Vec<f64>,
    frame: Vec<f64>,
}

impl Columns {
    fn push(&mut self, r: &crate::collide::pipeline::FrameResult, frame_ms: f64) {
        let t = &r.timings;
        self.download.push(t.download);
        self.update.push(t.update);
        self.overlap.push(t.overlap + t.stencil);
        self.readback.push(t.encode + t.readback);
        self.tri_test.push(t.tri_test);
        self.frame.push(frame_ms);
    }
}

pub fn measure(opts: &BenchOptions) -> anyhow::Result<ThenAndNow> {
    let triangles = if opts.quick { 2_000 } else { 15_000 };
    let frames = if opts.quick { 4 } else { 20 };
    let scene = Scene::build("interlocking-tori", Some(triangles))?;
    let ctx = opts.gl;
    let leaf_size =
        auto_leaf_size_for_pair(&scene.x.rest, &scene.y.rest, ctx.info().is_software())?;
    let options = Options {
        leaf_size,
        predicate: Predicate::Moller,
        ..Options::default()
    };
    let workload = format!(
        "the interlocking tori of Table III ({triangles} triangles each, leaf size {leaf_size}), \
         median over {frames} deforming frames"
    );
    let mut classic = StreamingCollider::new(ctx, &scene.x.rest, &scene.y.rest, options)?;
    let mut compute = match ctx.require_compute("the compute formulation") {
        Ok(()) => Some(ComputeCollider::new(
            ctx,
            &scene.x.rest,
            &scene.y.rest,
            options,
        )?),
        Err(e) => {
            let mut out = ThenAndNow::unavailable(workload.clone(), e.to_string(), VERDICT);
            let mut c = Columns::default();
            for f in 0..frames {
                let (px, py) = scene.frame(f);
                let t = Instant::now();
                let r = classic.frame(&px, &py)?;
                c.push(&r, t.elapsed().as_secs_f64() * 1e3);
            }
            out.stages = rows(c, None, None);
            return Ok(out);
        }
    };
    let sx = AabbStream::build(&scene.x.rest, leaf_size)?;
    let sy = AabbStream::build(&scene.y.rest, leaf_size)?;
    let (mut c, mut k) = (Columns::default(), Columns::default());
    let mut cpu = Columns::default();
    let mut same = true;
    // Warm-ups (shader compilation): the classic pipeline's own
    // ([`StreamingCollider::warm_up`]), a frame of compute.
    let (px, py) = scene.frame(0);
    classic.warm_up(&px, &py)?;
    if let Some(k) = compute.as_mut() {
        k.frame(&px, &py)?;
    }
    for f in 0..frames {
        let (px, py) = scene.frame(f);
        let t = Instant::now();
        let then = classic.frame(&px, &py)?;
        c.push(&then, t.elapsed().as_secs_f64() * 1e3);
        if let Some(modern) = compute.as_mut() {
            let t = Instant::now();
            let now = modern.frame(&px, &py)?;
            k.push(&now, t.elapsed().as_secs_f64() * 1e3);
            same &= now.pairs == then.pairs && now.cap_leaves == then.cap_leaves;
        }
        // SOLID on the CPU: refit the tree, traverse it, test the triangles.
        let start = Instant::now();
        let (bx, by) = (solid::refit(&sx, &px), solid::refit(&sy, &py));
        let refit_ms = start.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let caps = solid::overlapping_leaves(&sx, &bx, &sy, &by);
        let overlap_ms = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let view = |triangles, positions, stream| ModelView {
            triangles,
            positions,
            stream,
        };
        let pairs = test_caps(
            view(&scene.x.rest.triangles, &px, &sx),
            view(&scene.y.rest.triangles, &py, &sy),
            &caps,
            Predicate::Moller,
        );
        cpu.tri_test.push(t.elapsed().as_secs_f64() * 1e3);
        cpu.update.push(refit_ms);
        cpu.overlap.push(overlap_ms);
        cpu.frame.push(start.elapsed().as_secs_f64() * 1e3);
        same &= pairs.pairs == then.pairs;
    }
    Ok(ThenAndNow {
        workload,
        unavailable: None,
        stages: rows(c, Some(k), Some(cpu)),
        same_answer: Some(same),
        verdict: VERDICT.into(),
    })
}

fn rows(c: Columns, k: Option<Columns>, cpu: Option<Columns>) -> Vec<StageRow> {
    let pick = |cols: &Option<Columns>, f: fn(&Columns) -> &Vec<f64>| {
        cols.as_ref()
            .map(f)
            .filter(|v| !v.is_empty())
            .map(|v| median(v.clone()))
    };
    let row = |name: &str, f: fn(&Columns) -> &Vec<f64>| {
        StageRow::new(
            name,
            Some(median(f(&c).clone())),
            pick(&k, f),
            pick(&cpu, f),
        )
    };
    vec![
        row("download (vertices to the GPU)", |c| &c.download),
        row("stream update / leaf boxes (CPU: SOLID refit)", |c| {
            &c.update
        }),
        row(
            "overlap test (classic: stencil + P0 + occlusion count; CPU: tree traversal)",
            |c| &c.overlap,
        ),
        row(
            "readback (classic: encode + decode; compute: count + pairs)",
            |c| &c.readback,
        ),
        row("triangle test (CPU in all three)", |c| &c.tri_test),
        row("frame", |c| &c.frame),
    ]
}
