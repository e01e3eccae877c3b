//! The paper's claims, each judged on the measured results.

use super::bench::{Paper2Results, Variant};
use crate::crowd::scene::RunStats;
use crate::crowd::ModelKind;
use crate::report::versions::TIMING_POLICY;
use crate::report::{Basis, Claim, ClaimDef, Evidence};
use crate::timing::{faster, judge_ends, judge_under_load, Ends, Spread};

/// Every claim of the section, with what decides it.
pub const CLAIMS: &[ClaimDef] = &[OVERTAKES_VS, OVERTAKES_VS_SINGLE, STAGE_COSTS, SINGLE_DRAW];

pub fn claims(results: &Paper2Results) -> Vec<Claim> {
    let mut claims = vec![
        crossover(results, Variant::VertexShader),
        crossover(results, Variant::VertexShaderSingle),
    ];
    claims.extend(stage_costs(results));
    claims.push(single_draw(results));
    claims
}

// region: rule single-draw
/// Section 2: every character skinned in one draw call where the crowd fits a target.
const SINGLE_DRAW: ClaimDef = ClaimDef {
    id: "paper2.single-draw",
    rule: &["src/report/paper2/claims.rs#rule single-draw"],
    published: &[],
    workload: &[
        "src/report/paper2/bench.rs#workload quick-counts",
        "src/report/paper2/bench.rs#workload counts",
        "src/report/paper2/bench.rs#workload frames",
    ],
    band: None,
};

/// Section 2: "through a single drawcall, all vertices of all characters are transformed".
/// Judged on the method, not on the run's sizes: every two-pass run of Table 1 skinned its
/// crowd in as few draws as the render target allows, one where the crowd fits one target
/// (the texture limit sets how many characters that is, so `--quick` and the full run differ
/// only in how many runs are past it); and at least one run fitted, so one draw was seen.
pub fn single_draw(results: &Paper2Results) -> Claim {
    let two_pass: Vec<_> = results
        .table1
        .iter()
        .filter(|r| Variant::of(r) == Variant::TwoPass && !r.lod_and_culling)
        .collect();
    // Characters one pass-1 draw holds at LOD 0 for a model (Table 1 runs without LODs).
    let per_draw = |model: &str| {
        results
            .models
            .iter()
            .find(|m| m.model.name() == model)
            .and_then(|m| m.lods.first())
            .map(|lod0| lod0.characters_per_draw.max(1))
    };
    let needed = |r: &RunStats| per_draw(&r.model).map(|per| r.characters.div_ceil(per));
    let fitted = two_pass.iter().filter(|r| needed(r) == Some(1)).count();
    let past = two_pass.len() - fitted;
    let off: Vec<String> = two_pass
        .iter()
        .filter(|r| needed(r) != Some(r.passes.pass1_draws))
        .map(|r| {
            format!(
                "{} x {}: {} draws where {} would do",
                r.model,
                r.characters,
                r.passes.pass1_draws,
                needed(r).map_or("?".into(), |n| n.to_string())
            )
        })
        .collect();
    let limits: Vec<String> = results
        .models
        .iter()
        .filter_map(|m| {
            let lod0 = m.lods.first()?;
            Some(format!(
                "{} {}s of {} vertices",
                lod0.characters_per_draw,
                m.model.name(),
                lod0.vertices
            ))
        })
        .collect();
    Claim {
        id: SINGLE_DRAW.id.into(),
        claim: "All vertices of all characters are skinned in a single draw call (pass 1), \
                where the crowd fits one render target"
            .into(),
        paper: "Section 2: one draw call over a render target of n characters x m vertices".into(),
        measured: format!(
            "draws counted per frame: {fitted} two-pass runs of Table 1 fit one target and each \
             took {}; {past} larger ones took one draw per target-full, as the limit requires \
             ({}). The limit is the renderer's, not the method's: one draw holds at most {} at \
             LOD 0 ({}-texel targets, rows of {} characters), so the run's sizes decide only how \
             many runs are past it ({})",
            if off.is_empty() { "one" } else { "NOT one" },
            if off.is_empty() {
                "all as counted".to_string()
            } else {
                off.join("; ")
            },
            limits.join(" or "),
            results.setup.max_texture_size,
            results.setup.row_characters,
            results.renderer
        ),
        decided_by: Basis::Count,
        holds: Some(fitted > 0 && off.is_empty()),
        evidence: vec![
            Evidence::count("two-pass runs whose crowd fits one target", fitted as f64),
            Evidence::count(
                "two-pass runs not in the draws the target's limit requires",
                off.len() as f64,
            ),
        ],
        ..Claim::default()
    }
}
// endregion

