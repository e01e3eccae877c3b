//! Table 1: frames per second of vertex-shader and two-pass skinning against the number of
//! characters, beside the paper's, as a table and as one plot per model.

use super::bench::{Paper2Results, Variant};
use crate::crowd::ModelKind;
use crate::page::plot::{Plot, Series};
use crate::report::published::Paper2Table1;
use crate::report::{BenchOptions, Figure, Table};

/// The paper's frame rates of `kind` (VS, 2-pass) at `n` characters, when it has the row.
pub fn paper_fps(paper: &Paper2Table1, kind: ModelKind, n: usize) -> Option<(f64, f64)> {
    let (vs, two_pass) = match kind {
        ModelKind::Soldier => (&paper.soldier_vs, &paper.soldier_two_pass),
        ModelKind::Horse => (&paper.horse_vs, &paper.horse_two_pass),
    };
    let i = paper.characters.iter().position(|&c| c == n)?;
    Some((*vs.get(i)?, *two_pass.get(i)?))
}

/// A frame rate, or "-" where there is none.
pub fn show(fps: Option<f64>, decimals: usize) -> String {
    fps.map_or("-".to_string(), |v| format!("{v:.decimals$}"))
}

pub fn table(results: &Paper2Results, paper: &Paper2Table1) -> Table {
    let [w, h] = results.size;
    let mut table = Table {
        caption: format!(
            "Table 1: frames per second, no culling, every character at LOD 0 ({w}x{h}). Paper: \
             GeForce 7800 GTX. Here: {}",
            results.renderer
        ),
        header: vec!["n".into()],
        rows: Vec::new(),
    };
    for kind in ModelKind::ALL {
        for label in [
            "VS paper",
            "VS here",
            "VS 1/draw here",
            "2-pass paper",
            "2-pass here",
        ] {
            table.header.push(format!("{} {label}", kind.name()));
        }
    }
    for n in results.counts() {
        let mut row = vec![n.to_string()];
        for kind in ModelKind::ALL {
            let published = paper_fps(paper, kind, n);
            let here = |v| show(results.fps(kind, n, v), 1);
            row.extend([
                show(published.map(|p| p.0), 0),
                here(Variant::VertexShader),
                here(Variant::VertexShaderSingle),
                show(published.map(|p| p.1), 0),
                here(Variant::TwoPass),
            ]);
        }
        table.rows.push(row);
    }
    table
}

/// One log-log plot per model: the paper's two curves and the three measured here.
pub fn figures(
    opts: &BenchOptions,
    results: &Paper2Results,
    paper: &Paper2Table1,
) -> anyhow::Result<Vec<Figure>> {
    let mut figures = Vec::new();
    for kind in ModelKind::ALL {
        let published = |pick: fn((f64, f64)) -> f64| -> Vec<(f64, f64)> {
            paper
                .characters
                .iter()
                .filter_map(|&n| paper_fps(paper, kind, n).map(|p| (n as f64, pick(p))))
                .collect()
        };
        let here = |v: Variant| -> Vec<(f64, f64)> {
            results
                .counts()
                .into_iter()
                .filter_map(|n| results.fps(kind, n, v).map(|f| (n as f64, f)))
                .collect()
        };
        let plot = Plot {
            title: format!(
                "Table 1, {}: frames per second against crowd size",
                kind.name()
            ),
            x_label: "characters".into(),
            y_label: "frames per second".into(),
            log_x: true,
            log_y: true,
            series: vec![
                Series::new("VS, paper (GeForce 7800 GTX; dashed)", published(|p| p.0))
                    .slot(0)
                    .dashed(),
                Series::new(
                    "2-pass, paper (GeForce 7800 GTX; dashed)",
                    published(|p| p.1),
                )
                .slot(1)
                .dashed(),
                Series::new("VS, here", here(Variant::VertexShader)).slot(0),
                Series::new("2-pass, here", here(Variant::TwoPass)).slot(1),
                Series::new("VS 1/draw, here", here(Variant::VertexShaderSingle)).slot(2),
            ],
        };
        let file = format!("table1_{}.png", kind.name());
        plot.write_png(&opts.out_dir.join(&file))?;
        figures.push(Figure {
            file,
            caption: format!(
                "Table 1 as a plot, {}: the paper's frame rates and this renderer's ({})",
                kind.name(),
                results.renderer
            ),
        });
    }
    Ok(figures)
}
