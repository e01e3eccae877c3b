//! The paper's claims beside what this run measured, one function per claim, each judged as
//! the paper states it.

use super::bench::{FrameTimes, Paper1Results, SceneRun};
use super::fig10_12::{cullide_ratio, solid_ratios};
use super::fig7::crossover_text;
use crate::collide::reduction::Scheme;
use crate::collide::reduction_gpu::{paper_switch, CalibrationPoint, PAPER_ETA_THRESHOLD};
use crate::report::evidence::PairSet;
use crate::report::versions::{Fnv, TIMING_POLICY};
use crate::report::{Basis, Claim, ClaimDef, Evidence};
use crate::timing::{end, judge_ends, Ends, Spread};

/// Every claim of the section, with what decides it.
pub const CLAIMS: &[ClaimDef] = &[TORI, SPARSE, READBACK, SOLID, CULLIDE];

// region: rule constants
/// The `P0` side of the paper's readback claims (Sec. 5.3.2).
const PAPER_P0: usize = 2048;
/// Sec. 5.3.2: "we can always read 2048 x 2048 data in less than 7.2 ms".
const PAPER_READBACK_MS: f64 = 7.2;
// endregion

pub fn claims(results: &Paper1Results) -> Vec<Claim> {
    [
        interactive_tori(results),
        hierarchy_pays_below_threshold(results),
        readback_bound(results),
        beats_solid(results),
        beats_cullide(results),
    ]
    .into_iter()
    .flatten()
    .collect()
}

// region: rule shared
fn min_max(v: impl Iterator<Item = f64>) -> (f64, f64) {
    v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    })
}

/// A scene's frames, each a run of the quantity `of` takes from it.
fn over_frames(run: &SceneRun, of: impl Fn(&FrameTimes) -> f64) -> Spread {
    Spread::of(&run.frame_times.iter().map(of).collect::<Vec<_>>())
}

/// The runs of several scenes in words: "N frames per scene; <what>: lo-hi unit".
fn frames_in_words(runs: &[&SceneRun], what: &str, spreads: &[Spread], unit: &str) -> String {
    let (lo, hi) = min_max(spreads.iter().flat_map(|s| [s.min, s.max]));
    let frames = runs.iter().map(|r| r.frame_times.len()).max().unwrap_or(0);
    format!("{frames} timed frames per scene; {what} frame by frame {lo:.2}-{hi:.2}{unit}")
}
// endregion

// region: rule tori-frame
/// Table III: a whole frame of the tori scenes within the paper's 7.86-29.35 ms.
const TORI: ClaimDef = ClaimDef {
    id: "paper1.tori-frame-interactive",
    rule: &[
        "src/report/paper1/claims.rs#rule tori-frame",
        "src/report/paper1/claims.rs#rule shared",
        TIMING_POLICY,
    ],
    published: &["paper1.table3"],
    workload: &[
        "src/report/paper1/bench.rs#workload scenes",
        "src/report/paper1/bench.rs#workload tori-size",
    ],
    // Twice the most it moved between three llvmpipe runs of one build, 2 cores (31%).
    band: Some(0.65),
};

fn interactive_tori(results: &Paper1Results) -> Option<Claim> {
    let tori: Vec<&SceneRun> = results
        .scenes
        .iter()
        .filter(|r| r.name.ends_with("tori"))
        .collect();
    if tori.is_empty() {
        return None;
    }
    let worst = tori
        .iter()
        .map(|r| r.stream.timings.total)
        .fold(0.0, f64::max);
    let frames: Vec<Spread> = tori
        .iter()
        .map(|r| over_frames(r, |f| f.stream_total))
        .collect();
    // The slowest scene, with every frame at its fastest run or at its slowest.
    let ends =
        Ends::of(|favour| frames.iter().map(|s| end(s, !favour)).fold(0.0, f64::max) <= 29.35);
    let verdict = judge_ends(
        ends,
        &frames_in_words(&tori, "whole frames", &frames, " ms"),
        "the slowest scene's frames fall on both sides of 29.35 ms",
        results.scenes_load,
    );
    Some(Claim {
        id: TORI.id.into(),
        claim: "A whole frame of the 15K-triangle tori scenes is interactive".into(),
        paper: "7.86-29.35 ms per frame (Table III, GeForce 7800 GTX)".into(),
        measured: format!(
            "slowest tori scene {worst:.2} ms per frame ({})",
            verdict.note
        ),
        decided_by: Basis::Timing,
        holds: verdict.holds,
        evidence: vec![TORI.timing(
            "slowest tori scene, whole frame",
            worst,
            " ms",
            false,
            results.scenes_load,
        )],
        ..Claim::default()
    })
}
// endregion

