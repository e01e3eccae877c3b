//! Table IV: CULLIDE on the same scenes and frames, beside the paper's row.

use super::bench::Paper1Results;
use super::{f2, header};
use crate::collide::scenes::SCENES;
use crate::report::published::{Paper1, Paper1Table4Row};
use crate::report::Table;

/// The paper's row for scene `name` (Table IV lists the scenes in [`SCENES`]' order).
fn published<'a>(paper: &'a Paper1, name: &str) -> Option<&'a Paper1Table4Row> {
    let i = SCENES.iter().position(|&s| s == name)?;
    paper.table4.get(i)
}

pub fn table(results: &Paper1Results, paper: &Paper1) -> Table {
    let rows = results
        .scenes
        .iter()
        .map(|r| {
            let p = published(paper, &r.name);
            let cell = |f: fn(&Paper1Table4Row) -> String| p.map_or("-".into(), f);
            let c = &r.cullide;
            vec![
                r.label.clone(),
                f2(c.pruning_ms),
                cell(|p| p.pruning.to_string()),
                f2(c.tri_test_ms),
                cell(|p| p.tri_test.to_string()),
                c.pctps.to_string(),
                cell(|p| p.pctps.to_string()),
                c.ctps.to_string(),
                cell(|p| p.ctps.to_string()),
                format!("{:.0}", r.cullide_missing_percent),
                cell(|p| p.missing_percent.to_string()),
                c.queries.to_string(),
            ]
        })
        .collect();
    let resolution = results.setup.cullide_resolution;
    Table {
        caption: format!(
            "Table IV: CULLIDE at {resolution}x{resolution}, mean per frame ({}); missing = \
             exact pairs CULLIDE did not report",
            results.renderer
        ),
        header: header(&[
            "scene",
            "pruning",
            "(paper)",
            "tri test",
            "(paper)",
            "PCTPs",
            "(paper)",
            "CTPs",
            "(paper)",
            "missing %",
            "(paper)",
            "queries",
        ]),
        rows,
    }
}
