//! Self-collision, frame by frame: the streaming-AABB self test against brute force on paper
//! 1's deformations (wavy, pulsating) of a flattened torus and on the swelling knotted tube,
//! with the pair texture of the frame with most pairs and its hierarchical levels as figures.

use super::{Block, Setting};
use crate::collide::deform::{Deformation, Deforming, Pulsating, Wavy};
use crate::collide::reduction::Scheme;
use crate::collide::stream_setup::{auto_leaf_size, max_slots};
use crate::gl::dump::picture_png;
use crate::lecture1::knotted_tube::KnottedTube;
use crate::lecture1::pictures::pair_buffers;
use crate::lecture1::reference::self_pairs;
use crate::lecture1::self_collision::{Options, SelfCollider};
use crate::lecture1::weld::weld;
use crate::mesh::{torus_with_triangles, Mesh};
use crate::report::{Figure, Table};
use crate::timing::{Load, Spread};
use glam::Vec3;
use serde::Serialize;
use std::time::Instant;

/// One scene's run.
#[derive(Serialize)]
pub struct SceneRun {
    pub scene: String,
    pub triangles: usize,
    pub leaf_size: usize,
    pub leaves: usize,
    pub frames: Vec<FrameRow>,
    /// The figure of the frame with the most pairs.
    pub figure: String,
}

/// One frame: the GPU's pairs against brute force, and both timed.
#[derive(Serialize)]
pub struct FrameRow {
    pub frame: usize,
    pub t: f32,
    pub gpu_pairs: usize,
    pub cpu_pairs: usize,
    /// The two lists are equal (not only their lengths).
    pub equal: bool,
    pub caps: usize,
    pub pctps: u64,
    /// Wall clock of the whole GPU frame (download, update, test, readback, triangle test).
    pub gpu_frame_ms: Spread,
    /// Wall clock of brute force on the CPU.
    pub cpu_ms: Spread,
}

/// A scene: its rest mesh and its positions at time `t`.
struct Motion {
    name: String,
    mesh: Mesh,
    at: Box<dyn Fn(f32) -> Vec<Vec3>>,
    dt: f32,
}

fn scenes(quick: bool) -> Vec<Motion> {
    let (torus_n, knot_n) = if quick { (600, 800) } else { (2000, 3000) };
    // A torus flattened to 15% of its height: paper 1's deformations press its sides together.
    let torus = weld(&torus_with_triangles(1.0, 0.3, torus_n).scaled(Vec3::new(1.0, 1.0, 0.15)));
    let size = 2.0;
    let deformed = |name: &str, deformation: Deformation| {
        let d = Deforming::new(torus.clone(), deformation);
        Motion {
            name: name.into(),
            mesh: d.rest.clone(),
            at: Box::new(move |t| d.positions(t)),
            dt: 0.3,
        }
    };
    let tube = KnottedTube::with_triangles(knot_n);
    vec![
        deformed(
            "flattened torus, wavy",
            Deformation::Wavy(Wavy::for_size(size, 7)),
        ),
        deformed(
            "flattened torus, pulsating (amplitude 0.1)",
            Deformation::Pulsating(Pulsating {
                amplitude: 0.1,
                ..Pulsating::for_size(size)
            }),
        ),
        Motion {
            name: "knotted tube, swelling".into(),
            mesh: tube.mesh.clone(),
            at: Box::new(move |t| tube.positions(t)),
            dt: if quick { 0.6 } else { 0.3 },
        },
    ]
}

pub fn block(setting: &Setting) -> anyhow::Result<Block> {
    let opts = setting.opts;
    let bar = setting.stage("self-collision");
    let frames = if opts.quick { 4 } else { 8 };
    let mut runs = Vec::new();
    let mut figures = Vec::new();
    for (k, motion) in scenes(opts.quick).into_iter().enumerate() {
        let file = format!("lecture1_self_collision_{k}.png");
        let run = scene(setting, &motion, frames, &file)?;
        figures.push(Figure {
            file,
            caption: format!(
                "Self-collision, {}: the pair texture P0 of frame {} (leaf pairs of one \
                 tile; only pairs above the diagonal are tested) and its hierarchical 4x4 \
                 levels P1..P3, as the GPU left them",
                run.scene,
                run.frames
                    .iter()
                    .max_by_key(|f| f.gpu_pairs)
                    .map_or(0, |f| f.frame)
            ),
        });
        runs.push(run);
    }
    let load = Load::now();
    bar.finish_and_clear();
    let all_equal = runs.iter().flat_map(|r| &r.frames).all(|f| f.equal);
    let total: usize = runs
        .iter()
        .flat_map(|r| &r.frames)
        .map(|f| f.cpu_pairs)
        .sum();
    Ok(Block {
        summary: format!(
            "Self-collision: {} frames of three deforming scenes; the GPU's pairs {} brute \
             force in every frame ({total} intersecting pairs in all).",
            runs.iter().map(|r| r.frames.len()).sum::<usize>(),
            if all_equal {
                "equal"
            } else {
                "DO NOT ALL EQUAL"
            }
        ),
        tables: vec![table(setting, &runs, load)],
        figures,
        results: serde_json::to_value(&runs)?,
        load,
        checks_made: vec!["self-collision vs brute force"],
        paths: vec![super::paths::SELF_COLLISION],
        ..Block::default()
    })
}