// region: rule sparse-readback
/// Sec. 5.3.1-5.3.2: the hierarchical readback below eta = 0.095%.
const SPARSE: ClaimDef = ClaimDef {
    id: "paper1.hierarchy-below-threshold",
    rule: &[
        "src/report/paper1/claims.rs#rule sparse-readback",
        "src/report/paper1/claims.rs#rule calibration-runs",
        "src/report/paper1/claims.rs#rule shared",
        TIMING_POLICY,
    ],
    published: &["paper1.readback"],
    workload: &["src/report/paper1/bench.rs#workload fig7"],
    band: Some(0.25),
};

/// Sec. 5.3.1-5.3.2: the hierarchy works well while eta is small (0.095% on the 7800), the
/// reduced scheme above. Judged on clustered contents (the paper's P0 is a scene's) by time,
/// hierarchical against reduced at every calibrated eta below 0.095%.
fn hierarchy_pays_below_threshold(results: &Paper1Results) -> Option<Claim> {
    let clustered = &results.fig7.clustered;
    let sparse: Vec<_> = clustered
        .points
        .iter()
        .filter(|p| p.eta < PAPER_ETA_THRESHOLD)
        .collect();
    if sparse.is_empty() {
        return None;
    }
    let lost =
        |p: &&&CalibrationPoint| p.paper_fastest().map(|(s, _)| s) != Some(Scheme::Hierarchical);
    // Losses from the crossover on are what "the reduced scheme is faster from" says; only
    // those below it need naming.
    let unstated: Vec<String> = sparse
        .iter()
        .filter(lost)
        .filter(|p| clustered.crossover_eta.is_none_or(|from| p.eta < from))
        .map(|p| format!("{:.4}%", p.eta * 100.0))
        .collect();
    // Hierarchical against reduced at each sparse point, with the runs at the end that
    // favours the hierarchy (its fastest against reduced's slowest) or the other end.
    let ends = Ends::of(|favour| {
        sparse.iter().all(|p| {
            let cost = |s| {
                p.cost(s)
                    .map(|c| c.end_ms(favour == (s == Scheme::Hierarchical)))
            };
            cost(Scheme::Hierarchical)
                .zip(cost(Scheme::Reduced))
                .is_some_and(|(h, r)| h < r)
        })
    });
    let verdict = judge_ends(
        ends,
        &calibration_runs(&sparse),
        "the two schemes' runs overlap below 0.095%",
        results.fig7_load,
    );
    let bytes = results
        .fig7
        .uniform
        .points
        .iter()
        .chain(&clustered.points)
        .filter(|p| p.eta < PAPER_ETA_THRESHOLD)
        .map(|p| p.schemes[0].bytes as f64 / p.schemes[2].bytes as f64)
        .fold(0.0, f64::max);
    // The hierarchy's time over the reduced scheme's, at the sparse point where it does worst.
    let worst_ratio = sparse
        .iter()
        .filter_map(|p| {
            let h = p.cost(Scheme::Hierarchical)?.total_ms();
            let r = p.cost(Scheme::Reduced)?.total_ms();
            Some(h / r)
        })
        .fold(0.0, f64::max);
    Some(Claim {
        id: SPARSE.id.into(),
        claim: "Below eta = 0.095% the hierarchical readback is faster than the reduced one".into(),
        paper: "the hierarchy works well while eta is small, 0.095% in the paper; from there \
                the reduced scheme (Sec. 5.3.1-5.3.2, Fig. 7, 2048x2048 P0, GeForce 7800)"
            .into(),
        measured: format!(
            "clustered CAPs in a {p0}x{p0} P0: {}{}; uniform CAPs: {}; below 0.095% the \
             hierarchy reads at most {:.3}% of P0's bytes ({})",
            crossover_text(clustered),
            if unstated.is_empty() {
                String::new()
            } else {
                format!(
                    ", and the hierarchical scheme is also the slower one at eta = {}",
                    unstated.join(", ")
                )
            },
            crossover_text(&results.fig7.uniform),
            100.0 * bytes,
            verdict.note,
            p0 = results.fig7.p0,
        ),
        decided_by: Basis::Timing,
        holds: verdict.holds,
        evidence: vec![
            SPARSE.timing(
                "hierarchical / reduced time below 0.095%, the worst eta",
                worst_ratio,
                "x",
                false,
                results.fig7_load,
            ),
            Evidence::count(
                "share of P0's bytes the hierarchy reads below 0.095%",
                bytes,
            ),
        ],
        ..Claim::default()
    })
}
// endregion

