//! The paper's claims, each judged on the measured results.

use super::bench::{Paper2Results, Variant};
use crate::crowd::ModelKind;
use crate::report::timing::judge_under_load;
use crate::report::Claim;

pub fn claims(results: &Paper2Results) -> Vec<Claim> {
    let mut claims = vec![
        crossover(results, Variant::VertexShader),
        crossover(results, Variant::VertexShaderSingle),
    ];
    claims.extend(stage_costs(results));
    claims.push(single_draw(results));
    claims
}

/// Section 2: "through a single drawcall, all vertices of all characters are transformed".
/// Holds when every measured two-pass run of Table 1 skinned its crowd in one pass-1 draw;
/// the measured text gives the crowd size from which it stops holding on this renderer.
pub fn single_draw(results: &Paper2Results) -> Claim {
    let two_pass: Vec<_> = results
        .table1
        .iter()
        .filter(|r| Variant::of(r) == Variant::TwoPass)
        .collect();
    let most_draws = two_pass
        .iter()
        .max_by_key(|r| (r.passes.pass1_draws, r.characters));
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
        claim: "All vertices of all characters are skinned in a single draw call (pass 1)".into(),
        paper: "Section 2: one draw call over a render target of n characters x m vertices".into(),
        measured: format!(
            "one draw holds at most {} at LOD 0 ({}-texel targets, rows of {} characters); \
             larger crowds are skinned in batches, a draw each; {} ({})",
            limits.join(" or "),
            results.setup.max_texture_size,
            results.setup.row_characters,
            most_draws.map_or("no two-pass run".to_string(), |r| format!(
                "Table 1's {} x {} took {} draw(s)",
                r.model, r.characters, r.passes.pass1_draws
            )),
            results.renderer
        ),
        holds: Some(!two_pass.is_empty() && two_pass.iter().all(|r| r.passes.pass1_draws == 1)),
    }
}

/// Table 1: the vertex shader wins at one character, two-pass from 16 on. Holds when, for
/// both models, two-pass is faster than `baseline` from some measured n > 1, n <= 16, at
/// every larger measured n.
pub fn crossover(results: &Paper2Results, baseline: Variant) -> Claim {
    let counts = results.counts();
    let mut parts = Vec::new();
    let mut holds = true;
    for kind in ModelKind::ALL {
        let faster: Vec<bool> = counts
            .iter()
            .map(|&n| {
                let fps = |v| results.fps(kind, n, v);
                fps(Variant::TwoPass)
                    .zip(fps(baseline))
                    .is_some_and(|(two_pass, other)| two_pass > other)
            })
            .collect();
        match (0..counts.len()).find(|&i| faster[i..].iter().all(|&f| f)) {
            Some(i) => {
                parts.push(format!(
                    "{}: two-pass faster from n = {} on",
                    kind.name(),
                    counts[i]
                ));
                holds &= i > 0 && counts[i] <= 16;
            }
            None => {
                parts.push(format!(
                    "{}: no crossover up to n = {}",
                    kind.name(),
                    counts.last().copied().unwrap_or(0)
                ));
                holds = false;
            }
        }
    }
    let verdict = judge_under_load(holds, results.table1_load);
    Claim {
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
        holds: verdict.holds,
    }
}

/// Why the crossover does or does not happen: at the largest crowd, the two-pass GPU work
/// (pass 1 + copy + pass 2) against the vertex-shader stage (skinning and drawing).
pub fn stage_costs(results: &Paper2Results) -> Option<Claim> {
    let n = *results.counts().last()?;
    let mut parts = Vec::new();
    let mut holds = true;
    for kind in ModelKind::ALL {
        let tp = Paper2Results::find(&results.table1, kind, n, Variant::TwoPass)?;
        let vs = Paper2Results::find(&results.table1, kind, n, Variant::VertexShader)?;
        let w = &tp.passes.wall;
        let two_pass = w.pass1 + w.copy + w.pass2;
        let baseline = vs.passes.wall.vertex_shader;
        holds &= two_pass < baseline;
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
    let verdict = judge_under_load(holds, results.table1_load);
    Some(Claim {
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
        holds: verdict.holds,
    })
}
