//! A claim's identity and version, so that results last (DESIGN.md, "Results that last"): each
//! claim has a stable id written in code and a version that is a hash of what decides it, as
//! asv versions each benchmark by its own code and not by the suite's. What decides a claim:
//!
//! - the rule that judges it: named regions of the code (`// region: NAME` ... `// endregion`,
//!   the same markers the course cuts its pages by), usually the function that builds the
//!   claim with its [`ClaimDef`] above it, and the timing policy it is judged by;
//! - the published values it is judged against: keys of `assets/paper_tables.toml`;
//! - the workload that measures it: regions of the measuring code that set its sizes, and
//!   whether the run is a `--quick` one.
//!
//! Editing anything else (the guide, a caption, the page's html, a table that decides no
//! claim) changes no version; changing one claim's rule changes that claim's version only.
//! Comment lines and white space inside a region do not count, so rewording a comment or
//! `cargo fmt` leaves a version alone.
//!
//! The Rust files under `src/report/`, `src/timing.rs` and `src/mass/models.rs` (the paper
//! objects paper 4 measures) are compiled into the binary
//! (`build.rs`), so any build can say what HEAD's version of every claim is without a run
//! ([`current`], `classic-gpgpu claims`), and `compare` can tell a kept run's claim that is
//! still current from one whose definition changed since.

use super::published::PAPER_TABLES_TOML;

include!(concat!(env!("OUT_DIR"), "/claim_sources.rs"));

/// What decides one claim, written beside the function that judges it (inside its rule
/// region, so that editing it changes the version too).
#[derive(Clone, Copy, Debug)]
pub struct ClaimDef {
    /// `<section>.<name>`, stable across builds: written here, never derived from the claim's
    /// words, which may be reworded.
    pub id: &'static str,
    /// The code that judges it: regions, each `path#name` (`src/report/paper1/claims.rs#rule
    /// beats-cullide`).
    pub rule: &'static [&'static str],
    /// The published values it is judged against: dotted keys of `assets/paper_tables.toml`
    /// (`paper4.fig4`).
    pub published: &'static [&'static str],
    /// The code that sets the sizes that measure it: regions, each `path#name`.
    pub workload: &'static [&'static str],
    /// For a claim decided by a timing: how far its figure may move, relative, between two
    /// quiet runs before `compare --baseline` calls the change a regression (0.25: 25%; wider
    /// where one build's runs were measured to move more, said beside it).
    pub band: Option<f64>,
}

/// The timing policy every claim judged on a timing rests on ([`crate::timing::judge_ends`]
/// and its kin): a part of those claims' rules.
pub const TIMING_POLICY: &str = "src/timing.rs#rule timing-verdicts";

/// FNV-1a, 64 bits: a short, stable hash (the same on every platform and Rust version, unlike
/// `std`'s hasher).
#[derive(Clone, Copy, Debug)]
pub struct Fnv(u64);

impl Default for Fnv {
    fn default() -> Fnv {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    /// Adds `bytes`, then a separator, so that ("ab", "c") and ("a", "bc") differ.
    pub fn add(&mut self, bytes: &[u8]) -> &mut Fnv {
        for &byte in bytes.iter().chain([&0xff]) {
            self.0 = (self.0 ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
        }
        self
    }

    /// The hash as 16 hex digits.
    pub fn hex(&self) -> String {
        format!("{:016x}", self.0)
    }
}

/// The text of the region `name` of `text`: the lines between `// region: NAME` and the
/// `// endregion` that closes it (regions may nest). An error when the region is missing,
/// named twice, unclosed or empty.
pub fn cut<'a>(text: &'a str, name: &str) -> Result<Vec<&'a str>, String> {
    let opens = |line: &str| {
        line.trim()
            .strip_prefix("// region:")
            .map(|n| n.trim().to_string())
    };
    let starts: Vec<usize> = text
        .lines()
        .enumerate()
        .filter(|(_, line)| opens(line).as_deref() == Some(name))
        .map(|(i, _)| i)
        .collect();
    let start = match starts.as_slice() {
        [] => return Err(format!("no region `{name}`")),
        [one] => *one,
        _ => return Err(format!("region `{name}` is named {} times", starts.len())),
    };
    let mut depth = 1;
    let mut lines = Vec::new();
    for line in text.lines().skip(start + 1) {
        if opens(line).is_some() {
            depth += 1;
        } else if line.trim() == "// endregion" {
            depth -= 1;
            if depth == 0 {
                return if lines.iter().all(|l: &&str| l.trim().is_empty()) {
                    Err(format!("region `{name}` is empty"))
                } else {
                    Ok(lines)
                };
            }
        }
        lines.push(line);
    }
    Err(format!("region `{name}` is not closed"))
}

