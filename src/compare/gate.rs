//! `compare --baseline OLD.json NEW.json`: the regression gate CI runs on each build. Every
//! claim of the baseline is looked up in the new run (by its id) and, where both judged the
//! same version of it, its numbers ([`crate::report::Evidence`]) are compared:
//!
//! - a count, a pair set or an exact result that changed is a regression, as is an error that
//!   passed its bound and a verdict decided by counts (or errors, or the run's size) that
//!   flipped, and a claim the new run lost from a section it ran;
//! - a timing is judged only when both runs were quiet (load at most
//!   [`crate::timing::LOADED_PER_CORE`] per core) on one machine (renderer and CPU), against the
//!   band its claim states, at the papers' sizes, and is otherwise "not judged", never a
//!   failure (so is a timed claim whose baseline kept no figures, as runs from before claims
//!   kept them): a `--quick` run's timings, as CI's, are too short to hold still;
//! - a claim whose version differs "changed definition": it is listed, not judged.
//!
//! Anchors: Mesa's deqp-runner (a baseline of expected results, each failure listed) and asv's
//! `compare` (a change in a timing called only where the samples allow it).

use super::run::Run;
use crate::page::html::xml_escape;
use crate::report::evidence::Measure;
use crate::report::{Basis, Claim, Evidence, Section};
use crate::timing::Load;
use serde::Serialize;

/// What the gate made of one claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// Nothing it rests on changed.
    Same,
    /// Something changed within what the claim allows (an error within its bound, a timing
    /// within its band, a verdict on timings): listed, not a regression.
    Changed,
    /// The verdict, decided by counts or errors, is the same, and it is all that could be
    /// compared (the baseline kept no figures): listed with the new figures.
    SameVerdict,
    Regressed,
    /// The two runs judged different versions of the claim.
    ChangedDefinition,
    /// A timing it rests on could not be judged (a run was loaded, or its load unknown).
    NotJudged,
    /// The claim is only in the new run, or only in the baseline of a section the new run
    /// did not run: listed, not compared.
    NotCompared,
}

impl Outcome {
    /// The word that starts the claim's line.
    pub fn word(self) -> &'static str {
        match self {
            Outcome::Same => "same",
            Outcome::Changed => "changed",
            Outcome::SameVerdict => "same verdict",
            Outcome::Regressed => "REGRESSED",
            Outcome::ChangedDefinition => "changed definition",
            Outcome::NotJudged => "not judged",
            Outcome::NotCompared => "not compared",
        }
    }
}

/// One claim through the gate.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The claim's id (its section and words for a run from before ids).
    pub id: String,
    pub section: String,
    pub outcome: Outcome,
    /// What changed, one line each.
    pub changes: Vec<String>,
}

/// The gate's result.
#[derive(Clone, Debug, Serialize)]
pub struct Gate {
    pub baseline: String,
    pub new: String,
    pub rows: Vec<Row>,
}

impl Gate {
    fn count(&self, outcome: Outcome) -> usize {
        self.rows.iter().filter(|r| r.outcome == outcome).count()
    }

    /// The claims compared: every claim of the baseline in a section the new run ran.
    pub fn compared(&self) -> usize {
        self.rows
            .iter()
            .filter(|r| r.outcome != Outcome::NotCompared)
            .count()
    }

    pub fn regressed(&self) -> usize {
        self.count(Outcome::Regressed)
    }

    /// `compared N claims: R regressed, C changed definition, J not judged`.
    pub fn summary(&self) -> String {
        format!(
            "compared {} claims: {} regressed, {} changed definition, {} not judged",
            self.compared(),
            self.regressed(),
            self.count(Outcome::ChangedDefinition),
            self.count(Outcome::NotJudged)
        )
    }

    /// Every row that is not [`Outcome::Same`], a line each with its changes under it, then
    /// the summary as the last line.
    pub fn to_text(&self) -> String {
        let mut out = format!("baseline {}\nnew      {}\n", self.baseline, self.new);
        let listed = |r: &&Row| !matches!(r.outcome, Outcome::Same | Outcome::NotCompared);
        for row in self.rows.iter().filter(listed) {
            out.push_str(&format!("{}: {}\n", row.outcome.word(), row.id));
            for change in &row.changes {
                out.push_str(&format!("    {change}\n"));
            }
        }
        // The claims not compared, a line per reason (a section one run did not run).
        let mut reasons: Vec<(&str, usize)> = Vec::new();
        for row in self
            .rows
            .iter()
            .filter(|r| r.outcome == Outcome::NotCompared)
        {
            let why = row.changes.first().map_or("", String::as_str);
            match reasons.iter_mut().find(|(w, _)| *w == why) {
                Some((_, n)) => *n += 1,
                None => reasons.push((why, 1)),
            }
        }
        for (why, n) in reasons {
            out.push_str(&format!(
                "not compared: {n} claim{}: {why}\n",
                if n == 1 { "" } else { "s" }
            ));
        }
        out.push_str(&self.summary());
        out.push('\n');
        out
    }

