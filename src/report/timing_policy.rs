//! The report's one rule for claims judged on a timing, the same for every claim of every
//! section, applied here to each section as [`super::run_section`] builds it (no section
//! decides it for itself):
//!
//! - A timing claim is judged by what the renderer at hand measured, whatever the renderer,
//!   and not judged only when the measurement cannot decide it: the machine was loaded, the
//!   runs fall on both sides of the paper's number ([`crate::timing`]), or the run did not reach
//!   the sizes the claim is about. The renderer is never the reason.
//! - On a software renderer (llvmpipe, softpipe, lavapipe under zink) the "GPU" passes run on
//!   the CPU's cores, the cores the CPU baselines use too. There a verdict says what this
//!   renderer does against the paper's number, not what the paper's GPU did: every timing claim
//!   of such a run says so ([`SOFTWARE_MARK`]), and the report and the README say it once
//!   ([`IN_WORDS`]).

use super::{Basis, Claim, Section};

/// The policy in a reader's words, said once at the top of the report (and in the README).
pub const IN_WORDS: &str = "Timing claims, one rule for every section: a claim about speed is \
    judged by what the renderer at hand measured, whatever the renderer, and is not judged only \
    when the measurement cannot decide it (the machine was loaded, its runs fall on both sides \
    of the paper's number, or the run did not reach the sizes the claim is about). On a \
    software renderer (llvmpipe, softpipe, lavapipe under zink) the 'GPU' passes run on the \
    CPU's cores, the same cores as the CPU baselines: there a verdict says what that renderer \
    does against the paper's number, not what the paper's GPU did, and each such claim says \
    so.";

/// What every timing claim of a run on a software renderer ends with.
pub const SOFTWARE_MARK: &str = "on a software renderer: the verdict is this renderer's, not \
    the paper's GPU's";

/// Marks every timing claim of `section` when the run was on a software renderer.
pub fn apply(section: &mut Section, software: bool) {
    if !software {
        return;
    }
    for claim in section.claims.iter_mut().filter(|c| is_timing(c)) {
        if !claim.measured.contains(SOFTWARE_MARK) {
            claim.measured = format!("{}; {SOFTWARE_MARK}", claim.measured);
        }
    }
}

/// The timing claims of `section` that the policy does not cover: one not judged without a
/// reason in its text, or with the renderer as the reason. Empty when every claim is covered.
pub fn problems(section: &Section) -> Vec<String> {
    section
        .claims
        .iter()
        .filter(|c| is_timing(c) && c.holds.is_none())
        .filter_map(|c| {
            let text = c.measured.replace(SOFTWARE_MARK, "").to_lowercase();
            // The reason: from "not judged" to the end of its clause.
            let reason = text
                .find("not judged")
                .map(|at| text[at..].split(';').next().unwrap_or_default());
            match reason {
                None => Some(format!("'{}' is not judged and does not say why", c.claim)),
                Some(r) if r.contains("software renderer") || r.contains("not the gpu") => Some(
                    format!("'{}' is not judged because of the renderer", c.claim),
                ),
                Some(_) => None,
            }
        })
        .collect()
}

fn is_timing(claim: &Claim) -> bool {
    claim.decided_by == Basis::Timing
}

#[cfg(test)]
mod tests {
    use super::*;

    fn timing(claim: &str, holds: Option<bool>, measured: &str) -> Claim {
        Claim {
            claim: claim.into(),
            paper: "the paper's number".into(),
            measured: measured.into(),
            holds,
            decided_by: Basis::Timing,
            ..Claim::default()
        }
    }

    /// Sections as papers 1, 3 and 4 and lectures 1 and 3 make them on llvmpipe: claims judged
    /// yes and no by timing, one not judged for the load, one a section tried to leave
    /// unjudged for the renderer, and a count that the policy leaves alone.
    fn llvmpipe_sections() -> Vec<Section> {
        let section = |id: &str, claims: Vec<Claim>| Section {
            id: id.into(),
            claims,
            ..Section::default()
        };
        vec![
            section(
                "paper1",
                vec![timing("faster than SOLID", Some(false), "0.06-0.10x")],
            ),
            section(
                "paper3",
                vec![timing(
                    "20 times faster",
                    None,
                    "0.92x; not judged: a software renderer is not the GPU the claim is about",
                )],
            ),
            section(
                "paper4",
                vec![timing(
                    "beats the analytic method",
                    None,
                    "9.2 ms; not judged: machine loaded (2.1 per core)",
                )],
            ),
            section(
                "lecture3",
                vec![
                    timing("hundreds of frames per second", Some(true), "310 frames/s"),
                    timing("a timing that keeps quiet", None, "12 ms"),
                    Claim {
                        decided_by: Basis::Count,
                        ..timing("same pairs", Some(true), "equal")
                    },
                ],
            ),
        ]
    }

    #[test]
    fn no_timing_claim_of_an_llvmpipe_report_escapes_the_policy() {
        let mut sections = llvmpipe_sections();
        for s in &mut sections {
            apply(s, true);
        }
        let problems: Vec<String> = sections.iter().flat_map(problems).collect();
        assert_eq!(
            problems,
            [
                "'20 times faster' is not judged because of the renderer",
                "'a timing that keeps quiet' is not judged and does not say why"
            ]
        );
        for c in sections.iter().flat_map(|s| &s.claims) {
            let marked = c.measured.ends_with(SOFTWARE_MARK);
            assert_eq!(marked, c.decided_by == Basis::Timing, "{}", c.measured);
        }
        // Applied twice (a section kept by `--only` and built again), marked once.
        let mut again = sections[0].clone();
        apply(&mut again, true);
        assert_eq!(again.claims[0].measured.matches(SOFTWARE_MARK).count(), 1);
    }

    #[test]
    fn a_gpu_run_is_not_marked_and_the_rule_is_the_same() {
        let mut sections = llvmpipe_sections();
        apply(&mut sections[0], false);
        assert!(!sections[0].claims[0].measured.contains(SOFTWARE_MARK));
        assert_eq!(
            problems(&sections[1]).len(),
            1,
            "the renderer is no reason on a GPU either"
        );
        assert!(problems(&sections[2]).is_empty());
        assert!(IN_WORDS.contains("whatever the renderer") && IN_WORDS.contains("llvmpipe"));
    }
}
