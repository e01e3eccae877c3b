//! The leaf size `n` (Sec. 4.1's "user-provided number of triangles") swept on the
//! interlocking tori: what the default trades (a larger `P0` against more triangle tests).

use super::bench::Paper1Results;
use super::{f2, header};
use crate::collide::stream_setup::DEFAULT_LEAF_SIZE;
use crate::report::Table;

pub fn table(results: &Paper1Results) -> Table {
    let fastest = results
        .leaf_sweep
        .iter()
        .min_by(|a, b| a.total_ms.total_cmp(&b.total_ms))
        .map_or("none ran".to_string(), |p| p.leaf_size.to_string());
    Table {
        caption: format!(
            "Leaf size n on interlocking tori ({}): a larger n shrinks P0 and the overlap \
             pass, and adds triangle pairs to test on the CPU. Fastest here (mean total of \
             the frames): n = {fastest}. The commands start from n = {DEFAULT_LEAF_SIZE} and \
             double it per model until a stream has at most {} slots on a software renderer \
             or {} on a GPU (collide::stream_setup)",
            results.renderer,
            crate::collide::stream_setup::SOFTWARE_MAX_SLOTS,
            crate::collide::stream_setup::HARDWARE_MAX_SLOTS
        ),
        header: header(&[
            "n",
            "P0 side",
            "overlap ms",
            "tri test ms",
            "PCTPs",
            "total ms",
        ]),
        rows: results
            .leaf_sweep
            .iter()
            .map(|p| {
                vec![
                    p.leaf_size.to_string(),
                    p.p0.to_string(),
                    f2(p.overlap_ms),
                    f2(p.tri_ms),
                    p.pctps.to_string(),
                    f2(p.total_ms),
                ]
            })
            .collect(),
    }
}
