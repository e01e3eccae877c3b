//! Where the time of the section's run went: the per-pass profile of the whole run.

use super::bench::Paper1Results;
use crate::report::Table;

pub fn table(results: &Paper1Results) -> Option<Table> {
    let profile = results.profile.as_ref()?;
    Some(crate::report::profile::table(
        profile,
        "Paper 1, where the run's time goes",
        0.005,
    ))
}
