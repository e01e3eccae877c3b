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

/// The stamped copy of `old` (the results.json's text as read), and the ids stamped. The text is
/// patched, not written again: each stamped claim gains an `id` and a `version` before its
/// `"claim"`, the run a `stamped` field, and every other byte (every number) stays as it was; the
/// patched text must parse to the old document plus those fields.
pub fn stamp(
    old: &str,
    old_file: &str,
    like: &Run,
    except: &[String],
) -> anyhow::Result<(String, Vec<String>)> {
    for id in except {
        if crate::report::claim_defs::find(id).is_none() {
            bail!("--except {id}: not a claim of this build (`classic-gpgpu claims` lists them)");
        }
    }
    let value: Value =
        serde_json::from_str(old).with_context(|| format!("{old_file}: not JSON"))?;
    let recorded_version = |c: &Value| c["version"].as_str().is_some_and(|v| !v.is_empty());
    let sections = value["sections"]
        .as_array()
        .with_context(|| format!("{old_file}: no sections"))?;
    if sections
        .iter()
        .flat_map(|s| s["claims"].as_array().into_iter().flatten())
        .any(recorded_version)
    {
        bail!(
            "{old_file}: its claims already carry versions; only a run from before them is \
             stamped"
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
    let quick = value["quick"] == true;
    let mut expected = value.clone();
    let mut text = old.to_string();
    let mut ids = Vec::new();
    for section in expected["sections"].as_array_mut().into_iter().flatten() {
        let section_id = section["id"].as_str().unwrap_or_default().to_string();
        let Some(new) = like.section(&section_id) else {
            continue;
        };
        for claim in section["claims"].as_array_mut().into_iter().flatten() {
            let words = claim["claim"].as_str().unwrap_or_default().to_string();
            let Some(same) = new.claims.iter().find(|c| c.claim == words) else {
                continue;
            };
            if except.contains(&same.id) {
                continue;
            }
            let Some(version) = super::current_version(&same.id, quick) else {
                continue;
            };
            text = add_before_claim(&text, &words, &same.id, &version)
                .with_context(|| format!("{old_file}: claim '{words}'"))?;
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
    let note = format!(
        "ids and versions given afterwards, at commit {}, to {} of its claims, matched by their \
         words to those of a run of the same versions ({}, commit {}{}){}; whoever stamped \
         asserts that how each is judged, its published values and its sizes did not change \
         between the run's commit and {0}",
        provenance::short_commit(provenance::COMMIT),
        ids.len(),
        like.label,
        like.short_commit(),
        if like.quick { ", --quick" } else { "" },
        if except.is_empty() {
            String::new()
        } else {
            format!(
                "; left without a version, changed since the run: {}",
                except.join(", ")
            )
        }
    );
    let open = text
        .find('{')
        .with_context(|| format!("{old_file}: not a JSON object"))?;
    text.insert_str(open + 1, &format!("\n  \"stamped\": {},", json!(note)));
    expected["stamped"] = json!(note);
    let patched: Value = serde_json::from_str(&text)
        .with_context(|| format!("{old_file}: the stamped text does not parse"))?;
    if patched != expected {
        bail!("{old_file}: the stamped text is not the run plus its stamps; nothing written");
    }
    Ok((text, ids))
}

/// `text` with the fields `"id"` and `"version"` put before the claim's `"claim": <words>`
/// (which must be there once), on lines of their own where the text has lines.
fn add_before_claim(text: &str, words: &str, id: &str, version: &str) -> anyhow::Result<String> {
    let value = json!(words).to_string();
    // Each place the words are the value of a "claim" key: where that key starts.
    let keys: Vec<usize> = text
        .match_indices(&value)
        .filter_map(|(at, _)| text[..at].trim_end().strip_suffix("\"claim\":"))
        .map(|before| before.trim_end().len())
        .filter(|&after| text[..after].ends_with(['{', ',']))
        .map(|after| after + text[after..].find('"').unwrap_or(0))
        .collect();
    let [key] = keys.as_slice() else {
        bail!(
            "its \"claim\" is there {} times, not once; the claims are stamped only where each \
             is there once",
            keys.len()
        );
    };
    let line_start = text[..*key].rfind('\n').map_or(0, |i| i + 1);
    let indent = &text[line_start..*key];
    let gap = if indent.trim().is_empty() && line_start > 0 {
        format!("\n{indent}")
    } else {
        String::new()
    };
    Ok(format!(
        "{}\"id\": {},{gap}\"version\": {},{gap}{}",
        &text[..*key],
        json!(id),
        json!(version),
        &text[*key..]
    ))
}
