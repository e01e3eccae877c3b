//! Each claim's version is a hash of what decides it, tried on the project's own files: changing
//! one claim's rule (or its published value, or its sizes) changes that claim's version and no
//! other; editing code that decides no claim (a caption, the page's html, a comment) changes
//! none. The versions are computed from the files as this build compiled them in, with one file
//! replaced by an edited copy.

use classic_gpgpu::report::claim_defs;
use classic_gpgpu::report::published::PAPER_TABLES_TOML;
use classic_gpgpu::report::versions::{self, compiled_source, ClaimDef};
use std::collections::BTreeMap;

/// Every claim's version at the papers' sizes, with `file` read as `text` and the published
/// tables as `tables`.
fn versions_with(file: &str, text: &str, tables: &str) -> BTreeMap<&'static str, String> {
    let sources = |path: &str| {
        if path == file {
            Some(text)
        } else {
            compiled_source(path)
        }
    };
    claim_defs::all()
        .into_iter()
        .map(|(_, def): (_, &ClaimDef)| {
            let v =
                versions::version(def, false, &sources, tables).unwrap_or_else(|e| panic!("{e}"));
            (def.id, v)
        })
        .collect()
}

/// The ids whose versions differ between two sets.
fn changed(
    a: &BTreeMap<&'static str, String>,
    b: &BTreeMap<&'static str, String>,
) -> Vec<&'static str> {
    a.iter()
        .filter(|(id, v)| b.get(*id) != Some(v))
        .map(|(id, _)| *id)
        .collect()
}

/// `file`'s compiled-in text with `from` replaced by `to` (which must be there once).
fn edited(file: &str, from: &str, to: &str) -> String {
    let text = compiled_source(file).unwrap_or_else(|| panic!("{file} is not compiled in"));
    assert_eq!(text.matches(from).count(), 1, "{file}: `{from}`");
    text.replace(from, to)
}

fn current() -> BTreeMap<&'static str, String> {
    versions_with("", "", PAPER_TABLES_TOML)
}

#[test]
fn the_build_versions_every_claim_as_it_is() {
    let now = current();
    assert!(now.len() >= 30, "{}", now.len());
    for (id, v) in &now {
        let def = claim_defs::find(id).unwrap();
        assert_eq!(&versions::current(def, false).unwrap(), v, "{id}");
    }
}

#[test]
fn changing_one_claims_rule_changes_that_claims_version_only() {
    let file = "src/report/paper4/claims.rs";
    let text = edited(
        file,
        "holds: Some(worst_closed < bound),",
        "holds: Some(worst_closed <= bound),",
    );
    assert_eq!(
        changed(&current(), &versions_with(file, &text, PAPER_TABLES_TOML)),
        ["paper4.error-bound"]
    );
    // A rule shared by two claims (paper 2's crossover, judged against two baselines) changes
    // both, and nothing else.
    let file = "src/report/paper2/claims.rs";
    let text = edited(
        file,
        "let from_16 = counts.iter().filter(|&&n| n >= 16);",
        "let from_16 = counts.iter().filter(|&&n| n >= 32);",
    );
    assert_eq!(
        changed(&current(), &versions_with(file, &text, PAPER_TABLES_TOML)),
        ["paper2.overtakes-vs", "paper2.overtakes-vs-one-per-draw"]
    );
}

#[test]
fn the_timing_policy_is_part_of_every_timed_claims_rule() {
    let file = "src/timing.rs";
    let text = edited(
        file,
        "pub const LOADED_PER_CORE: f64 = 1.0;",
        "pub const LOADED_PER_CORE: f64 = 1.5;",
    );
    let moved = changed(&current(), &versions_with(file, &text, PAPER_TABLES_TOML));
    for (_, def) in claim_defs::all() {
        assert_eq!(
            moved.contains(&def.id),
            def.rule.contains(&versions::TIMING_POLICY),
            "{}",
            def.id
        );
        // A claim judged on a timing states the band the gate judges it in.
        assert_eq!(
            def.band.is_some(),
            def.rule.contains(&versions::TIMING_POLICY),
            "{}",
            def.id
        );
    }
    assert!(moved.len() >= 10, "{moved:?}");
}