/// What of a region's lines counts: the code, without comment lines and without white space.
pub fn normalise(lines: &[&str]) -> String {
    lines
        .iter()
        .filter(|l| !l.trim_start().starts_with("//"))
        .flat_map(|l| l.chars().filter(|c| !c.is_whitespace()))
        .collect()
}

/// The value at a dotted key of a TOML document (`paper4.fig4`), as canonical JSON.
fn published_value(tables: &toml::Value, key: &str) -> Result<String, String> {
    let mut value = tables;
    for part in key.split('.') {
        value = value
            .get(part)
            .ok_or_else(|| format!("assets/paper_tables.toml has no key `{key}`"))?;
    }
    serde_json::to_string(value).map_err(|e| format!("`{key}`: {e}"))
}

/// The version of `def` for a run at `--quick` sizes or not, from the project's files as
/// `sources` gives them (path to text) and the published tables' TOML text. The error names
/// the claim and the part that is missing.
pub fn version<'s>(
    def: &ClaimDef,
    quick: bool,
    sources: &dyn Fn(&str) -> Option<&'s str>,
    tables: &str,
) -> Result<String, String> {
    let fail = |e: String| format!("claim {}: {e}", def.id);
    let mut hash = Fnv::default();
    hash.add(def.id.as_bytes());
    let regions = |kind: &str, parts: &[&str], hash: &mut Fnv| -> Result<(), String> {
        for part in parts {
            let (file, name) = part
                .split_once('#')
                .ok_or_else(|| fail(format!("{kind} part `{part}` is not `path#region`")))?;
            let text = sources(file).ok_or_else(|| {
                fail(format!(
                    "{kind} part `{part}`: {file} is not a file a claim may be cut from (the Rust \
                     files under src/report/, src/timing.rs and src/mass/models.rs)"
                ))
            })?;
            let lines = cut(text, name).map_err(|e| fail(format!("{file}: {e}")))?;
            hash.add(kind.as_bytes())
                .add(part.as_bytes())
                .add(normalise(&lines).as_bytes());
        }
        Ok(())
    };
    regions("rule", def.rule, &mut hash)?;
    regions("workload", def.workload, &mut hash)?;
    let tables: toml::Value = tables
        .parse()
        .map_err(|e| fail(format!("assets/paper_tables.toml: {e}")))?;
    for key in def.published {
        let value = published_value(&tables, key).map_err(fail)?;
        hash.add(b"published")
            .add(key.as_bytes())
            .add(value.as_bytes());
    }
    hash.add(if quick { b"--quick" } else { b"papers' sizes" });
    if let Some(band) = def.band {
        hash.add(format!("band {band}").as_bytes());
    }
    Ok(hash.hex())
}

/// A file of this build that claims may be cut from, as compiled in.
pub fn compiled_source(path: &str) -> Option<&'static str> {
    CLAIM_SOURCES
        .iter()
        .find(|(name, _)| *name == path)
        .map(|(_, text)| *text)
}

/// This build's version of `def` (HEAD's, for the binary of a checkout).
pub fn current(def: &ClaimDef, quick: bool) -> Result<String, String> {
    version(def, quick, &compiled_source, PAPER_TABLES_TOML)
}

#[cfg(test)]
mod tests {
    use super::*;

