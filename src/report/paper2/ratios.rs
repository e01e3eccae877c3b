//! Table 1 as ratios: two-pass over vertex-shader frame rate, the paper's and ours against
//! both baselines, so hardware generations compare by shape rather than by speed.

use super::bench::{Paper2Results, Variant};
use super::table1::paper_fps;
use crate::crowd::ModelKind;
use crate::report::published::Paper2Table1;
use crate::report::Table;

pub fn table(results: &Paper2Results, paper: &Paper2Table1) -> Table {
    let mut table = Table {
        caption: "Two-pass / vertex-shader frame-rate ratio (> 1: the paper's method is faster)"
            .into(),
        header: vec!["n".into()],
        rows: Vec::new(),
    };
    for kind in ModelKind::ALL {
        for label in ["paper", "here vs VS", "here vs VS 1/draw"] {
            table.header.push(format!("{} {label}", kind.name()));
        }
    }
    let ratio = |a: Option<f64>, b: Option<f64>| {
        a.zip(b)
            .map_or("-".to_string(), |(a, b)| format!("{:.2}", a / b))
    };
    for n in results.counts() {
        let mut row = vec![n.to_string()];
        for kind in ModelKind::ALL {
            let published = paper_fps(paper, kind, n);
            let two_pass = results.fps(kind, n, Variant::TwoPass);
            row.extend([
                ratio(published.map(|p| p.1), published.map(|p| p.0)),
                ratio(two_pass, results.fps(kind, n, Variant::VertexShader)),
                ratio(two_pass, results.fps(kind, n, Variant::VertexShaderSingle)),
            ]);
        }
        table.rows.push(row);
    }
    table
}
