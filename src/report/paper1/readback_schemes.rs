//! The readback schemes of Sec. 5.3 on real frames: each forced in turn on the interlocking
//! tori, beside the calibrated curves of Fig. 7.

use super::bench::Paper1Results;
use super::{f2, header};
use crate::report::Table;

pub fn table(results: &Paper1Results) -> Table {
    let s = &results.readback_schemes;
    Table {
        caption: format!(
            "Readback schemes on the interlocking tori ({0}x{0} P0, mean of {1} frames, {2})",
            s.p0, s.frames, results.renderer
        ),
        header: header(&[
            "scheme",
            "eta %",
            "encode ms",
            "read+decode ms",
            "total ms",
            "bytes read",
        ]),
        rows: s
            .rows
            .iter()
            .map(|r| {
                vec![
                    format!("{:?}", r.scheme).to_lowercase(),
                    format!("{:.4}", 100.0 * r.eta),
                    f2(r.encode_ms),
                    f2(r.decode_ms),
                    f2(r.encode_ms + r.decode_ms),
                    format!("{:.0}", r.bytes),
                ]
            })
            .collect(),
    }
}
