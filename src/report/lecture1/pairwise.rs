//! Pairwise triangle tests in textures: agreement with brute force and with paper 1's
//! streaming AABBs (one model and two), and where each method wins by triangle count:
//! streaming AABBs, the pair quad (classic), its compute counterpart and CPU brute force on
//! the swelling knot at its thickest, as a table and a plot; the pair quad's buffers as a
//! figure.

use super::self_collision::{ms, timed, timed_answer};
use super::{Block, Setting};
use crate::collide::pipeline::{Options as PairOptions, StreamingCollider};
use crate::collide::reduction_gpu::ReadbackMode;
use crate::collide::scenes::Scene;
use crate::collide::stream_setup::{auto_leaf_size, auto_leaf_size_for_pair, max_slots};
use crate::collide::tri_test::Predicate;
use crate::gl::dump::picture_png;
use crate::lecture1::knotted_tube::{KnottedTube, RADIUS_RANGE};
use crate::lecture1::pairwise::{PairwiseTester, DEFAULT_TILE};
use crate::lecture1::pairwise_compute::ComputePairwiseTester;
use crate::lecture1::pictures::pair_buffers;
use crate::lecture1::reference::{pairs_between, self_pairs};
use crate::lecture1::self_collision::{Options, SelfCollider};
use crate::mesh::Mesh;
use crate::page::plot::{Plot, Series};
use crate::report::versions::TIMING_POLICY;
use crate::report::{Basis, Claim, ClaimDef, Figure, Table};
use crate::timing::{faster, judge_ends, Ends, Load, Spread};
use serde::Serialize;

pub const PLOT_PNG: &str = "lecture1_pairwise_by_count.png";
pub const BUFFERS_PNG: &str = "lecture1_pairwise_buffers.png";

/// The knot at one triangle count: every method's answer and time.
#[derive(Serialize)]
pub struct CountRow {
    pub triangles: usize,
    pub pairs: usize,
    /// Streaming AABBs, the pair quad and (where it ran) compute all equal brute force.
    pub all_equal: bool,
    /// Pairs the pair quad reported before the CPU's confirmation.
    pub candidates: usize,
    pub tiles: usize,
    pub brute_force_ms: Spread,
    pub streaming_aabb_ms: Spread,
    pub pairwise_ms: Spread,
    /// The pair passes alone, GL timer query (median of the runs).
    pub pairwise_passes_ms: f64,
    pub compute_ms: Option<Spread>,
    /// The compute dispatch and its list's readback, wall clock between glFinish calls.
    pub compute_dispatch_ms: Option<f64>,
}

impl CountRow {
    /// The fastest whole query, by median.
    pub fn fastest(&self) -> &'static str {
        let mut best = ("brute force (CPU)", self.brute_force_ms.median);
        for (name, t) in [
            ("streaming AABBs", Some(self.streaming_aabb_ms.median)),
            ("pairwise in textures", Some(self.pairwise_ms.median)),
            ("pairwise compute", self.compute_ms.map(|s| s.median)),
        ] {
            if let Some(t) = t.filter(|&t| t < best.1) {
                best = (name, t);
            }
        }
        best.0
    }
}

/// Two models: the pair quad between them against streaming AABBs and brute force.
#[derive(Serialize)]
pub struct TwoModels {
    pub scene: String,
    pub triangles: (usize, usize),
    pub pairs: usize,
    pub pairwise_equal: bool,
    pub streaming_equal: bool,
    pub compute_equal: Option<bool>,
}

#[derive(Serialize)]
pub struct PairwiseRun {
    pub by_count: Vec<CountRow>,
    pub two_models: TwoModels,
    /// Why the compute formulation did not run, if so.
    pub compute_unavailable: Option<String>,
}