// region: rule calibration-runs
/// The calibration's runs in words: how many per point, and how far the slowest run of a
/// scheme was from its fastest.
fn calibration_runs(points: &[&CalibrationPoint]) -> String {
    let runs = points.iter().map(|p| p.runs).min().unwrap_or(0);
    let widest = points
        .iter()
        .flat_map(|p| &p.schemes)
        .map(|c| c.slowest_ms / c.total_ms())
        .filter(|r| r.is_finite())
        .fold(1.0, f64::max);
    format!(
        "at least {runs} run{} of each scheme per eta, the fastest kept; the slowest run at \
         most {widest:.2}x the fastest",
        if runs == 1 { "" } else { "s" }
    )
}
// endregion

// region: rule readback-bound
/// Sec. 5.3.2: any 2048 x 2048 P0 read back in under 7.2 ms.
const READBACK: ClaimDef = ClaimDef {
    id: "paper1.any-p0-read-back-quickly",
    rule: &[
        "src/report/paper1/claims.rs#rule readback-bound",
        "src/report/paper1/claims.rs#rule constants",
        "src/report/paper1/claims.rs#rule calibration-runs",
        "src/report/paper1/claims.rs#rule shared",
        TIMING_POLICY,
    ],
    published: &["paper1.readback"],
    workload: &["src/report/paper1/bench.rs#workload fig7"],
    band: Some(0.25),
};

