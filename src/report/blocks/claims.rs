//! What the reduction is for, judged on the largest size.

use super::bench::BlocksResults;
use crate::report::{Basis, Claim};

pub fn claims(results: &BlocksResults) -> Vec<Claim> {
    let Some(largest) = results.reduction.last() else {
        return Vec::new();
    };
    vec![Claim {
        claim: "Reduction to a single texel gives the sum a full readback gives".into(),
        paper: "paper 4, section 3.3 (readback latency motivates buffer reduction)".into(),
        measured: format!(
            "decided by the sums: relative difference {:.1e} (allowed 1e-4 for the fp32 \
             sums) at n = {}, reading back {} bytes instead of {}; time \
             ratio readback/reduce {:.2} (not judged)",
            largest.relative_difference,
            largest.size,
            largest.reduce_bytes,
            largest.readback_bytes,
            largest.readback_wall_ms / largest.reduce_wall_ms
        ),
        decided_by: Basis::Error,
        holds: Some(largest.relative_difference < 1e-4),
    }]
}