    /// The same as JUnit XML: a test case per claim compared; a regression is a failure, a
    /// changed definition or a timing not judged is skipped with the reason.
    pub fn to_junit(&self) -> String {
        let compared: Vec<&Row> = self
            .rows
            .iter()
            .filter(|r| r.outcome != Outcome::NotCompared)
            .collect();
        let skipped = compared
            .iter()
            .filter(|r| matches!(r.outcome, Outcome::ChangedDefinition | Outcome::NotJudged))
            .count();
        let mut xml = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
        xml.push_str(&format!(
            "<testsuites name=\"classic-gpgpu compare --baseline\" tests=\"{}\" failures=\"{}\" \
             skipped=\"{skipped}\">\n  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" \
             errors=\"0\" skipped=\"{skipped}\">\n",
            compared.len(),
            self.regressed(),
            xml_escape(&format!("{} against {}", self.new, self.baseline)),
            compared.len(),
            self.regressed(),
        ));
        for row in compared {
            let open = format!(
                "    <testcase classname=\"classic_gpgpu.compare.{}\" name=\"{}\"",
                xml_escape(&row.section),
                xml_escape(&row.id)
            );
            let detail = xml_escape(&row.changes.join("\n"));
            let body = match row.outcome {
                Outcome::Regressed => format!("<failure message=\"{detail}\">{detail}</failure>"),
                Outcome::ChangedDefinition | Outcome::NotJudged => {
                    format!("<skipped message=\"{}: {detail}\"/>", row.outcome.word())
                }
                _ => format!("<system-out>{detail}</system-out>"),
            };
            xml.push_str(&format!("{open}>\n      {body}\n    </testcase>\n"));
        }
        xml.push_str("  </testsuite>\n</testsuites>\n");
        xml
    }
}

/// The claims of a run by key ([`super::key`]), in report order.
fn claims(run: &Run) -> Vec<(String, &Section, &Claim)> {
    run.sections
        .iter()
        .flat_map(|s| s.claims.iter().map(move |c| (super::key(s, c), s, c)))
        .collect()
}

/// The gate: `new` against `baseline`.
pub fn gate(baseline: &Run, new: &Run) -> Gate {
    let old_claims = claims(baseline);
    let new_claims = claims(new);
    let mut rows = Vec::new();
    for (key, section, old) in &old_claims {
        let found = new_claims
            .iter()
            .find(|(k, s, c)| same_claim((key, *section, *old), (k, *s, *c)));
        let row = |outcome, changes| Row {
            id: key.clone(),
            section: section.id.clone(),
            outcome,
            changes,
        };
        rows.push(match found {
            // Named by the new run's id where the baseline's claim has none.
            Some((new_key, _, claim)) => judge(new_key, section, old, claim, baseline, new),
            None if new.section(&section.id).is_some() => row(
                Outcome::Regressed,
                vec![format!(
                    "the new run made no such claim, though it ran section {}",
                    section.id
                )],
            ),
            None => row(
                Outcome::NotCompared,
                vec![format!("the new run did not run section {}", section.id)],
            ),
        });
    }
    for (key, section, claim) in &new_claims {
        let known = old_claims
            .iter()
            .any(|(k, s, c)| same_claim((k, *s, *c), (key, *section, *claim)));
        if !known {
            rows.push(Row {
                id: key.clone(),
                section: section.id.clone(),
                outcome: Outcome::NotCompared,
                changes: vec!["a claim the baseline does not have".into()],
            });
        }
    }
    Gate {
        baseline: describe(baseline),
        new: describe(new),
        rows,
    }
}

/// Whether two runs' claims are the same claim: the same id, or where one run is from before
/// claims had ids, the same section and words.
fn same_claim(a: (&String, &Section, &Claim), b: (&String, &Section, &Claim)) -> bool {
    a.0 == b.0
        || ((a.2.id.is_empty() || b.2.id.is_empty()) && a.1.id == b.1.id && a.2.claim == b.2.claim)
}

/// A run in a line: file, renderer, commit, date, sizes.
fn describe(run: &Run) -> String {
    format!(
        "{} ({}, commit {}, {}{})",
        run.file,
        run.label,
        run.short_commit(),
        run.date,
        if run.quick { ", --quick" } else { "" }
    )
}

