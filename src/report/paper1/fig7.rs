//! Fig. 7 (Sec. 5.3.2): readback time of each scheme against `eta`, the share of AABB pairs
//! that collide, on a `P0` filled at each `eta` with clustered CAPs (as contacts make them,
//! what Sec. 5.3.1 counts on) and with uniformly random ones.

use super::bench::{Fig7Curve, Paper1Results};
use super::{f2, header};
use crate::collide::reduction::P0Contents;
use crate::collide::reduction_gpu::{SchemeCost, PAPER_ETA_THRESHOLD};
use crate::page::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};

/// The two curves, clustered first (the paper's case).
pub fn curves(results: &Paper1Results) -> [&Fig7Curve; 2] {
    [&results.fig7.clustered, &results.fig7.uniform]
}

/// "0.0950%", or what a missing crossover means.
pub fn crossover_text(curve: &Fig7Curve) -> String {
    match curve.crossover_eta {
        Some(eta) if Some(eta) == curve.points.first().map(|p| p.eta) => {
            format!(
                "the reduced scheme is faster from the smallest eta ({:.4}%)",
                eta * 100.0
            )
        }
        Some(eta) => format!(
            "the reduced scheme is faster from eta = {:.4}%",
            eta * 100.0
        ),
        None => "the hierarchical scheme is faster up to the largest eta".into(),
    }
}

fn contents_name(contents: P0Contents) -> &'static str {
    match contents {
        P0Contents::Clustered => "clustered CAPs",
        P0Contents::Uniform => "uniform random CAPs",
    }
}

fn contents_of(curve: &Fig7Curve) -> P0Contents {
    curve
        .points
        .first()
        .map_or(P0Contents::Clustered, |p| p.contents)
}

pub fn tables(results: &Paper1Results) -> Vec<Table> {
    curves(results)
        .into_iter()
        .map(|curve| table(results, curve))
        .collect()
}

fn table(results: &Paper1Results, curve: &Fig7Curve) -> Table {
    let f = &results.fig7;
    Table {
        caption: format!(
            "Fig. 7, {}: readback of a {p0}x{p0} P0 against eta, best of each point's runs ({}): \
             encode (GPU) + read/decode (wall) ms, and bytes read back; {} (paper: 0.095%, \
             GeForce 7800, 2048x2048); auto leaves the hierarchy at {}",
            contents_name(contents_of(curve)),
            results.renderer,
            crossover_text(curve),
            curve
                .auto_switch_eta
                .map_or("no calibrated eta".into(), |e| format!("{:.4}%", e * 100.0)),
            p0 = f.p0,
        ),
        header: header(&[
            "eta %",
            "CAPs",
            "CAPs per set P1 texel",
            "hier enc",
            "hier dec",
            "hier bytes",
            "red enc",
            "red dec",
            "red bytes",
            "full read",
            "full bytes",
            "hier/full bytes %",
            "faster of H, RH",
            "fastest",
            "runs",
        ]),
        rows: curve
            .points
            .iter()
            .map(|p| {
                let s = &p.schemes;
                vec![
                    format!("{:.4}", p.eta * 100.0),
                    p.caps.to_string(),
                    format!("{:.1}", p.caps_per_set_p1_texel),
                    f2(s[0].encode_ms),
                    f2(s[0].decode_ms),
                    s[0].bytes.to_string(),
                    f2(s[1].encode_ms),
                    f2(s[1].decode_ms),
                    s[1].bytes.to_string(),
                    f2(s[2].decode_ms),
                    s[2].bytes.to_string(),
                    format!("{:.3}", 100.0 * s[0].bytes as f64 / s[2].bytes as f64),
                    p.paper_fastest()
                        .map_or("-".into(), |(scheme, _)| scheme.to_string()),
                    p.fastest().to_string(),
                    p.runs.to_string(),
                ]
            })
            .collect(),
    }
}

/// The paper's curves (encoding, decoding and their total for the hierarchical (H) and
/// reduced (RH) schemes), the full readback, and the paper's switch as a vertical line.
pub fn series(curve: &Fig7Curve) -> Vec<Series> {
    let points = &curve.points;
    let line = |name: &str, f: &dyn Fn(&SchemeCost) -> f64, k: usize| {
        Series::new(
            name,
            points
                .iter()
                .map(|p| (p.eta * 100.0, f(&p.schemes[k])))
                .collect(),
        )
    };
    let mut series = vec![
        line("Encoding(H)", &|s| s.encode_ms, 0),
        line("Decoding(H)", &|s| s.decode_ms, 0),
        line("Total(H)", &|s| s.total_ms(), 0),
        line("Encoding(RH)", &|s| s.encode_ms, 1),
        line("Reading+Decoding(RH)", &|s| s.decode_ms, 1),
        line("Total(RH)", &|s| s.total_ms(), 1),
        line("full readback", &|s| s.decode_ms, 2),
    ];
    let ys: Vec<f64> = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .filter(|&y| y > 0.0 && y.is_finite())
        .collect();
    let (lo, hi) = ys
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &y| (a.min(y), b.max(y)));
    if lo <= hi {
        let x = PAPER_ETA_THRESHOLD * 100.0;
        series.push(Series::guide(
            "paper's switch (0.095%)",
            vec![(x, lo), (x, hi)],
        ));
    }
    series
}

/// One figure per kind of contents: `paper1_fig7_readback.png` (clustered, the paper's
/// case) and `paper1_fig7_readback_uniform.png`.
pub fn figures(opts: &BenchOptions, results: &Paper1Results) -> anyhow::Result<Vec<Figure>> {
    let mut figures = Vec::new();
    for curve in curves(results) {
        let contents = contents_of(curve);
        let file = match contents {
            P0Contents::Clustered => "paper1_fig7_readback.png",
            P0Contents::Uniform => "paper1_fig7_readback_uniform.png",
        };
        Plot {
            title: format!(
                "Fig. 7: readback time vs eta, {} ({})",
                contents_name(contents),
                opts.gl.info().renderer
            ),
            x_label: "eta (% of AABB pairs colliding)".into(),
            y_label: "ms".into(),
            log_x: true,
            log_y: true,
            series: series(curve),
        }
        .write_png(&opts.out_dir.join(file))?;
        figures.push(Figure {
            file: file.into(),
            caption: format!(
                "Fig. 7: readback time of each scheme against eta, {} in a {p0}x{p0} P0; {}",
                contents_name(contents),
                crossover_text(curve),
                p0 = results.fig7.p0
            ),
        });
    }
    Ok(figures)
}