#[test]
fn a_published_value_or_a_size_changes_the_claims_that_use_it() {
    let tables =
        PAPER_TABLES_TOML.replacen("frames_per_second = 16.0", "frames_per_second = 17.0", 1);
    assert_ne!(
        tables, PAPER_TABLES_TOML,
        "the buoyancy rate is transcribed as 16"
    );
    assert_eq!(
        changed(&current(), &versions_with("", "", &tables)),
        ["paper4.interactive-buoyancy"]
    );
    let file = "src/report/paper4/bench.rs";
    let text = edited(
        file,
        "vec![8, 16, 32, 64, 128, 256, 512]",
        "vec![8, 16, 32, 64, 128, 256]",
    );
    assert_eq!(
        changed(&current(), &versions_with(file, &text, PAPER_TABLES_TOML)),
        [
            "paper4.error-bound",
            "paper4.outperforms-analytic-bunny",
            "paper4.outperforms-analytic-pipe"
        ]
    );
}

#[test]
fn code_that_decides_no_claim_changes_no_version() {
    let now = current();
    // A caption of a table, in a claims file's section folder.
    let file = "src/report/paper4/claims.rs";
    let text = compiled_source(file).unwrap().replace(
        "//! The paper's claims",
        "//! The paper's claims, reworded,",
    );
    assert_ne!(text, compiled_source(file).unwrap());
    assert!(changed(&now, &versions_with(file, &text, PAPER_TABLES_TOML)).is_empty());
    // The report page's html.
    let file = "src/report/html.rs";
    let text = format!(
        "{}\n// a new line of the page\n",
        compiled_source(file).unwrap()
    );
    assert!(changed(&now, &versions_with(file, &text, PAPER_TABLES_TOML)).is_empty());
    // A comment and the layout inside a rule.
    let file = "src/report/paper1/claims.rs";
    let text = edited(
        file,
        "    // The switch placed where it pays on this renderer: the faster of the two at each eta.",
        "    // Reworded: the faster of the two schemes at each eta.\n\n",
    );
    assert!(changed(&now, &versions_with(file, &text, PAPER_TABLES_TOML)).is_empty());
    // A published value no claim uses (paper 1's source line).
    let tables = PAPER_TABLES_TOML.replacen("IEEE TVCG 13(2), 2007", "IEEE TVCG 13(2), 2007.", 1);
    assert_ne!(tables, PAPER_TABLES_TOML);
    assert!(changed(&now, &versions_with("", "", &tables)).is_empty());
}

#[test]
fn quick_runs_judge_other_versions() {
    for (_, def) in claim_defs::all() {
        assert_ne!(
            versions::current(def, true).unwrap(),
            versions::current(def, false).unwrap(),
            "{}",
            def.id
        );
    }
}

#[test]
fn changing_the_meshes_paper_4_measures_changes_paper_4s_versions_only() {
    // The bunny refined to other counts than Table 1's.
    let file = "src/mass/models.rs";
    let text = edited(
        file,
        "pub const BUNNY_FACES: usize = 5110;",
        "pub const BUNNY_FACES: usize = 3674;",
    );
    assert_eq!(
        changed(&current(), &versions_with(file, &text, PAPER_TABLES_TOML)),
        [
            "paper4.error-bound",
            "paper4.interactive-buoyancy",
            "paper4.outperforms-analytic-bunny",
            "paper4.outperforms-analytic-pipe"
        ]
    );
    // A function of the file outside the objects' region (the OBJ loader's message).
    let text = edited(
        file,
        "the file has no triangles",
        "the file holds no triangle",
    );
    assert!(changed(&current(), &versions_with(file, &text, PAPER_TABLES_TOML)).is_empty());
}
