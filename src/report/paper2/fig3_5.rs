//! Fig. 3-5: the frame rates of the paper's snapshot scenes, 1,024 soldiers at full detail
//! (Fig. 3) and the LOD runs of 10,240 soldiers and 5,120 horses (Fig. 4-5), beside the
//! averages the paper quotes.

use super::bench::{lod_divisor, Paper2Results, Variant};
use crate::report::published;
use crate::report::Table;

pub fn table(results: &Paper2Results, paper: &published::Paper2) -> Table {
    let mut table = Table {
        caption: "Fig. 3-5: frames per second of the snapshot scenes; Fig. 4-5 with LOD (1,084 / \
                  544 / 312 polygons), sprites and view-frustum culling"
            .into(),
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
        ]
        .map(String::from)
        .to_vec(),
        rows: Vec::new(),
    };
    for run in &paper.runs {
        let Ok(kind) = run.model.parse() else {
            continue;
        };
        let (n, source) = if run.lod_and_culling {
            (
                run.characters / lod_divisor(results.quick),
                &results.lod_runs,
            )
        } else {
            (run.characters, &results.table1)
        };
        let find = |v| Paper2Results::find(source, kind, n, v);
        let (Some(tp), Some(vs)) = (find(Variant::TwoPass), find(Variant::VertexShader)) else {
            continue;
        };
        table.rows.push(vec![
            run.figure.clone(),
            run.model.clone(),
            n.to_string(),
            if n == run.characters {
                format!("{:.0}", run.fps)
            } else {
                format!("{:.0} (at {})", run.fps, run.characters)
            },
            format!("{:.1}", tp.fps),
            format!("{:.1}", vs.fps),
            format!("{} / {} / {}", tp.per_lod[0], tp.per_lod[1], tp.per_lod[2]),
            tp.passes.sprites.to_string(),
            tp.culled.to_string(),
        ]);
    }
    table
}
