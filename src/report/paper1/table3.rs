//! Table III: the streaming pipeline per frame, each scene beside the paper's row.

use super::bench::Paper1Results;
use super::{f2, header};
use crate::collide::scenes::SCENES;
use crate::report::published::{Paper1, Paper1Table3Row};
use crate::report::Table;

/// The paper's row for scene `name` (Table III lists the scenes in [`SCENES`]' order).
fn published<'a>(paper: &'a Paper1, name: &str) -> Option<&'a Paper1Table3Row> {
    let i = SCENES.iter().position(|&s| s == name)?;
    paper.table3.get(i)
}

pub fn table(results: &Paper1Results, paper: &Paper1) -> Table {
    let rows = results
        .scenes
        .iter()
        .map(|r| {
            let p = published(paper, &r.name);
            let cell = |f: fn(&Paper1Table3Row) -> String| p.map_or("-".into(), f);
            let t = &r.stream.timings;
            vec![
                r.label.clone(),
                format!("{}x2", r.triangles),
                r.stream.caps.to_string(),
                cell(|p| p.caps.to_string()),
                r.stream.pctps.to_string(),
                cell(|p| p.pctps.to_string()),
                r.stream.ctps.to_string(),
                cell(|p| p.ctps.to_string()),
                f2(t.overlap),
                cell(|p| p.overlap.to_string()),
                format!("{:.2}/{:.2}", t.encode, t.readback),
                cell(|p| format!("{}/{}", p.readback_encode, p.readback_decode)),
                f2(t.tri_test),
                cell(|p| p.tri_test.to_string()),
                f2(t.download),
                cell(|p| p.texture_download.to_string()),
                f2(t.update),
                cell(|p| p.stream_update.to_string()),
                f2(t.total),
                cell(|p| p.total.to_string()),
                r.schemes.join("+"),
            ]
        })
        .collect();
    Table {
        caption: format!(
            "Table III: streaming AABBs per frame, mean of {} frames ({}); paper (GeForce 7800 \
             GTX) in the (paper) columns",
            results.setup.frames, results.renderer
        ),
        header: header(&[
            "scene",
            "nTris",
            "nCAPs",
            "(paper)",
            "nPCTPs",
            "(paper)",
            "nCTPs",
            "(paper)",
            "overlap",
            "(paper)",
            "readback enc/dec",
            "(paper)",
            "tri test",
            "(paper)",
            "download",
            "(paper)",
            "update",
            "(paper)",
            "total",
            "(paper)",
            "scheme",
        ]),
        rows,
    }
}
