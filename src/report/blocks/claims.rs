//! What the reduction is for, judged on the largest size.

use super::bench::BlocksResults;
use crate::report::{Basis, Claim, ClaimDef, Evidence};

/// Every claim of the section, with what decides it.
pub const CLAIMS: &[ClaimDef] = &[REDUCTION_SUM];

// region: rule reduction-sum
/// Paper 4, section 3.3: a reduction to one texel gives the sum a full readback gives.
const REDUCTION_SUM: ClaimDef = ClaimDef {
    id: "blocks.reduction-sum",
    rule: &["src/report/blocks/claims.rs#rule reduction-sum"],
    published: &[],
    workload: &["src/report/blocks/bench.rs#workload sizes"],
    band: None,
};

/// The relative difference the fp32 sums may show.
const SUM_TOLERANCE: f64 = 1e-4;

pub fn claims(results: &BlocksResults) -> Vec<Claim> {
    let Some(largest) = results.reduction.last() else {
        return Vec::new();
    };
    vec![Claim {
        id: REDUCTION_SUM.id.into(),
        claim: "Reduction to a single texel gives the sum a full readback gives".into(),
        paper: "paper 4, section 3.3 (readback latency motivates buffer reduction)".into(),
        measured: format!(
            "decided by the sums: relative difference {:.1e} (allowed {SUM_TOLERANCE:.0e} for \
             the fp32 sums) at n = {}, reading back {} bytes instead of {}; time \
             ratio readback/reduce {:.2} (not judged)",
            largest.relative_difference,
            largest.size,
            largest.reduce_bytes,
            largest.readback_bytes,
            largest.readback_wall_ms / largest.reduce_wall_ms
        ),
        decided_by: Basis::Error,
        holds: Some(largest.relative_difference < SUM_TOLERANCE),
        evidence: vec![
            Evidence::error(
                "relative difference of the sums, largest size",
                largest.relative_difference,
                SUM_TOLERANCE,
            ),
            Evidence::count(
                "bytes read back after the reduction",
                largest.reduce_bytes as f64,
            ),
        ],
        ..Claim::default()
    }]
}
// endregion