/// One claim judged by both runs.
fn judge(key: &str, section: &Section, old: &Claim, new: &Claim, a: &Run, b: &Run) -> Row {
    let mut row = Row {
        id: key.into(),
        section: section.id.clone(),
        outcome: Outcome::Same,
        changes: Vec::new(),
    };
    if old.version.is_empty() || new.version.is_empty() || old.version != new.version {
        row.outcome = Outcome::ChangedDefinition;
        let why = if a.quick != b.quick {
            "the runs were made at different sizes".to_string()
        } else if old.version.is_empty() || new.version.is_empty() {
            format!(
                "{}: run before per-claim versions",
                if old.version.is_empty() {
                    &a.file
                } else {
                    &b.file
                }
            )
        } else {
            format!("changed since {}", a.short_commit())
        };
        row.changes.push(format!(
            "version {} -> {} ({why})",
            or_none(&old.version),
            or_none(&new.version)
        ));
        return row;
    }
    let mut regressed = false;
    let mut not_judged = false;
    if old.holds != new.holds {
        let by_counts = new.decided_by != Basis::Timing && old.decided_by != Basis::Timing;
        regressed |= by_counts;
        row.changes.push(format!(
            "verdict {} -> {} (decided by {}{})",
            old.verdict(),
            new.verdict(),
            or_none(new.decided_by.in_words()),
            if by_counts {
                ""
            } else {
                ": a timing's verdict; its figures are judged below"
            }
        ));
    }
    for e in &old.evidence {
        let Some(n) = new.evidence.iter().find(|n| n.name == e.name) else {
            row.changes
                .push(format!("{}: not in the new run's figures", e.name));
            continue;
        };
        let (change, verdict) = match timing_not_judged(e, n, a, b) {
            None => compare_evidence(e, n),
            Some(why) => (
                format!(
                    "{}: {} -> {} (not judged: {why})",
                    e.name,
                    e.value_in_words(),
                    n.value_in_words()
                ),
                Verdict::NotJudged,
            ),
        };
        match verdict {
            Verdict::Regressed => regressed = true,
            Verdict::NotJudged => not_judged = true,
            Verdict::Same | Verdict::Within => {}
        }
        if verdict != Verdict::Same {
            row.changes.push(change);
        }
    }
    for n in &new.evidence {
        if !old.evidence.iter().any(|e| e.name == n.name) {
            row.changes
                .push(format!("{}: new figure {}", n.name, n.value_in_words()));
        }
    }
    // A baseline that kept no figures (a run from before claims kept them): only a verdict
    // decided by counts can be judged; a timing's has nothing to be judged against.
    let mut verdict_only = false;
    if old.evidence.is_empty() && !new.evidence.is_empty() {
        let timed = old.decided_by == Basis::Timing || new.decided_by == Basis::Timing;
        not_judged |= timed;
        verdict_only = !timed && old.holds == new.holds;
        row.changes.insert(
            0,
            format!(
                "the baseline kept no figures of this claim: {}",
                if timed {
                    "its timings are not judged"
                } else {
                    "only its verdict is compared"
                }
            ),
        );
    }
    row.outcome = if regressed {
        Outcome::Regressed
    } else if not_judged {
        Outcome::NotJudged
    } else if verdict_only {
        Outcome::SameVerdict
    } else if row.changes.is_empty() {
        Outcome::Same
    } else {
        Outcome::Changed
    };
    row
}

fn or_none(text: &str) -> &str {
    if text.is_empty() {
        "(none)"
    } else {
        text
    }
}

/// How one number moved between two runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    Same,
    /// Changed, within what the claim allows.
    Within,
    Regressed,
    NotJudged,
}

/// Why a timing that moved between two runs cannot be judged, if it cannot: the runs are of
/// two machines, or of `--quick` sizes, whose passes are too short for their medians to hold
/// still between two runs of one machine (two quiet quick runs differ by more than a band).
fn timing_not_judged(e: &Evidence, n: &Evidence, a: &Run, b: &Run) -> Option<&'static str> {
    if !is_timing(e) || e == n {
        None
    } else if !same_machine(a, b) {
        Some("timings of two machines")
    } else if a.quick || b.quick {
        Some("timings at --quick sizes are too short to judge")
    } else {
        None
    }
}

/// Whether two runs are of one machine (the same renderer and CPU): only then are their timings
/// judged against each other.
fn same_machine(a: &Run, b: &Run) -> bool {
    a.renderer == b.renderer && a.cpu == b.cpu
}

fn is_timing(e: &Evidence) -> bool {
    matches!(e.measure, Measure::Timing { .. })
}

/// Whether a load counts as quiet for judging a timing (a load not recorded does not).
fn quiet(load: &Option<Load>) -> bool {
    load.is_some_and(|l| !l.is_loaded())
}