    const CLAIMS_RS: &str = "\
use x;

// region: rule a
const A: ClaimDef = ClaimDef { id: \"s.a\", rule: &[\"f.rs#rule a\"], published: &[], \
                                 workload: &[], band: None };
/// The doc comment of a.
fn a(r: &R) -> Claim {
    // a comment
    Claim { holds: Some(r.pairs == 0), ..Default::default() }
}
// endregion

// region: rule b
fn b(r: &R) -> Claim {
    Claim { holds: Some(r.error < 0.05), ..Default::default() }
}
// endregion
";

    fn def(id: &'static str, rule: &'static [&'static str]) -> ClaimDef {
        ClaimDef {
            id,
            rule,
            published: &["paper4.fig4"],
            workload: &[],
            band: None,
        }
    }

    fn version_of(d: &ClaimDef, text: &str, tables: &str) -> String {
        version(d, false, &|p: &str| (p == "f.rs").then_some(text), tables).unwrap()
    }

    const TABLES: &str = "[paper4.fig4]\nbound = 0.05\n[paper4.fig5]\nx = 1\n";

    #[test]
    fn a_version_changes_with_its_rule_only() {
        let (a, b) = (def("s.a", &["f.rs#rule a"]), def("s.b", &["f.rs#rule b"]));
        let before = [
            version_of(&a, CLAIMS_RS, TABLES),
            version_of(&b, CLAIMS_RS, TABLES),
        ];
        // b's rule changes: b's version changes, a's does not.
        let edited = CLAIMS_RS.replace("r.error < 0.05", "r.error <= 0.05");
        assert_eq!(version_of(&a, &edited, TABLES), before[0]);
        assert_ne!(version_of(&b, &edited, TABLES), before[1]);
        // Code outside every region, comments and layout inside one: no version changes.
        let elsewhere = CLAIMS_RS
            .replace(
                "use x;",
                "use x;\nfn caption() -> &'static str { \"Fig. 4\" }",
            )
            .replace("// a comment", "// another comment, longer")
            .replace("/// The doc comment of a.", "/// Reworded.")
            .replace("Claim { holds", "Claim {\n        holds");
        assert_eq!(version_of(&a, &elsewhere, TABLES), before[0]);
        assert_eq!(version_of(&b, &elsewhere, TABLES), before[1]);
    }

    #[test]
    fn a_version_changes_with_its_published_value_and_its_sizes() {
        let a = def("s.a", &["f.rs#rule a"]);
        let v = version_of(&a, CLAIMS_RS, TABLES);
        // Its own published value.
        assert_ne!(
            version_of(&a, CLAIMS_RS, &TABLES.replace("0.05", "0.04")),
            v
        );
        // Another value of the tables.
        assert_eq!(
            version_of(&a, CLAIMS_RS, &TABLES.replace("x = 1", "x = 2")),
            v
        );
        // --quick sizes are another workload.
        let quick = version(&a, true, &|_: &str| Some(CLAIMS_RS), TABLES).unwrap();
        assert_ne!(quick, v);
        // A workload region: changing its code changes the version.
        let sized = ClaimDef {
            workload: &["f.rs#rule b"],
            ..a
        };
        let edited = CLAIMS_RS.replace("r.error < 0.05", "r.error < 0.5");
        assert_ne!(
            version_of(&sized, CLAIMS_RS, TABLES),
            version_of(&sized, &edited, TABLES)
        );
        // The band a timing is judged in.
        let banded = ClaimDef {
            band: Some(0.25),
            ..a
        };
        assert_ne!(version_of(&banded, CLAIMS_RS, TABLES), v);
    }

    #[test]
    fn a_missing_part_is_an_error_naming_the_claim() {
        let missing = def("s.c", &["f.rs#rule c"]);
        let e = version(&missing, false, &|_: &str| Some(CLAIMS_RS), TABLES).unwrap_err();
        assert!(e.contains("s.c") && e.contains("rule c"), "{e}");
        let other_file = def("s.a", &["g.rs#rule a"]);
        let e = version(&other_file, false, &|_: &str| None::<&str>, TABLES).unwrap_err();
        assert!(e.contains("g.rs"), "{e}");
        let key = ClaimDef {
            published: &["paper4.fig9"],
            ..def("s.a", &["f.rs#rule a"])
        };
        let e = version(&key, false, &|_: &str| Some(CLAIMS_RS), TABLES).unwrap_err();
        assert!(e.contains("paper4.fig9"), "{e}");
        assert!(cut("// region: x\n\n// endregion\n", "x").is_err());
        assert!(cut("// region: x\nfn f() {}\n", "x").is_err());
        assert!(cut(
            "// region: x\na\n// endregion\n// region: x\nb\n// endregion\n",
            "x"
        )
        .is_err());
    }

    #[test]
    fn regions_nest() {
        let text = "// region: outer\na\n// region: inner\nb\n// endregion\nc\n// endregion\n";
        assert_eq!(normalise(&cut(text, "outer").unwrap()), "abc");
        assert_eq!(normalise(&cut(text, "inner").unwrap()), "b");
    }
}