// region: rule overtakes
/// Table 1: two-pass overtakes vertex-shader skinning (instanced).
const OVERTAKES_VS: ClaimDef = ClaimDef {
    id: "paper2.overtakes-vs",
    rule: &["src/report/paper2/claims.rs#rule overtakes", TIMING_POLICY],
    published: &["paper2.table1"],
    workload: &[
        "src/report/paper2/bench.rs#workload quick-counts",
        "src/report/paper2/bench.rs#workload counts",
        "src/report/paper2/bench.rs#workload frames",
    ],
    band: Some(0.25),
};

/// Table 1: two-pass overtakes vertex-shader skinning, one character per draw.
const OVERTAKES_VS_SINGLE: ClaimDef = ClaimDef {
    id: "paper2.overtakes-vs-one-per-draw",
    rule: &["src/report/paper2/claims.rs#rule overtakes", TIMING_POLICY],
    published: &["paper2.table1"],
    workload: &[
        "src/report/paper2/bench.rs#workload quick-counts",
        "src/report/paper2/bench.rs#workload counts",
        "src/report/paper2/bench.rs#workload frames",
    ],
    band: Some(0.25),
};

/// Table 1: the vertex shader wins at one character, two-pass from 16 on. Holds when, for
/// both models, two-pass is faster than `baseline` from some measured n > 1, n <= 16, at
/// every larger measured n.
pub fn crossover(results: &Paper2Results, baseline: Variant) -> Claim {
    let counts = results.counts();
    // The paper's two halves for one model: the baseline faster at the first count (one
    // character), two-pass faster at every count from 16 on. Each comparison takes every
    // measurement's frames at the end that favours the claim (`favour`) or at the other end.
    let holds_at = |favour: bool| {
        ModelKind::ALL.iter().all(|&kind| {
            let frames = |n, v| Paper2Results::find(&results.table1, kind, n, v).map(frames);
            let two_pass_faster = |n, favour| {
                frames(n, Variant::TwoPass)
                    .zip(frames(n, baseline))
                    .map(|(two_pass, other)| faster(&two_pass, &other, favour))
            };
            let baseline_first = counts
                .first()
                .is_some_and(|&n| two_pass_faster(n, !favour).is_some_and(|faster| !faster));
            let from_16 = counts.iter().filter(|&&n| n >= 16);
            baseline_first
                && counts.iter().any(|&n| n >= 16)
                && from_16
                    .map(|&n| two_pass_faster(n, favour))
                    .all(|f| f == Some(true))
        })
    };
    let mut parts = Vec::new();
    for kind in ModelKind::ALL {
        // The medians say where it crosses; the ends of the frames, whether that is decided.
        let by_median = {
            let faster_at: Vec<bool> = counts
                .iter()
                .map(|&n| {
                    let fps = |v| results.fps(kind, n, v);
                    fps(Variant::TwoPass)
                        .zip(fps(baseline))
                        .is_some_and(|(two_pass, other)| two_pass > other)
                })
                .collect();
            (0..counts.len()).find(|&i| faster_at[i..].iter().all(|&f| f))
        };
        parts.push(match by_median {
            Some(i) => format!("{}: two-pass faster from n = {} on", kind.name(), counts[i]),
            None => format!(
                "{}: no crossover up to n = {}",
                kind.name(),
                counts.last().copied().unwrap_or(0)
            ),
        });
    }
    let frame_counts: Vec<usize> = results.table1.iter().map(|r| r.frames).collect();
    let runs = format!(
        "medians of {}-{} interleaved timed frames per measurement, each judged with its \
         fastest and slowest frame",
        frame_counts.iter().min().unwrap_or(&0),
        frame_counts.iter().max().unwrap_or(&0)
    );
    let verdict = judge_ends(
        Ends::of(holds_at),
        &runs,
        "the frames of two-pass and of the baseline overlap where it would cross",
        results.table1_load,
    );
    let def = if baseline == Variant::VertexShader {
        OVERTAKES_VS
    } else {
        OVERTAKES_VS_SINGLE
    };
    // Two-pass frame time over the baseline's at the largest crowd, per model (medians).
    let largest = counts.last().copied().unwrap_or(0);
    let evidence = ModelKind::ALL
        .iter()
        .filter_map(|&kind| {
            let fps = |v| results.fps(kind, largest, v);
            let (two_pass, other) = (fps(Variant::TwoPass)?, fps(baseline)?);
            Some(def.timing(
                &format!(
                    "{}: two-pass / baseline frame time at n = {largest}",
                    kind.name()
                ),
                other / two_pass,
                "x",
                false,
                results.table1_load,
            ))
        })
        .collect();
    Claim {
        id: def.id.into(),
        claim: format!(
            "Two-pass (pixel-shader) skinning overtakes vertex-shader skinning ({}) once there \
             are enough characters",
            baseline.label()
        ),
        paper: "VS is faster for 1 character; two-pass is faster from 16 characters on (Table 1, \
                GeForce 7800 GTX)"
            .into(),
        measured: format!(
            "{} ({}; {})",
            parts.join("; "),
            results.renderer,
            verdict.note
        ),
        decided_by: Basis::Timing,
        holds: verdict.holds,
        evidence,
        ..Claim::default()
    }
}

