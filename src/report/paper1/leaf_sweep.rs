//! The leaf size `n` (Sec. 4.1's "user-provided number of triangles") swept on the
//! interlocking tori: what the default trades (a larger `P0` against more triangle tests).

use super::bench::Paper1Results;
use super::{f2, header};
use crate::collide::stream_setup::DEFAULT_LEAF_SIZE;
use crate::report::Table;

pub fn table(results: &Paper1Results) -> Table {
    Table {
        caption: format!(
            "Leaf size n on interlocking tori ({}): why the default is {DEFAULT_LEAF_SIZE}",
            results.renderer
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