/// Sec. 5.3.2: with the variable scheme (hierarchical or reduced; the paper has no full
/// readback) a 2048 x 2048 P0 is always read in under 7.2 ms.
fn readback_bound(results: &Paper1Results) -> Option<Claim> {
    let f = &results.fig7;
    let points: Vec<_> = f.clustered.points.iter().chain(&f.uniform.points).collect();
    if points.is_empty() {
        return None;
    }
    // The switch placed where it pays on this renderer: the faster of the two at each eta.
    let best = points
        .iter()
        .filter_map(|p| p.paper_fastest().map(|(_, ms)| ms))
        .fold(0.0, f64::max);
    // The paper's own switch, at 0.095%.
    let fixed = points
        .iter()
        .filter_map(|p| p.cost(paper_switch(p.eta)).map(|c| c.total_ms()))
        .fold(0.0, f64::max);
    let judged = f.p0 == PAPER_P0;
    // The faster of the two at each eta, every scheme at its fastest run or its slowest.
    let ends = Ends::of(|favour| {
        points
            .iter()
            .filter_map(|p| {
                let h = p.cost(Scheme::Hierarchical)?.end_ms(favour);
                let r = p.cost(Scheme::Reduced)?.end_ms(favour);
                Some(h.min(r))
            })
            .fold(0.0, f64::max)
            < PAPER_READBACK_MS
    });
    let verdict = judge_ends(
        ends,
        &calibration_runs(&points),
        "the runs fall on both sides of 7.2 ms",
        results.fig7_load,
    );
    Some(Claim {
        id: READBACK.id.into(),
        claim: "With the scheme chosen per eta, any P0 is read back quickly".into(),
        paper: "a 2048 x 2048 P0 always read in less than 7.2 ms, hierarchical or reduced \
                (Sec. 5.3.2)"
            .into(),
        measured: format!(
            "{p0}x{p0} P0, eta = 0.001% .. 10%, clustered and uniform CAPs: at most {best:.2} ms \
             with the faster of hierarchical and reduced at each eta, {fixed:.2} ms with the \
             paper's switch at 0.095% ({})",
            if judged {
                verdict.note
            } else {
                "not judged: the paper's claim is for 2048x2048".into()
            },
            p0 = f.p0
        ),
        decided_by: Basis::Timing,
        holds: if judged { verdict.holds } else { None },
        evidence: vec![READBACK.timing(
            "slowest readback, the faster scheme at each eta",
            best,
            " ms",
            false,
            results.fig7_load,
        )],
        ..Claim::default()
    })
}
// endregion

// region: rule beats-solid
/// Sec. 7.4.1: faster than SOLID's refit and traversal.
const SOLID: ClaimDef = ClaimDef {
    id: "paper1.beats-solid",
    rule: &[
        "src/report/paper1/claims.rs#rule beats-solid",
        "src/report/paper1/claims.rs#rule shared",
        TIMING_POLICY,
    ],
    published: &["paper1.claims"],
    workload: &[
        "src/report/paper1/bench.rs#workload scenes",
        "src/report/paper1/bench.rs#workload tori-size",
    ],
    // Twice the most it moved between three llvmpipe runs of one build, 2 cores (49%).
    band: Some(1.0),
};

/// Sec. 7.4.1: "excluding the downloading time, 2~10 times faster than SOLID; including
/// everything together, 1.4~2 times" (culling and update; the triangle test left out).
fn beats_solid(results: &Paper1Results) -> Option<Claim> {
    if results.scenes.is_empty() {
        return None;
    }
    let ratios: Vec<(f64, f64)> = results.scenes.iter().map(solid_ratios).collect();
    let (lo, hi) = min_max(ratios.iter().map(|r| r.1));
    let (lo0, hi0) = min_max(ratios.iter().map(|r| r.0));
    // Frame by frame: SOLID's culling over the streaming culling, without and with download.
    let scenes: Vec<&SceneRun> = results.scenes.iter().collect();
    let without: Vec<Spread> = scenes
        .iter()
        .map(|r| over_frames(r, |f| f.solid_cull / f.stream_cull))
        .collect();
    let with: Vec<Spread> = scenes
        .iter()
        .map(|r| over_frames(r, |f| f.solid_cull / (f.stream_cull + f.stream_download)))
        .collect();
    let lowest = |s: &[Spread], favour| {
        s.iter()
            .map(|s| end(s, favour))
            .fold(f64::INFINITY, f64::min)
    };
    let ends = Ends::of(|favour| lowest(&without, favour) >= 2.0 && lowest(&with, favour) >= 1.4);
    let verdict = judge_ends(
        ends,
        &frames_in_words(&scenes, "SOLID / streaming without download", &without, "x"),
        "the frames fall on both sides of 2x or 1.4x",
        results.scenes_load,
    );
    Some(Claim {
        id: SOLID.id.into(),
        claim: "Streaming culling + update beats SOLID's refit + traversal".into(),
        paper: "2-10x without texture download, 1.4-2x with it".into(),
        measured: format!(
            "SOLID / streaming {lo0:.2}-{hi0:.2}x without download, {lo:.2}-{hi:.2}x with it \
             ({}{})",
            if results.setup.software_renderer {
                "SOLID runs on the CPU that also runs the software renderer here; "
            } else {
                ""
            },
            verdict.note
        ),
        decided_by: Basis::Timing,
        holds: verdict.holds,
        evidence: vec![SOLID.timing(
            "SOLID / streaming with the download, the lowest scene",
            lo,
            "x",
            true,
            results.scenes_load,
        )],
        ..Claim::default()
    })
}
// endregion

