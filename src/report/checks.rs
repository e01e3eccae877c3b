//! What a section says it checked, held to what its run did.
//!
//! A section lists its checks once (a `const` table of [`Check`]s): its summary names them
//! from that list ([`sentence`]), and the code that makes a check records its id as the run
//! goes. [`verify`] then fails the section when a listed check was not made or a made check
//! is not listed, and when the run took a path (a method, a formulation, a scene) that no
//! fidelity row covers. [`super::run_section`] runs it for every section.

use super::Fidelity;

/// One check of a section: an id the run records, and the words the summary says of it.
#[derive(Clone, Copy, Debug)]
pub struct Check {
    pub id: &'static str,
    /// What is compared with what, as the summary says it ("the pairs found on the GPU
    /// against brute force on the CPU ...").
    pub says: &'static str,
}

/// The summary's sentence naming `checks`, in the list's order.
pub fn sentence(checks: &[Check]) -> String {
    let items: Vec<String> = checks
        .iter()
        .enumerate()
        .map(|(i, c)| format!("({}) {}", i + 1, c.says))
        .collect();
    format!("Checked in this run: {}.", items.join("; "))
}

/// The ids of `checks`.
pub fn ids(checks: &[Check]) -> Vec<String> {
    checks.iter().map(|c| c.id.to_string()).collect()
}

/// The section's claims against its run: every listed check made, every made check listed,
/// every path taken covered by a fidelity row.
pub fn verify(
    section: &str,
    listed: &[String],
    made: &[String],
    paths: &[String],
    rows: &[Fidelity],
) -> anyhow::Result<()> {
    if let Some(id) = listed.iter().find(|id| !made.contains(id)) {
        anyhow::bail!(
            "section {section}: its summary names the check '{id}', which the run did not \
             make (list only the checks the code makes)"
        );
    }
    if let Some(id) = made.iter().find(|id| !listed.contains(id)) {
        anyhow::bail!(
            "section {section}: the run made the check '{id}', which the section's list of \
             checks does not name (add it to the list)"
        );
    }
    if let Some(path) = paths
        .iter()
        .find(|p| !rows.iter().any(|r| r.paths.contains(p)))
    {
        anyhow::bail!(
            "section {section}: the run took the path '{path}', which no fidelity row covers \
             (add a row saying what the source does, what the code does and why)"
        );
    }
    Ok(())
}

/// The paths that `rows` cover.
pub fn covered(rows: &[Fidelity]) -> Vec<String> {
    rows.iter().flat_map(|r| r.paths.iter().cloned()).collect()
}

/// The ids of the checks whose condition holds (the comparison's numbers are in the
/// results), in the given order.
pub fn made(conditions: &[(bool, &'static str)]) -> Vec<String> {
    conditions
        .iter()
        .filter(|(made, _)| *made)
        .map(|(_, id)| id.to_string())
        .collect()
}

/// `checks` but those a run cannot make here: `skip` holds the ids of checks that need what
/// the context lacks (the compute formulation on OpenGL 3.3), so the summary does not name
/// them and [`verify`] does not ask for them.
pub fn without(checks: &[Check], skip: &[&str]) -> Vec<Check> {
    checks
        .iter()
        .filter(|c| !skip.contains(&c.id))
        .copied()
        .collect()
}

/// Paper 1's checks in a report run (the streaming pairs against brute force are tests'
/// work, not the run's).
pub const PAPER1: &[Check] = &[
    Check {
        id: "solid vs streaming",
        says: "SOLID's pairs against the streaming pairs, frame by frame (the frames where \
               they agree are counted)",
    },
    Check {
        id: "cullide vs streaming",
        says: "CULLIDE's pairs against the streaming pairs (the share it misses)",
    },
    Check {
        id: "then and now same pairs",
        says: "the then-and-now workload's pairs, the same from every formulation",
    },
];

/// Paper 2's checks in a report run: none (the skinned vertices are compared with CPU
/// linear blend skinning by the tests, `tests/crowd_gpu.rs`; the run times, it does not
/// compare).
pub const PAPER2: &[Check] = &[];

/// Paper 3's checks in a report run.
pub const PAPER3: &[Check] = &[
    Check {
        id: "outputs vs CPU",
        says: "every measured formulation's network outputs against the CPU forward pass \
               (the largest difference, in the tables)",
    },
    Check {
        id: "detection vs CPU",
        says: "text.png's classes from both GPU formulations against the CPU's (the share \
               that agree)",
    },
    Check {
        id: "then and now same outputs",
        says: "the then-and-now workload's outputs, classic against compute within their \
               bound",
    },
];

/// The summary's sentence for a list that may be empty.
pub fn sentence_or_none(checks: &[Check], none: &str) -> String {
    if checks.is_empty() {
        none.to_string()
    } else {
        sentence(checks)
    }
}
