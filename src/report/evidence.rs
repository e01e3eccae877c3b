//! The numbers a claim's verdict rests on, kept machine readable beside its words, so that
//! `compare --baseline` can tell which of them changed between two runs and whether the
//! change is a regression: a count, a pair set or an exact result that changed, an error that
//! passed its bound, or a timing that moved past its band between two quiet runs (a baseline
//! of expected results, as Mesa's deqp-runner keeps; a timing change called only where the
//! samples allow it, as asv's `compare` does).

use super::versions::{ClaimDef, Fnv};
use crate::timing::Load;
use serde::{Deserialize, Serialize};

/// One number of a claim, named.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Evidence {
    /// What the number is, in a few words ("pairs missed by streaming"); unique in its claim.
    pub name: String,
    #[serde(flatten)]
    pub measure: Measure,
}

/// What kind of number it is, which says how a change between two runs is judged.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Measure {
    /// A count (pixels, pairs, draws, steps) or a share of counts: the same on every run of
    /// the same sizes and renderer, so any change is a regression.
    Count { value: f64 },
    /// An exact result (bit for bit, equal to the reference): any change is a regression.
    Exact { value: bool },
    /// A set of pairs, by its size and a digest of its sorted pairs: any change is a
    /// regression.
    PairSet(PairSet),
    /// An error against a reference and the bound the claim allows: a regression when it
    /// passes the bound.
    Error { value: f64, bound: f64 },
    /// A timing (a median, or a ratio of medians): judged only when both runs were quiet, a
    /// regression when it moved the wrong way by more than `band` (relative).
    Timing {
        value: f64,
        unit: String,
        higher_is_better: bool,
        band: f64,
        /// The machine's load when it was taken.
        load: Option<Load>,
    },
}

/// A set of pairs of indices, as a run records it: how many, and a digest of them all.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PairSet {
    pub pairs: u64,
    pub digest: String,
}

/// Builds a [`PairSet`] frame by frame (each frame's pairs sorted, as the pipelines give
/// them).
#[derive(Clone, Debug, Default)]
pub struct PairDigest {
    pairs: u64,
    hash: Fnv,
}

impl PairDigest {
    /// Adds one frame's pairs (the frame boundary counts: the same pairs split otherwise over
    /// the frames give another digest).
    pub fn frame(&mut self, pairs: &[(u32, u32)]) {
        self.pairs += pairs.len() as u64;
        for (a, b) in pairs {
            self.hash.add(&a.to_le_bytes()).add(&b.to_le_bytes());
        }
        self.hash.add(b"frame");
    }

    pub fn finish(&self) -> PairSet {
        PairSet {
            pairs: self.pairs,
            digest: self.hash.hex(),
        }
    }
}

impl Evidence {
    pub fn count(name: &str, value: f64) -> Evidence {
        Evidence {
            name: name.into(),
            measure: Measure::Count { value },
        }
    }

    pub fn exact(name: &str, value: bool) -> Evidence {
        Evidence {
            name: name.into(),
            measure: Measure::Exact { value },
        }
    }

    pub fn error(name: &str, value: f64, bound: f64) -> Evidence {
        Evidence {
            name: name.into(),
            measure: Measure::Error { value, bound },
        }
    }

    pub fn pairs(name: &str, set: &PairSet) -> Evidence {
        Evidence {
            name: name.into(),
            measure: Measure::PairSet(set.clone()),
        }
    }

    /// Whether its numbers are finite (a ratio of a zero time is not, and JSON cannot hold
    /// it): only those are kept in a run's results.
    pub fn is_finite(&self) -> bool {
        match &self.measure {
            Measure::Count { value } | Measure::Timing { value, .. } => value.is_finite(),
            Measure::Error { value, bound } => value.is_finite() && bound.is_finite(),
            Measure::Exact { .. } | Measure::PairSet(_) => true,
        }
    }

    /// The number in words: "12", "0.0310 (bound 0.05)", "21.4 ms", "yes".
    pub fn value_in_words(&self) -> String {
        match &self.measure {
            Measure::Count { value } => number(*value),
            Measure::Exact { value } => if *value { "yes" } else { "no" }.into(),
            Measure::PairSet(set) => format!("{} pairs (digest {})", set.pairs, set.digest),
            Measure::Error { value, bound } => format!("{value:.3e} (bound {bound:.1e})"),
            Measure::Timing { value, unit, .. } => format!("{}{unit}", number(*value)),
        }
    }
}

/// A number in words: whole numbers whole, others to 4 significant digits.
fn number(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{v:.0}")
    } else {
        let rounded: f64 = format!("{v:.3e}").parse().unwrap_or(v);
        format!("{rounded}")
    }
}

impl ClaimDef {
    /// A timing of this claim, judged in its [`ClaimDef::band`] (none stated: any move of a
    /// quiet run counts).
    pub fn timing(
        &self,
        name: &str,
        value: f64,
        unit: &str,
        higher_is_better: bool,
        load: Option<Load>,
    ) -> Evidence {
        Evidence {
            name: name.into(),
            measure: Measure::Timing {
                value,
                unit: unit.into(),
                higher_is_better,
                band: self.band.unwrap_or(0.0),
                load,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_evidence_json_can_hold_is_finite() {
        assert!(Evidence::count("pairs", 12.0).is_finite());
        assert!(!Evidence::count("speed-up", f64::INFINITY).is_finite());
        assert!(!Evidence::error("error", f64::NAN, 0.05).is_finite());
        assert!(!Evidence::error("error", 0.01, f64::INFINITY).is_finite());
        assert!(Evidence::exact("equal", false).is_finite());
        let ratio = |value| Evidence {
            name: "ratio".into(),
            measure: Measure::Timing {
                value,
                unit: "x".into(),
                higher_is_better: true,
                band: 0.2,
                load: None,
            },
        };
        assert!(ratio(2.5).is_finite());
        assert!(!ratio(f64::NAN).is_finite());
    }
}
