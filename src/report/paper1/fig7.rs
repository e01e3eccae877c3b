//! Fig. 7 (Sec. 5.3.2): readback time of each scheme against `eta`, the share of AABB pairs
//! that collide, on a `P0` filled at each `eta`.

use super::bench::Paper1Results;
use super::{f2, header};
use crate::collide::reduction_gpu::SchemeCost;
use crate::report::plot::{Plot, Series};
use crate::report::{BenchOptions, Figure, Table};

pub fn table(results: &Paper1Results) -> Table {
    Table {
        caption: format!(
            "Fig. 7: readback of a {0}x{0} P0 against eta, best of repeats ({1}): encode (GPU) + \
             read/decode (wall) ms, and bytes read back",
            results.setup.fig7_p0, results.renderer
        ),
        header: header(&[
            "eta %",
            "CAPs",
            "hier enc",
            "hier dec",
            "hier bytes",
            "red enc",
            "red dec",
            "red bytes",
            "full read",
            "full bytes",
            "hier/full bytes %",
            "fastest",
        ]),
        rows: results
            .fig7
            .iter()
            .map(|p| {
                let s = &p.schemes;
                vec![
                    format!("{:.4}", p.eta * 100.0),
                    p.caps.to_string(),
                    f2(s[0].encode_ms),
                    f2(s[0].decode_ms),
                    s[0].bytes.to_string(),
                    f2(s[1].encode_ms),
                    f2(s[1].decode_ms),
                    s[1].bytes.to_string(),
                    f2(s[2].decode_ms),
                    s[2].bytes.to_string(),
                    format!("{:.3}", 100.0 * s[0].bytes as f64 / s[2].bytes as f64),
                    format!("{:?}", p.fastest()).to_lowercase(),
                ]
            })
            .collect(),
    }
}

/// The paper's curves: encoding, decoding and their total for the hierarchical (H) and
/// reduced (RH) schemes, plus the full readback.
pub fn figure(opts: &BenchOptions, results: &Paper1Results) -> anyhow::Result<Figure> {
    let curve = |name: &str, f: &dyn Fn(&SchemeCost) -> f64, k: usize| {
        Series::new(
            name,
            results
                .fig7
                .iter()
                .map(|p| (p.eta * 100.0, f(&p.schemes[k])))
                .collect(),
        )
    };
    let file = "paper1_fig7_readback.png";
    Plot {
        title: format!("Fig. 7: readback time vs eta ({})", opts.gl.info().renderer),
        x_label: "eta (% of AABB pairs colliding)".into(),
        y_label: "ms".into(),
        log_x: true,
        log_y: true,
        series: vec![
            curve("Encoding(H)", &|s| s.encode_ms, 0),
            curve("Decoding(H)", &|s| s.decode_ms, 0),
            curve("Total(H)", &|s| s.total_ms(), 0),
            curve("Encoding(RH)", &|s| s.encode_ms, 1),
            curve("Reading+Decoding(RH)", &|s| s.decode_ms, 1),
            curve("Total(RH)", &|s| s.total_ms(), 1),
            curve("full readback", &|s| s.decode_ms, 2),
        ],
    }
    .write_png(&opts.out_dir.join(file))?;
    Ok(Figure {
        file: file.into(),
        caption: "Fig. 7: readback time of each scheme against eta".into(),
    })
}