fn scene(
    setting: &Setting,
    motion: &Motion,
    frames: usize,
    file: &str,
) -> anyhow::Result<SceneRun> {
    let ctx = setting.opts.gl;
    let leaf_size = auto_leaf_size(&motion.mesh, max_slots(setting.software))?;
    let mut collider = SelfCollider::new(
        ctx,
        &motion.mesh,
        Options {
            leaf_size,
            ..Options::default()
        },
    )?;
    // One untimed frame first (shader compilation, first draws).
    collider.frame(&(motion.at)(0.0))?;
    let mut rows = Vec::new();
    for f in 0..frames {
        let t = f as f32 * motion.dt;
        let positions = (motion.at)(t);
        // The answers compared are those of the first timed runs.
        let (cpu_ms, cpu) = timed_answer(setting, || Ok(self_pairs(&collider.mesh, &positions)))?;
        let (gpu_frame_ms, gpu) = timed_answer(setting, || collider.frame(&positions))?;
        rows.push(FrameRow {
            frame: f,
            t,
            gpu_pairs: gpu.pairs.len(),
            cpu_pairs: cpu.len(),
            equal: gpu.pairs == cpu,
            caps: gpu.caps,
            pctps: gpu.pctps,
            gpu_frame_ms,
            cpu_ms,
        });
    }
    // The figure: the frame with most pairs again, its P0 encoded hierarchically.
    let best = rows.iter().max_by_key(|r| r.gpu_pairs).map_or(0.0, |r| r.t);
    collider.frame(&(motion.at)(best))?;
    collider
        .reduction
        .read(ctx, &collider.target, Scheme::Hierarchical)?;
    let panels: Vec<_> = pair_buffers(
        &collider.target.p0,
        &collider.reduction,
        "of leaves (row, column)",
        false,
    )?
    .into_iter()
    .map(|b| b.panel)
    .collect();
    picture_png(&panels, (1200, 420), &setting.opts.out_dir.join(file))?;
    Ok(SceneRun {
        scene: motion.name.clone(),
        triangles: collider.mesh.triangles.len(),
        leaf_size,
        leaves: collider.stream.leaves.len(),
        frames: rows,
        figure: file.into(),
    })
}

/// Wall clock of `work` as the section's runs say.
pub(super) fn timed<T>(
    setting: &Setting,
    mut work: impl FnMut() -> anyhow::Result<T>,
) -> anyhow::Result<Spread> {
    let times = setting.runs.run(|_| -> anyhow::Result<f64> {
        let start = Instant::now();
        std::hint::black_box(work()?);
        Ok(start.elapsed().as_secs_f64() * 1e3)
    })?;
    Ok(Spread::of(&times))
}

/// [`timed`], and the first run's answer: a timing's runs give the answer that is checked,
/// so no run is made for it alone.
pub(super) fn timed_answer<T>(
    setting: &Setting,
    mut work: impl FnMut() -> anyhow::Result<T>,
) -> anyhow::Result<(Spread, T)> {
    let mut first = None;
    let spread = timed(setting, || {
        let answer = work()?;
        if first.is_none() {
            first = Some(answer);
        }
        Ok(())
    })?;
    let answer = first.ok_or_else(|| anyhow::anyhow!("a timing made no run"))?;
    Ok((spread, answer))
}

/// "12.3 (11.9-13.0)": a median and its runs' range.
pub(super) fn ms(s: &Spread) -> String {
    if s.runs > 1 {
        format!("{:.2} ({:.2}-{:.2})", s.median, s.min, s.max)
    } else {
        format!("{:.2}", s.median)
    }
}

fn table(setting: &Setting, runs: &[SceneRun], load: Option<Load>) -> Table {
    let mut rows = Vec::new();
    for r in runs {
        for (i, f) in r.frames.iter().enumerate() {
            // The scene is named once, on its first frame; its other frames follow below it.
            let scene = if i == 0 {
                format!(
                    "{} ({} triangles, {} leaves)",
                    r.scene, r.triangles, r.leaves
                )
            } else {
                String::new()
            };
            rows.push(vec![
                scene,
                f.frame.to_string(),
                format!("{:.1}", f.t),
                f.gpu_pairs.to_string(),
                f.cpu_pairs.to_string(),
                if f.equal { "yes" } else { "NO" }.into(),
                f.caps.to_string(),
                f.pctps.to_string(),
                ms(&f.gpu_frame_ms),
                ms(&f.cpu_ms),
            ]);
        }
    }
    Table {
        caption: format!(
            "Self-collision per frame: pairs of intersecting triangles that share no vertex, on \
             paper 1's wavy and pulsating deformations (Sec. 7.2) of a torus flattened to 15% of \
             its height, and on the knotted tube swelling until it presses through itself, \
             found by the streaming AABBs (GPU boxes, CPU exact triangle test) and by brute \
             force on the CPU with the same predicate, on {}. Each scene is named on its first \
             frame; the rows below it, up to the next name, are its later frames. Times: wall \
             clock of the whole frame, median (range) of {}; {}",
            setting.renderer,
            setting.runs.in_words(),
            load.map_or("load average unknown".into(), |l| l.in_words())
        ),
        header: [
            "scene",
            "frame",
            "t (s)",
            "pairs (GPU)",
            "pairs (brute force)",
            "equal",
            "colliding leaf pairs",
            "triangle pairs tested",
            "GPU frame (ms)",
            "brute force (ms)",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}
