//! CULLIDE's image resolution against its misses and its time (Sec. 7.4.2: a higher
//! resolution misses less but costs more).

use super::bench::Paper1Results;
use super::{f2, header};
use crate::report::Table;

pub fn table(results: &Paper1Results) -> Table {
    let c = &results.cullide_resolutions;
    Table {
        caption: format!(
            "CULLIDE's resolution on the interlocking tori, mean of {} frames ({})",
            c.frames, results.renderer
        ),
        header: header(&["resolution", "pruning + tri test ms", "PCTPs", "missing %"]),
        rows: c
            .rows
            .iter()
            .map(|r| {
                vec![
                    format!("{0}x{0}", r.resolution),
                    f2(r.ms),
                    r.pctps.to_string(),
                    format!("{:.0}", r.missing_percent),
                ]
            })
            .collect(),
    }
}