/// A measurement's timed frames as runs (ms).
fn frames(run: &RunStats) -> Spread {
    Spread {
        runs: run.frames,
        median: run.frame_ms,
        min: run.frame_ms_range[0],
        max: run.frame_ms_range[1],
    }
}
// endregion

// region: rule stage-costs
/// Implied by Table 1: two-pass GPU work costs less than vertex-shader skinning.
const STAGE_COSTS: ClaimDef = ClaimDef {
    id: "paper2.two-pass-costs-less",
    rule: &[
        "src/report/paper2/claims.rs#rule stage-costs",
        TIMING_POLICY,
    ],
    published: &["paper2.table1"],
    workload: &[
        "src/report/paper2/bench.rs#workload quick-counts",
        "src/report/paper2/bench.rs#workload counts",
        "src/report/paper2/bench.rs#workload frames",
    ],
    // Twice the most it moved between three llvmpipe runs of one build, 2 cores (57%).
    band: Some(1.15),
};

/// Why the crossover does or does not happen: at the largest crowd, the two-pass GPU work
/// (pass 1 + copy + pass 2) against the vertex-shader stage (skinning and drawing).
pub fn stage_costs(results: &Paper2Results) -> Option<Claim> {
    let n = *results.counts().last()?;
    let mut parts = Vec::new();
    let mut evidence = Vec::new();
    let mut holds = true;
    for kind in ModelKind::ALL {
        let tp = Paper2Results::find(&results.table1, kind, n, Variant::TwoPass)?;
        let vs = Paper2Results::find(&results.table1, kind, n, Variant::VertexShader)?;
        let w = &tp.passes.wall;
        let two_pass = w.pass1 + w.copy + w.pass2;
        let baseline = vs.passes.wall.vertex_shader;
        holds &= two_pass < baseline;
        evidence.push(STAGE_COSTS.timing(
            &format!(
                "{}: two-pass GPU work / VS skinning and drawing at n = {n}",
                kind.name()
            ),
            two_pass / baseline,
            "x",
            false,
            results.table1_load,
        ));
        parts.push(format!(
            "{} x {n}: pass 1 {:.1} + copy {:.1} + pass 2 {:.1} = {two_pass:.1} ms against \
             {baseline:.1} ms for VS skinning and drawing (pass 2 alone is {:.0}% of it)",
            kind.name(),
            w.pass1,
            w.copy,
            w.pass2,
            100.0 * w.pass2 / baseline
        ));
    }
    // The passes come from one profiled frame per configuration: one run, no spread.
    let mut verdict = judge_under_load(holds, results.table1_load);
    verdict.note = format!(
        "one profiled frame per configuration, a single run; {}",
        verdict.note
    );
    Some(Claim {
        id: STAGE_COSTS.id.into(),
        claim: "Skinning once in a pixel shader and drawing pre-skinned vertices costs the GPU \
                less than skinning in the vertex shader while drawing"
            .into(),
        paper: "Implied by Table 1: 2-pass is 3.6-7x faster than VS from 256 characters on".into(),
        measured: format!(
            "{} ({}; {})",
            parts.join("; "),
            results.renderer,
            verdict.note
        ),
        decided_by: Basis::Timing,
        holds: verdict.holds,
        evidence,
        ..Claim::default()
    })
}
// endregion