/// Two runs' values of one number: the line that says how it moved, and the verdict.
pub fn compare_evidence(old: &Evidence, new: &Evidence) -> (String, Verdict) {
    let line = |why: &str| {
        format!(
            "{}: {} -> {}{why}",
            old.name,
            old.value_in_words(),
            new.value_in_words()
        )
    };
    match (&old.measure, &new.measure) {
        (Measure::Count { value: a }, Measure::Count { value: b }) => changed_exactly(a == b, line),
        (Measure::Exact { value: a }, Measure::Exact { value: b }) => changed_exactly(a == b, line),
        (Measure::PairSet(a), Measure::PairSet(b)) => changed_exactly(a == b, line),
        (Measure::Error { value: a, .. }, Measure::Error { value: b, bound }) => {
            if a == b {
                (line(""), Verdict::Same)
            } else if b > bound && a <= bound {
                (line(" (past its bound)"), Verdict::Regressed)
            } else {
                (
                    line(" (within its bound, or past it before too)"),
                    Verdict::Within,
                )
            }
        }
        (
            Measure::Timing {
                value: a,
                load: load_a,
                ..
            },
            Measure::Timing {
                value: b,
                load: load_b,
                band,
                higher_is_better,
                ..
            },
        ) => {
            if a == b {
                return (line(""), Verdict::Same);
            }
            if !(quiet(load_a) && quiet(load_b)) {
                return (
                    line(&format!(
                        " (not judged: {} machine loaded or its load unknown)",
                        if quiet(load_a) {
                            "the new run's"
                        } else {
                            "the baseline's"
                        }
                    )),
                    Verdict::NotJudged,
                );
            }
            let worse = if *higher_is_better {
                *b < a * (1.0 - band)
            } else {
                *b > a * (1.0 + band)
            };
            let moved = if *a == 0.0 { 0.0 } else { (b - a) / a };
            let why = format!(
                " ({:+.0}%, band {:.0}%{})",
                100.0 * moved,
                100.0 * band,
                if worse { ", worse past the band" } else { "" }
            );
            if worse {
                (line(&why), Verdict::Regressed)
            } else {
                (line(&why), Verdict::Within)
            }
        }
        _ => (
            line(" (measured another way: a regression)"),
            Verdict::Regressed,
        ),
    }
}

/// A number that must not change: the same, or a regression.
fn changed_exactly(same: bool, line: impl Fn(&str) -> String) -> (String, Verdict) {
    if same {
        (line(""), Verdict::Same)
    } else {
        (line(" (changed: a regression)"), Verdict::Regressed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quiet_load() -> Option<Load> {
        Some(Load {
            one_minute: 0.5,
            cores: 2,
        })
    }

    fn timing(value: f64, load: Option<Load>) -> Evidence {
        Evidence {
            name: "frame".into(),
            measure: Measure::Timing {
                value,
                unit: " ms".into(),
                higher_is_better: false,
                band: 0.25,
                load,
            },
        }
    }

    #[test]
    fn a_timing_is_judged_against_its_band_only_between_quiet_runs() {
        let q = quiet_load();
        assert_eq!(
            compare_evidence(&timing(10.0, q), &timing(10.0, q)).1,
            Verdict::Same
        );
        assert_eq!(
            compare_evidence(&timing(10.0, q), &timing(12.0, q)).1,
            Verdict::Within
        );
        assert_eq!(
            compare_evidence(&timing(10.0, q), &timing(13.0, q)).1,
            Verdict::Regressed
        );
        // Faster is never a regression.
        assert_eq!(
            compare_evidence(&timing(10.0, q), &timing(5.0, q)).1,
            Verdict::Within
        );
        let loaded = Some(Load {
            one_minute: 8.0,
            cores: 2,
        });
        for (a, b) in [(q, loaded), (loaded, q), (None, q)] {
            let (line, verdict) = compare_evidence(&timing(10.0, a), &timing(30.0, b));
            assert_eq!(verdict, Verdict::NotJudged, "{line}");
            assert!(line.contains("not judged"), "{line}");
        }
    }

    #[test]
    fn counts_pairs_and_exact_results_must_not_change_and_errors_keep_their_bound() {
        let count = |v| Evidence::count("pairs", v);
        assert_eq!(compare_evidence(&count(3.0), &count(3.0)).1, Verdict::Same);
        assert_eq!(
            compare_evidence(&count(3.0), &count(4.0)).1,
            Verdict::Regressed
        );
        let exact = |v| Evidence::exact("bit for bit", v);
        assert_eq!(
            compare_evidence(&exact(true), &exact(false)).1,
            Verdict::Regressed
        );
        let error = |v| Evidence::error("error", v, 0.05);
        assert_eq!(
            compare_evidence(&error(0.01), &error(0.02)).1,
            Verdict::Within
        );
        assert_eq!(
            compare_evidence(&error(0.01), &error(0.06)).1,
            Verdict::Regressed
        );
    }
}