// region: rule beats-cullide
/// Sec. 7.4.2, Fig. 12: 3x faster than CULLIDE, no pair missed.
const CULLIDE: ClaimDef = ClaimDef {
    id: "paper1.beats-cullide",
    rule: &[
        "src/report/paper1/claims.rs#rule beats-cullide",
        "src/report/paper1/claims.rs#rule shared",
        TIMING_POLICY,
    ],
    published: &["paper1.claims", "paper1.table4"],
    workload: &[
        "src/report/paper1/bench.rs#workload scenes",
        "src/report/paper1/bench.rs#workload tori-size",
    ],
    band: Some(0.25),
};

/// Sec. 7.4.2 and Fig. 12: "on average, more than three times performance improvement"
/// over CULLIDE, and the streaming pipeline reports every colliding pair.
fn beats_cullide(results: &Paper1Results) -> Option<Claim> {
    let runs = &results.scenes;
    if runs.is_empty() {
        return None;
    }
    let ratios: Vec<f64> = runs.iter().map(cullide_ratio).collect();
    let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
    let (lo, hi) = min_max(ratios.iter().copied());
    let missing_stream = runs.iter().all(|r| r.solid_agrees == r.frames);
    let (mlo, mhi) = min_max(runs.iter().map(|r| r.cullide_missing_percent));
    // A missed pair is a definite no; the speed is judged only on a quiet machine, and only
    // where the scenes' frames, all at their end for or against the claim, agree.
    let scenes: Vec<&SceneRun> = runs.iter().collect();
    let frames: Vec<Spread> = scenes
        .iter()
        .map(|r| over_frames(r, |f| f.cullide_total / f.stream_total))
        .collect();
    let ends = Ends::of(|favour| {
        frames.iter().map(|s| end(s, favour)).sum::<f64>() / frames.len() as f64 >= 3.0
    });
    let verdict = judge_ends(
        ends,
        &frames_in_words(&scenes, "CULLIDE / streaming", &frames, "x"),
        "the mean over the scenes falls on both sides of 3x frame by frame",
        results.scenes_load,
    );
    let agreeing: usize = runs.iter().map(|r| r.solid_agrees).sum();
    let mut digest = Fnv::default();
    for r in runs {
        digest.add(r.pair_set.digest.as_bytes());
    }
    let pairs = PairSet {
        pairs: runs.iter().map(|r| r.pair_set.pairs).sum(),
        digest: digest.hex(),
    };
    Some(Claim {
        id: CULLIDE.id.into(),
        claim: "About 3x faster than CULLIDE, and nothing missed".into(),
        paper: "more than 3x over CULLIDE on average over the scenes (Fig. 12); CULLIDE misses \
                26-74% (Table IV), streaming 0%"
            .into(),
        measured: format!(
            "CULLIDE / streaming {mean:.2}x on average over {} scenes ({lo:.2}-{hi:.2}x); \
             CULLIDE missed {mlo:.0}-{mhi:.0}%; streaming equal to SOLID's exact pairs in every \
             frame: {missing_stream} ({})",
            runs.len(),
            verdict.note
        ),
        decided_by: if missing_stream {
            Basis::Timing
        } else {
            Basis::Count
        },
        holds: if missing_stream {
            verdict.holds
        } else {
            Some(false)
        },
        evidence: vec![
            CULLIDE.timing(
                "CULLIDE / streaming, mean over the scenes",
                mean,
                "x",
                true,
                results.scenes_load,
            ),
            Evidence::count(
                "frames whose streaming pairs equal SOLID's exact pairs",
                agreeing as f64,
            ),
            Evidence::pairs("streaming pairs, every scene and frame", &pairs),
            Evidence::count("CULLIDE's misses, highest share of a scene (%)", mhi),
        ],
        ..Claim::default()
    })
}
// endregion

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collide::cullide::CullideResult;
    use crate::collide::pipeline::{FrameResult, Timings};
    use crate::collide::reduction::P0Contents;
    use crate::collide::reduction_gpu::{CalibrationPoint, SchemeCost};
    use crate::report::paper1::bench::{Fig7, Fig7Curve};

    /// A scene whose streaming frame takes `stream_ms` (culling 1 ms, download 1 ms) and
    /// CULLIDE's `cullide_ms`; SOLID culls in `solid_cull_ms`.
    fn scene(name: &str, stream_ms: f64, cullide_ms: f64, solid_cull_ms: f64) -> SceneRun {
        SceneRun {
            name: name.into(),
            frames: 3,
            solid_agrees: 3,
            stream: FrameResult {
                timings: Timings {
                    overlap: 1.0,
                    download: 1.0,
                    total: stream_ms,
                    ..Timings::default()
                },
                ..FrameResult::default()
            },
            cullide: CullideResult {
                pruning_ms: cullide_ms,
                ..CullideResult::default()
            },
            solid_refit: solid_cull_ms,
            frame_times: vec![frame(stream_ms, cullide_ms, solid_cull_ms); 3],
            ..SceneRun::default()
        }
    }

    /// One frame as [`scene`] times it.
    fn frame(stream_ms: f64, cullide_ms: f64, solid_cull_ms: f64) -> FrameTimes {
        FrameTimes {
            stream_cull: 1.0,
            stream_download: 1.0,
            stream_total: stream_ms,
            solid_cull: solid_cull_ms,
            cullide_total: cullide_ms,
            ..FrameTimes::default()
        }
    }

    /// A calibration point with the totals of hierarchical, reduced and full (ms).
    fn point(eta: f64, contents: P0Contents, [h, r, f]: [f64; 3]) -> CalibrationPoint {
        let cost = |scheme, ms| SchemeCost {
            scheme,
            encode_ms: 0.0,
            decode_ms: ms,
            bytes: 1000,
            slowest_ms: ms,
        };
        CalibrationPoint {
            eta,
            contents,
            caps: 1,
            caps_per_set_p1_texel: 1.0,
            runs: 1,
            schemes: vec![
                cost(Scheme::Hierarchical, h),
                cost(Scheme::Reduced, r),
                cost(Scheme::Full, f),
            ],
        }
    }

    fn curve(contents: P0Contents, totals: &[(f64, [f64; 3])]) -> Fig7Curve {
        let points: Vec<_> = totals
            .iter()
            .map(|&(eta, t)| point(eta, contents, t))
            .collect();
        Fig7Curve {
            crossover_eta: crate::collide::reduction_gpu::crossover(&points),
            auto_switch_eta: None,
            points,
        }
    }

    fn results(scenes: Vec<SceneRun>, p0: usize, clustered: &[(f64, [f64; 3])]) -> Paper1Results {
        Paper1Results {
            scenes,
            fig7: Fig7 {
                p0,
                clustered: curve(P0Contents::Clustered, clustered),
                uniform: curve(P0Contents::Uniform, &[(1e-4, [1.0, 1.0, 1.0])]),
            },
            ..Paper1Results::default()
        }
    }

    fn judged<'a>(claims: &'a [Claim], start: &str) -> &'a Claim {
        claims
            .iter()
            .find(|c| c.claim.starts_with(start))
            .unwrap_or_else(|| panic!("no claim '{start}'"))
    }

    #[test]
    fn three_times_cullide_is_an_average_over_the_scenes() {
        // 2x and 5x: not 3x in every scene, but 3.5x on average.
        let r = results(
            vec![
                scene("interlocking-tori", 10.0, 20.0, 0.0),
                scene("bump-bunnies", 10.0, 50.0, 0.0),
            ],
            PAPER_P0,
            &[],
        );
        let c = claims(&r);
        assert_eq!(judged(&c, "About 3x").holds, Some(true));
        let r = results(
            vec![
                scene("interlocking-tori", 10.0, 20.0, 0.0),
                scene("bump-bunnies", 10.0, 35.0, 0.0),
            ],
            PAPER_P0,
            &[],
        );
        assert_eq!(judged(&claims(&r), "About 3x").holds, Some(false));
        // A missed pair fails it whatever the speed.
        let mut missing = scene("touching-tori", 1.0, 100.0, 0.0);
        missing.solid_agrees = 2;
        let r = results(vec![missing], PAPER_P0, &[]);
        assert_eq!(judged(&claims(&r), "About 3x").holds, Some(false));
    }

    #[test]
    fn the_readback_bound_counts_only_the_papers_two_schemes() {
        // Full readback is fast, but hierarchical and reduced both take 8 ms at 1%.
        let slow = [(1e-4, [1.0, 2.0, 0.5]), (1e-2, [9.0, 8.0, 0.5])];
        let c = claims(&results(Vec::new(), PAPER_P0, &slow));
        assert_eq!(judged(&c, "With the scheme chosen").holds, Some(false));
        let fast = [(1e-4, [1.0, 2.0, 0.5]), (1e-2, [9.0, 7.0, 0.5])];
        let c = claims(&results(Vec::new(), PAPER_P0, &fast));
        assert_eq!(judged(&c, "With the scheme chosen").holds, Some(true));
        // The claim is for 2048 x 2048: a quick run's 512 x 512 is not judged.
        let c = claims(&results(Vec::new(), 512, &fast));
        assert_eq!(judged(&c, "With the scheme chosen").holds, None);
    }

    #[test]
    fn the_sparse_readback_claim_is_judged_by_time_below_the_papers_threshold() {
        // Hierarchical faster than reduced below 0.095% (full readback faster still, and
        // the bytes do not matter): holds.
        let pays = [
            (1e-5, [1.0, 2.0, 0.1]),
            (6e-4, [1.5, 2.0, 0.1]),
            (1e-2, [5.0, 2.0, 0.1]),
        ];
        let c = claims(&results(Vec::new(), PAPER_P0, &pays));
        let claim = judged(&c, "Below eta = 0.095%");
        assert_eq!(claim.holds, Some(true));
        assert!(
            claim.measured.contains("from eta = 1.0000%"),
            "{}",
            claim.measured
        );
        // Reduced faster at 0.06%: the hierarchy stopped paying before the paper's threshold.
        let early = [(1e-5, [1.0, 2.0, 0.1]), (6e-4, [2.5, 2.0, 0.1])];
        let c = claims(&results(Vec::new(), PAPER_P0, &early));
        let claim = judged(&c, "Below eta = 0.095%");
        assert_eq!(claim.holds, Some(false));
        // Said once: "faster from 0.06%", not again as "slower at 0.06%".
        assert!(
            claim.measured.contains("faster from eta = 0.0600%")
                && claim.measured.matches("0.0600%").count() == 1,
            "{}",
            claim.measured
        );
        // A loss below the crossover is not covered by "faster from": it is named.
        let dip = [
            (1e-5, [3.0, 2.0, 0.1]),
            (6e-4, [1.0, 2.0, 0.1]),
            (1e-2, [5.0, 2.0, 0.1]),
        ];
        let c = claims(&results(Vec::new(), PAPER_P0, &dip));
        let claim = judged(&c, "Below eta = 0.095%");
        assert_eq!(claim.holds, Some(false));
        assert!(
            claim
                .measured
                .contains("also the slower one at eta = 0.0010%"),
            "{}",
            claim.measured
        );
    }

    #[test]
    fn frames_on_both_sides_of_the_papers_number_are_not_judged() {
        // 3.5x on average from the medians, but one frame of each scene at 2x: the mean
        // over the scenes is 3x or more only at one end of the frames.
        let mut tori = scene("interlocking-tori", 10.0, 35.0, 30.0);
        tori.frame_times[0].cullide_total = 20.0;
        let r = results(vec![tori.clone()], PAPER_P0, &[]);
        let claim = judged(&claims(&r), "About 3x").clone();
        assert_eq!(claim.holds, None, "{}", claim.measured);
        assert!(
            claim.measured.contains("not judged: the mean"),
            "{}",
            claim.measured
        );
        assert!(
            claim.measured.contains("3 timed frames per scene"),
            "{}",
            claim.measured
        );
        // A slow frame of the tori over 29.35 ms leaves "interactive" undecided too.
        tori.frame_times[1].stream_total = 31.0;
        let r = results(vec![tori], PAPER_P0, &[]);
        assert_eq!(judged(&claims(&r), "A whole frame").holds, None);
        // Hierarchical's slowest run slower than reduced's fastest: the runs overlap.
        let mut r = results(Vec::new(), PAPER_P0, &[(1e-5, [1.0, 2.0, 0.1])]);
        r.fig7.clustered.points[0].schemes[0].slowest_ms = 2.5;
        let claim = judged(&claims(&r), "Below eta = 0.095%").clone();
        assert_eq!(claim.holds, None, "{}", claim.measured);
        assert!(
            claim.measured.contains("runs overlap"),
            "{}",
            claim.measured
        );
    }

    #[test]
    fn timing_claims_are_not_judged_on_a_loaded_machine() {
        let mut r = results(
            vec![scene("interlocking-tori", 10.0, 50.0, 30.0)],
            PAPER_P0,
            &[(1e-5, [1.0, 2.0, 0.1])],
        );
        let loaded = Some(crate::timing::Load {
            one_minute: 12.0,
            cores: 2,
        });
        r.scenes_load = loaded;
        r.fig7_load = loaded;
        for claim in claims(&r) {
            assert_eq!(claim.holds, None, "{}", claim.claim);
            assert!(
                claim.measured.contains("not judged: machine loaded"),
                "{}",
                claim.measured
            );
        }
        // A missed pair is a definite no, loaded or not.
        let mut missing = scene("touching-tori", 1.0, 100.0, 0.0);
        missing.solid_agrees = 2;
        let mut r = results(vec![missing], PAPER_P0, &[]);
        r.scenes_load = loaded;
        assert_eq!(judged(&claims(&r), "About 3x").holds, Some(false));
    }

    #[test]
    fn solid_is_judged_with_and_without_the_download() {
        // Culling 1 ms, download 1 ms. SOLID 3 ms: 3x without, 1.5x with the download.
        let r = results(vec![scene("touching-tori", 5.0, 50.0, 3.0)], 512, &[]);
        assert_eq!(judged(&claims(&r), "Streaming culling").holds, Some(true));
        // SOLID 2.6 ms: 2.6x without, but 1.3x with the download.
        let r = results(vec![scene("touching-tori", 5.0, 50.0, 2.6)], 512, &[]);
        assert_eq!(judged(&claims(&r), "Streaming culling").holds, Some(false));
        // A download of 0.1 ms and SOLID 1.8 ms: 1.64x with it, but 1.8x without, under 2x.
        let mut light = scene("touching-tori", 5.0, 50.0, 1.8);
        light.stream.timings.download = 0.1;
        let r = results(vec![light], 512, &[]);
        assert_eq!(judged(&claims(&r), "Streaming culling").holds, Some(false));
    }

    #[test]
    fn no_results_no_claims() {
        assert!(claims(&Paper1Results::default()).is_empty());
    }
}
