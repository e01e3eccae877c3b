//! Where the time of the section's run went: the per-pass profile of the whole run.

use super::Paper3Results;
use crate::report::Table;

pub fn table(results: &Paper3Results) -> Option<Table> {
    let profile = results.profile.as_ref()?;
    Some(crate::report::profile::table(
        profile,
        "Paper 3, where the run's time goes",
        0.005,
    ))
}
