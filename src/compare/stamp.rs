//! `classic-gpgpu claims --stamp OLD.json --like NEW.json --out FILE`: gives the claims of a run
//! from before per-claim versions this build's ids and versions, so that a kept run that cannot
//! be made again (a GPU lent once) keeps every claim whose definition has not changed since.
//!
//! The ids come from a run of this build (`--like`): an old claim takes the id of the claim of
//! the same section and the same words. The versions are this build's, at the old run's sizes.
//! Whoever stamps asserts that no claim stamped changed its rule, published value or sizes
//! between the old run's commit and this build; the claims that did are named in `--except`
//! and keep no version ("re-run needed"). The file records who stamped it, when and how.

use super::run::Run;
use crate::report::provenance;
use anyhow::{bail, Context as _};
use serde_json::{json, Value};

/// The stamped copy of `old` (the results.json's text as read) and the ids stamped.
pub fn stamp(
    old: &Value,
    old_file: &str,
    like: &Run,
    except: &[String],
) -> anyhow::Result<(Value, Vec<String>)> {
    for id in except {
        if crate::report::versions::find(id).is_none() {
            bail!("--except {id}: not a claim of this build (`classic-gpgpu claims` lists them)");
        }
    }
    let recorded_version = |c: &Value| c["version"].as_str().is_some_and(|v| !v.is_empty());
    let sections = old["sections"]
        .as_array()
        .with_context(|| format!("{old_file}: no sections"))?;
    if sections
        .iter()
        .flat_map(|s| s["claims"].as_array().into_iter().flatten())
        .any(recorded_version)
    {
        bail!(
            "{old_file}: its claims already carry versions; only a run from before them is stamped"
        );
    }
    for section in &like.sections {
        for claim in &section.claims {
            if super::current_version(&claim.id, like.quick).as_deref() != Some(&claim.version) {
                bail!(
                    "--like {}: claim '{}' is not of this build's version; give a results.json \
                     this build made",
                    like.file,
                    claim.id
                );
            }
        }
    }
    let quick = old["quick"] == true;
    let mut stamped = old.clone();
    let mut ids = Vec::new();
    for section in stamped["sections"].as_array_mut().into_iter().flatten() {
        let section_id = section["id"].as_str().unwrap_or_default().to_string();
        let Some(new) = like.section(&section_id) else {
            continue;
        };
        for claim in section["claims"].as_array_mut().into_iter().flatten() {
            let words = claim["claim"].as_str().unwrap_or_default();
            let Some(same) = new.claims.iter().find(|c| c.claim == words) else {
                continue;
            };
            if except.contains(&same.id) {
                continue;
            }
            let Some(version) = super::current_version(&same.id, quick) else {
                continue;
            };
            claim["id"] = json!(same.id);
            claim["version"] = json!(version);
            ids.push(same.id.clone());
        }
    }
    if ids.is_empty() {
        bail!(
            "{old_file}: no claim has the words of a claim of {}; nothing to stamp",
            like.file
        );
    }
    stamped["stamped"] =
        json!(format!(
        "ids and versions given afterwards, at commit {}, to {} of its claims (matched by their \
         words to {} of commit {}{}): asserted unchanged in rule, published value and sizes \
         since the run's commit",
        provenance::short_commit(provenance::COMMIT),
        ids.len(),
        like.file,
        like.short_commit(),
        if except.is_empty() {
            String::new()
        } else {
            format!("; left without a version, changed since: {}", except.join(", "))
        }
    ));
    Ok((stamped, ids))
}
