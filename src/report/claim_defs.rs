//! Every claim this build can make, from the report's stages ([`super::reproduce::stages`]):
//! each with its section, found by id, and listed with its versions for `classic-gpgpu claims`.
//! Kept apart from [`super::versions`], which the sections' claims use, so that the versions
//! need not import the report's stages.

use super::versions::{current, ClaimDef};
use serde::Serialize;

/// Every claim the report can make, with its section, in report order.
pub fn all() -> Vec<(&'static str, &'static ClaimDef)> {
    super::reproduce::stages()
        .into_iter()
        .flat_map(|stage| stage.claims.iter().map(move |def| (stage.id, def)))
        .collect()
}

/// The definition of claim `id`, if this build has one.
pub fn find(id: &str) -> Option<&'static ClaimDef> {
    all().into_iter().map(|(_, d)| d).find(|d| d.id == id)
}

/// One claim as `classic-gpgpu claims` lists it: its versions at both sizes and what they
/// hash.
#[derive(Clone, Debug, Serialize)]
pub struct Listed {
    pub section: String,
    pub id: String,
    /// At the papers' sizes.
    pub version: String,
    /// At `--quick` sizes.
    pub quick_version: String,
    pub rule: Vec<String>,
    pub published: Vec<String>,
    pub workload: Vec<String>,
    pub band: Option<f64>,
}

/// Every claim of this build, listed.
pub fn listed() -> Result<Vec<Listed>, String> {
    all()
        .into_iter()
        .map(|(section, def)| {
            Ok(Listed {
                section: section.into(),
                id: def.id.into(),
                version: current(def, false)?,
                quick_version: current(def, true)?,
                rule: def.rule.iter().map(|s| s.to_string()).collect(),
                published: def.published.iter().map(|s| s.to_string()).collect(),
                workload: def.workload.iter().map(|s| s.to_string()).collect(),
                band: def.band,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_claim_of_the_report_has_a_version_of_its_own() {
        let listed = listed().unwrap_or_else(|e| panic!("{e}"));
        assert!(listed.len() >= 30, "{}", listed.len());
        let mut ids: Vec<&str> = listed.iter().map(|l| l.id.as_str()).collect();
        ids.sort();
        ids.dedup();
        assert_eq!(ids.len(), listed.len(), "an id is used twice");
        for l in &listed {
            assert!(
                l.id.starts_with(&format!("{}.", l.section)),
                "{} in section {}",
                l.id,
                l.section
            );
            assert_ne!(l.version, l.quick_version, "{}", l.id);
        }
    }
}
