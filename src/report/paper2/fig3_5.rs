//! Fig. 3-5: the frame rates of the paper's snapshot scenes, 1,024 soldiers at full detail
//! (Fig. 3) and the LOD runs of 10,240 soldiers and 5,120 horses (Fig. 4-5), beside the
//! averages the paper quotes. The LOD runs are the paper's setup (three meshes, culling, no
//! sprites); the same crowds with this project's sprite level follow in rows of their own,
//! marked as an extension.

use super::bench::{lod_divisor, Paper2Results, Variant};
use crate::crowd::scene::RunStats;
use crate::crowd::ModelKind;
use crate::report::published;
use crate::report::Table;

pub fn table(results: &Paper2Results, paper: &published::Paper2) -> Table {
    let mut table = Table {
        caption: format!(
            "Fig. 3-5: frames per second of the snapshot scenes, on {}; Fig. 4-5 in the paper's \
             setup, three LOD meshes (1,084 / 544 / 312 polygons) and view-frustum culling, no \
             sprites; the rows marked 'extension' draw the same crowds with sprites beyond {} m \
             (not in the paper); pass-1 draws: one per LOD mesh in use and batch",
            results.renderer,
            results
                .setup
                .sprite_policy
                .sprites_beyond
                .map_or("-".to_string(), |d| format!("{d:.0}"))
        ),
        header: [
            "figure",
            "model",
            "n",
            "paper FPS",
            "2-pass here",
            "VS here",
            "LOD 0/1/2",
            "sprites",
            "culled",
            "pass-1 draws",
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    let mut extensions = Vec::new();
    for run in &paper.runs {
        let Ok(kind) = run.model.parse::<ModelKind>() else {
            continue;
        };
        let n = if run.lod_and_culling {
            run.characters / lod_divisor(results.quick)
        } else {
            run.characters
        };
        let published = if n == run.characters {
            format!("{:.0}", run.fps)
        } else {
            format!("{:.0} (at {})", run.fps, run.characters)
        };
        let source = if run.lod_and_culling {
            &results.lod_runs
        } else {
            &results.table1
        };
        if let Some(cells) = row(source, kind, n) {
            table.rows.push(
                [
                    vec![
                        run.figure.clone(),
                        run.model.clone(),
                        n.to_string(),
                        published,
                    ],
                    cells,
                ]
                .concat(),
            );
        }
        if run.lod_and_culling {
            if let Some(cells) = row(&results.sprite_runs, kind, n) {
                extensions.push(
                    [
                        vec![
                            format!("{} + sprites (extension)", run.figure),
                            run.model.clone(),
                            n.to_string(),
                            "- (not in the paper)".into(),
                        ],
                        cells,
                    ]
                    .concat(),
                );
            }
        }
    }
    table.rows.extend(extensions);
    table
}

/// The measured cells of `kind` x `n` in `runs`: both methods' frame rates and the
/// two-pass frame's plan.
fn row(runs: &[RunStats], kind: ModelKind, n: usize) -> Option<Vec<String>> {
    let find = |v| Paper2Results::find(runs, kind, n, v);
    let (tp, vs) = (find(Variant::TwoPass)?, find(Variant::VertexShader)?);
    Some(vec![
        format!("{:.1}", tp.fps),
        format!("{:.1}", vs.fps),
        format!("{} / {} / {}", tp.per_lod[0], tp.per_lod[1], tp.per_lod[2]),
        tp.passes.sprites.to_string(),
        tp.culled.to_string(),
        tp.passes.pass1_draws.to_string(),
    ])
}