pub fn block(setting: &Setting) -> anyhow::Result<Block> {
    let ctx = setting.opts.gl;
    let bar = setting.stage("pairwise tests in textures");
    // region: workload pairwise-counts
    let counts: &[usize] = if setting.opts.quick {
        &[300, 600, 1200]
    } else {
        &[250, 500, 1000, 2000, 4000]
    };
    // endregion
    let tester = PairwiseTester::new(ctx, DEFAULT_TILE)?;
    let (mut compute, compute_unavailable) = match ComputePairwiseTester::new(ctx) {
        Ok(c) => (Some(c), None),
        Err(e) => (None, Some(e.to_string())),
    };
    let mut by_count = Vec::new();
    let mut buffers_of = None;
    for &n in counts {
        let mesh = thick_knot(n);
        by_count.push(count_row(setting, &tester, compute.as_mut(), &mesh)?);
        buffers_of = Some(mesh);
    }
    let load = Load::now();
    let two_models = two_models(setting, &tester, compute.as_mut())?;
    // The figure: the pair quad of the smallest knot (one tile).
    if let Some(mesh) = counts.first().map(|&n| thick_knot(n)).or(buffers_of) {
        let tile = tester.first_tile(&mesh, None)?;
        let panels: Vec<_> = pair_buffers(
            &tile.target.p0,
            &tile.reduction,
            "(knot triangle i, row; j, column)",
            false,
        )?
        .into_iter()
        .map(|b| b.panel)
        .collect();
        // Two by two, as wide as the page: shown at full size, texel for pixel.
        picture_png(
            &panels,
            (crate::page::html::CONTENT_WIDTH, 960),
            &setting.opts.out_dir.join(BUFFERS_PNG),
        )?;
    }
    plot(setting, &by_count)?;
    bar.finish_and_clear();
    let run = PairwiseRun {
        by_count,
        two_models,
        compute_unavailable,
    };
    let all_equal = run.by_count.iter().all(|r| r.all_equal)
        && run.two_models.pairwise_equal
        && run.two_models.streaming_equal
        && run.two_models.compute_equal != Some(false);
    Ok(Block {
        summary: format!(
            "Pairwise tests in textures: on the swelling knot at {} triangles and on two \
             models, the pair quad's pairs {} brute force and streaming AABBs.",
            run.by_count
                .iter()
                .map(|r| r.triangles.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            if all_equal {
                "equal"
            } else {
                "DO NOT ALL EQUAL"
            }
        ),
        checks_made: vec!["pairwise vs brute force"],
        paths: if run.compute_unavailable.is_none() {
            vec![super::paths::PAIRWISE, super::paths::PAIRWISE_COMPUTE]
        } else {
            vec![super::paths::PAIRWISE]
        },
        tables: vec![count_table(setting, &run, load), agreement_table(&run)],
        figures: vec![
            Figure {
                file: PLOT_PNG.into(),
                caption: format!(
                    "Time of a whole self-intersection query against triangle count on the \
                     swelling knot at its thickest (wall clock, medians, log-log), on {}",
                    setting.renderer
                ),
            },
            Figure {
                file: BUFFERS_PNG.into(),
                caption: format!(
                    "The pair quad on the knot of {} triangles: P0 (a texel per triangle \
                     pair, only i < j tested, neighbours skipped) and its hierarchical \
                     levels P1..P3 as the GPU left them",
                    run.by_count.first().map_or(0, |r| r.triangles)
                ),
            },
        ],
        claims: vec![claim(&run, load)],
        results: serde_json::to_value(&run)?,
        load,
        ..Block::default()
    })
}

/// The swelling knot of about `n` triangles at its thickest.
pub fn thick_knot(n: usize) -> Mesh {
    let tube = KnottedTube::with_triangles(n);
    let mut mesh = tube.mesh.clone();
    mesh.positions = tube.positions_at_radius(RADIUS_RANGE.1);
    mesh
}

fn count_row(
    setting: &Setting,
    tester: &PairwiseTester,
    mut compute: Option<&mut ComputePairwiseTester>,
    mesh: &Mesh,
) -> anyhow::Result<CountRow> {
    let ctx = setting.opts.gl;
    let leaf_size = auto_leaf_size(mesh, max_slots(setting.software))?;
    let mut collider = SelfCollider::new(
        ctx,
        mesh,
        Options {
            leaf_size,
            ..Options::default()
        },
    )?;
    // One untimed run of each GPU path (shader compilation, first draws), whose answers are
    // the ones compared.
    let streaming = collider.frame(&mesh.positions)?;
    let classic = tester.run(mesh, None)?;
    let now = match compute.as_deref_mut() {
        Some(c) => Some(c.run(mesh, None)?),
        None => None,
    };
    let (brute_force_ms, brute) =
        timed_answer(setting, || Ok(self_pairs(&collider.mesh, &mesh.positions)))?;
    let streaming_aabb_ms = timed(setting, || collider.frame(&mesh.positions))?;
    let mut passes = Vec::new();
    let pairwise_ms = timed(setting, || {
        let r = tester.run(mesh, None)?;
        passes.push(r.test_ms);
        Ok(r)
    })?;
    let (compute_ms, compute_dispatch_ms) = match compute {
        Some(c) => {
            let mut dispatch = Vec::new();
            let spread = timed(setting, || {
                let r = c.run(mesh, None)?;
                dispatch.push(r.test_ms);
                Ok(r)
            })?;
            (Some(spread), Some(Spread::of(&dispatch).median))
        }
        None => (None, None),
    };
    Ok(CountRow {
        triangles: mesh.triangles.len(),
        pairs: brute.len(),
        all_equal: streaming.pairs == brute
            && classic.pairs == brute
            && now.as_ref().is_none_or(|r| r.pairs == brute),
        candidates: classic.candidates,
        tiles: classic.tiles,
        brute_force_ms,
        streaming_aabb_ms,
        pairwise_ms,
        pairwise_passes_ms: Spread::of(&passes).median,
        compute_ms,
        compute_dispatch_ms,
    })
}

fn two_models(
    setting: &Setting,
    tester: &PairwiseTester,
    compute: Option<&mut ComputePairwiseTester>,
) -> anyhow::Result<TwoModels> {
    let n = if setting.opts.quick { 500 } else { 2000 };
    let scene = Scene::build("interlocking-tori", Some(n))?;
    let (px, py) = scene.frame(1);
    let a = Mesh::new(px.clone(), scene.x.rest.triangles.clone());
    let b = Mesh::new(py.clone(), scene.y.rest.triangles.clone());
    let brute = pairs_between(&a, &b);
    let options = PairOptions {
        leaf_size: auto_leaf_size_for_pair(&scene.x.rest, &scene.y.rest, setting.software)?,
        readback: ReadbackMode::PaperSwitch,
        predicate: Predicate::Exact,
        max_tile: None,
    };
    let mut streaming =
        StreamingCollider::new(setting.opts.gl, &scene.x.rest, &scene.y.rest, options)?;
    let streamed = streaming.frame(&px, &py)?;
    let classic = tester.run(&a, Some(&b))?;
    let compute_equal = match compute {
        Some(c) => Some(c.run(&a, Some(&b))?.pairs == brute),
        None => None,
    };
    Ok(TwoModels {
        scene: scene.label.clone(),
        triangles: (a.triangles.len(), b.triangles.len()),
        pairs: brute.len(),
        pairwise_equal: classic.pairs == brute,
        streaming_equal: streamed.pairs == brute,
        compute_equal,
    })
}

fn count_table(setting: &Setting, run: &PairwiseRun, load: Option<Load>) -> Table {
    let opt = |s: &Option<Spread>| s.as_ref().map_or("-".into(), ms);
    Table {
        caption: format!(
            "Where each wins, by triangle count: one self-intersection query on the swelling \
             knot at its thickest (pairs of intersecting triangles that share no vertex). \
             Whole queries by wall clock, median (range) of {}; the pair passes alone by GL \
             timer query, the compute dispatch with its list's readback by wall clock between \
             glFinish calls; on {}; {}.{}",
            setting.runs.in_words(),
            setting.renderer,
            load.map_or("load average unknown".into(), |l| l.in_words()),
            match &run.compute_unavailable {
                Some(why) => format!(" The compute formulation did not run: {why}."),
                None => String::new(),
            }
        ),
        header: [
            "triangles",
            "pairs",
            "all equal",
            "reported by the quad",
            "brute force CPU (ms)",
            "streaming AABBs (ms)",
            "pairwise in textures (ms)",
            "of which pair passes (ms)",
            "pairwise compute (ms)",
            "of which dispatch (ms)",
            "fastest here",
        ]
        .map(String::from)
        .to_vec(),
        rows: run
            .by_count
            .iter()
            .map(|r| {
                vec![
                    r.triangles.to_string(),
                    r.pairs.to_string(),
                    if r.all_equal { "yes" } else { "NO" }.into(),
                    r.candidates.to_string(),
                    ms(&r.brute_force_ms),
                    ms(&r.streaming_aabb_ms),
                    ms(&r.pairwise_ms),
                    format!("{:.2}", r.pairwise_passes_ms),
                    opt(&r.compute_ms),
                    r.compute_dispatch_ms
                        .map_or("-".into(), |v| format!("{v:.2}")),
                    r.fastest().into(),
                ]
            })
            .collect(),
    }
}

fn agreement_table(run: &PairwiseRun) -> Table {
    let t = &run.two_models;
    let yes = |b: bool| if b { "yes" } else { "NO" }.to_string();
    Table {
        caption: "Two models: the pair quad between them (i in A, j in B) against brute force \
                  and paper 1's streaming AABBs, frame 1 of the scene"
            .into(),
        header: [
            "scene",
            "triangles",
            "pairs (brute force)",
            "pairwise in textures equal",
            "streaming AABBs equal",
            "pairwise compute equal",
        ]
        .map(String::from)
        .to_vec(),
        rows: vec![vec![
            t.scene.clone(),
            format!("{} + {}", t.triangles.0, t.triangles.1),
            t.pairs.to_string(),
            yes(t.pairwise_equal),
            yes(t.streaming_equal),
            t.compute_equal.map_or("did not run".into(), yes),
        ]],
    }
}

// region: rule pairwise-limit
/// Paper 1 on its reference 38: pairwise GPU tests serve below about 1K triangles.
pub const PAIRWISE: ClaimDef = ClaimDef {
    id: "lecture1.pairwise-limit",
    rule: &[
        "src/report/lecture1/pairwise.rs#rule pairwise-limit",
        TIMING_POLICY,
    ],
    published: &[],
    workload: &["src/report/lecture1/pairwise.rs#workload pairwise-counts"],
    // Twice the most it moved between three llvmpipe runs of one build, 2 cores (58%).
    band: Some(1.2),
};

/// Paper 1 on its reference 38: pairwise GPU tests are limited to about 1K triangles, so
/// below that they serve and past it they do not. Judged so that it can fail either way: the
/// pair quad is faster than streaming AABBs at the smallest count run (below 1K), and
/// streaming is faster at every count from about 1K up. Where streaming wins already at the
/// smallest count, the limit is not near 1K on this renderer and the claim does not hold.
fn claim(run: &PairwiseRun, load: Option<Load>) -> Claim {
    const ABOUT_1K: usize = 900;
    let large: Vec<&CountRow> = run
        .by_count
        .iter()
        .filter(|r| r.triangles >= ABOUT_1K)
        .collect();
    let small = run
        .by_count
        .iter()
        .filter(|r| r.triangles < ABOUT_1K)
        .min_by_key(|r| r.triangles);
    let measured = run
        .by_count
        .iter()
        .map(|r| {
            format!(
                "{} triangles: streaming {:.1} ms, pair quad {:.1} ms",
                r.triangles, r.streaming_aabb_ms.median, r.pairwise_ms.median
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    let claim = "Pairwise GPU triangle tests serve below about 1K triangles and do not scale \
                 past it: the pair quad is faster at the smallest count, streaming AABBs from \
                 about 1K on"
        .to_string();
    let paper = "paper 1, Sec. 2.2.2, on its reference 38 (inferred to be Choi, Kim & Kim 2006)";
    let Some(small) = small.filter(|_| !large.is_empty()) else {
        return Claim {
            id: PAIRWISE.id.into(),
            claim,
            paper: paper.into(),
            measured: format!(
                "{measured}; not judged: the run needs a count below 1K and one of 1K or more \
                 (quick mode runs small counts only)"
            ),
            decided_by: Basis::RunSize,
            holds: None,
            ..Claim::default()
        };
    };
    // The pair quad faster at the smallest count, streaming at every large one, each pair of
    // runs taken at the end that favours the claim or at the other end.
    let ends = Ends::of(|favour| {
        faster(&small.pairwise_ms, &small.streaming_aabb_ms, favour)
            && large
                .iter()
                .all(|r| faster(&r.streaming_aabb_ms, &r.pairwise_ms, favour))
    });
    let runs = std::iter::once(small)
        .chain(large.iter().copied())
        .map(|r| {
            format!(
                "{} triangles: streaming {}, pair quad {}",
                r.triangles,
                r.streaming_aabb_ms.in_words(" ms"),
                r.pairwise_ms.in_words(" ms")
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    let verdict = judge_ends(
        ends,
        &runs,
        "the runs of streaming and of the pair quad overlap",
        load,
    );
    let crossover = if small.streaming_aabb_ms.median < small.pairwise_ms.median {
        format!(
            "; by the medians streaming is faster already at {} triangles, so the limit is not \
             near 1K here",
            small.triangles
        )
    } else {
        String::new()
    };
    let largest = large
        .iter()
        .max_by_key(|r| r.triangles)
        .copied()
        .unwrap_or(small);
    Claim {
        id: PAIRWISE.id.into(),
        claim,
        paper: paper.into(),
        measured: format!("{measured}{crossover}; {}", verdict.note),
        decided_by: Basis::Timing,
        holds: verdict.holds,
        evidence: vec![
            PAIRWISE.timing(
                &format!(
                    "pair quad / streaming time at {} triangles",
                    small.triangles
                ),
                small.pairwise_ms.median / small.streaming_aabb_ms.median,
                "x",
                false,
                load,
            ),
            PAIRWISE.timing(
                &format!(
                    "streaming / pair quad time at {} triangles",
                    largest.triangles
                ),
                largest.streaming_aabb_ms.median / largest.pairwise_ms.median,
                "x",
                false,
                load,
            ),
        ],
        ..Claim::default()
    }
}
// endregion

fn plot(setting: &Setting, rows: &[CountRow]) -> anyhow::Result<()> {
    let series = |name: &str, f: &dyn Fn(&CountRow) -> Option<f64>| {
        Series::new(
            name,
            rows.iter()
                .filter_map(|r| f(r).map(|t| (r.triangles as f64, t)))
                .collect(),
        )
    };
    let mut all = vec![
        series("brute force (CPU)", &|r| Some(r.brute_force_ms.median)),
        series("streaming AABBs", &|r| Some(r.streaming_aabb_ms.median)),
        series("pairwise in textures", &|r| Some(r.pairwise_ms.median)),
        series("pairwise compute", &|r| r.compute_ms.map(|s| s.median)),
    ];
    all.retain(|s| !s.points.is_empty());
    Plot {
        title: format!(
            "Self-intersection query on the knot, {}",
            setting.opts.gl.info().renderer
        ),
        x_label: "triangles".into(),
        y_label: "ms (wall clock, median)".into(),
        log_x: true,
        log_y: true,
        series: all,
    }
    .write_png(&setting.opts.out_dir.join(PLOT_PNG))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::timing::Load;

    /// A count whose streaming and pair-quad runs took these times (ms).
    fn count(triangles: usize, streaming: [f64; 3], pairwise: [f64; 3]) -> CountRow {
        CountRow {
            triangles,
            pairs: 0,
            all_equal: true,
            candidates: 0,
            tiles: 1,
            brute_force_ms: Spread::of(&[1.0]),
            streaming_aabb_ms: Spread::of(&streaming),
            pairwise_ms: Spread::of(&pairwise),
            pairwise_passes_ms: 0.0,
            compute_ms: None,
            compute_dispatch_ms: None,
        }
    }

    fn run(by_count: Vec<CountRow>) -> PairwiseRun {
        PairwiseRun {
            by_count,
            two_models: TwoModels {
                scene: "tori".into(),
                triangles: (1, 1),
                pairs: 0,
                pairwise_equal: true,
                streaming_equal: true,
                compute_equal: None,
            },
            compute_unavailable: None,
        }
    }

    const QUIET: Option<Load> = Some(Load {
        one_minute: 0.2,
        cores: 2,
    });

    #[test]
    fn the_1k_limit_fails_where_streaming_wins_from_the_smallest_count() {
        // The paper's picture: the pair quad wins at 250, streaming from 1000 on.
        let paper = run(vec![
            count(250, [5.0, 5.1, 5.2], [1.0, 1.1, 1.2]),
            count(1000, [6.0, 6.1, 6.2], [9.0, 9.1, 9.2]),
        ]);
        let c = claim(&paper, QUIET);
        assert_eq!((c.holds, c.decided_by), (Some(true), Basis::Timing));
        // Streaming faster already at 250: the limit is not near 1K, the claim fails.
        let early = run(vec![
            count(250, [1.0, 1.1, 1.2], [5.0, 5.1, 5.2]),
            count(1000, [6.0, 6.1, 6.2], [9.0, 9.1, 9.2]),
        ]);
        let c = claim(&early, QUIET);
        assert_eq!(c.holds, Some(false));
        assert!(
            c.measured.contains("faster already at 250"),
            "{}",
            c.measured
        );
        // No count of 1K or more: not judged, for the run's size.
        let small = run(vec![count(250, [5.0; 3], [1.0; 3])]);
        let c = claim(&small, QUIET);
        assert_eq!((c.holds, c.decided_by), (None, Basis::RunSize));
    }
}
