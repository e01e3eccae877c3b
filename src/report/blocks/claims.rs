//! What the reduction is for, judged on the largest size.

use super::bench::BlocksResults;
use crate::report::Claim;

pub fn claims(results: &BlocksResults) -> Vec<Claim> {
    let Some(largest) = results.reduction.last() else {
        return Vec::new();
    };
    vec![Claim {
        claim: "Reduction reads back a single texel instead of the whole buffer".into(),
        paper: "paper 4, section 3.3 (readback latency motivates buffer reduction)".into(),
        measured: format!(
            "{} bytes instead of {} at n = {}; time ratio readback/reduce {:.2}",
            largest.reduce_bytes,
            largest.readback_bytes,
            largest.size,
            largest.readback_wall_ms / largest.reduce_wall_ms
        ),
        holds: Some(largest.relative_difference < 1e-4),
    }]
}