#[cfg(test)]
mod tests {
    use super::*;
    use crate::crowd::{LodPolicy, Method};
    use crate::report::paper2::bench::Setup;
    use crate::timing::Load;

    /// One Table 1 measurement: `frames` frame times as (median, fastest, slowest) ms.
    fn run(kind: ModelKind, n: usize, variant: Variant, [median, lo, hi]: [f64; 3]) -> RunStats {
        let (method, batch) = match variant {
            Variant::TwoPass => (Method::TwoPass, 0),
            Variant::VertexShader => (Method::VertexShader, 64),
            Variant::VertexShaderSingle => (Method::VertexShader, 1),
        };
        RunStats {
            model: kind.name().into(),
            method: method.name().into(),
            vertex_shader_batch: batch,
            characters: n,
            frames: 5,
            frame_ms: median,
            frame_ms_range: [lo, hi],
            fps: 1e3 / median,
            ..RunStats::default()
        }
    }

    /// Two-pass against the vertex shader at 1, 16 and 64 characters, both models alike:
    /// `two_pass[i]` and `vs[i]` are the (median, fastest, slowest) frame times.
    fn results(two_pass: [[f64; 3]; 3], vs: [[f64; 3]; 3]) -> Paper2Results {
        let mut table1 = Vec::new();
        for kind in ModelKind::ALL {
            for (i, n) in [1, 16, 64].into_iter().enumerate() {
                table1.push(run(kind, n, Variant::TwoPass, two_pass[i]));
                table1.push(run(kind, n, Variant::VertexShader, vs[i]));
            }
        }
        Paper2Results {
            renderer: "test".into(),
            quick: true,
            size: [64, 64],
            setup: Setup {
                max_texture_size: 4096,
                row_characters: 64,
                lod_divisor: 1,
                lod_policy: LodPolicy::default(),
                sprite_policy: LodPolicy::with_sprites(),
            },
            models: Vec::new(),
            table1,
            lod_runs: Vec::new(),
            sprite_runs: Vec::new(),
            snapshots: Vec::new(),
            then_and_now: Default::default(),
            profile: None,
            table1_load: Some(Load {
                one_minute: 0.3,
                cores: 2,
            }),
        }
    }

    #[test]
    fn the_crossover_is_judged_on_the_ends_of_the_frames() {
        let vs = [[1.0, 0.9, 1.1], [10.0, 9.5, 10.5], [40.0, 39.0, 41.0]];
        // Two-pass slower at 1, faster from 16 on, every frame apart: holds.
        let apart = [[2.0, 1.9, 2.1], [8.0, 7.5, 8.5], [20.0, 19.0, 21.0]];
        let c = crossover(&results(apart, vs), Variant::VertexShader);
        assert_eq!(c.holds, Some(true), "{}", c.measured);
        assert!(c.measured.contains("from n = 16 on"), "{}", c.measured);
        // The same medians, but at 16 the frames overlap: where it crosses is not decided.
        let overlap = [[2.0, 1.9, 2.1], [8.0, 7.5, 11.0], [20.0, 19.0, 21.0]];
        let c = crossover(&results(overlap, vs), Variant::VertexShader);
        assert_eq!(c.holds, None, "{}", c.measured);
        assert!(
            c.measured.contains("not judged: the frames"),
            "{}",
            c.measured
        );
        // Slower at 64 in every frame: no, however the frames at 16 fall.
        let late = [[2.0, 1.9, 2.1], [8.0, 7.5, 11.0], [50.0, 49.0, 51.0]];
        let c = crossover(&results(late, vs), Variant::VertexShader);
        assert_eq!(c.holds, Some(false), "{}", c.measured);
        // Two-pass faster already at one character: the paper's first half fails.
        let early = [[0.5, 0.4, 0.6], [8.0, 7.5, 8.5], [20.0, 19.0, 21.0]];
        let c = crossover(&results(early, vs), Variant::VertexShader);
        assert_eq!(c.holds, Some(false), "{}", c.measured);
    }
}
