//! The lecture-1 section's blocks (a minimal stand-in for the section module, so that the
//! distance-field and swept-volume blocks compile and can be checked on this branch; the
//! section itself lists every block).

pub mod distance_field;
pub mod swept_volume;

use super::timing::Load;
use super::{BenchOptions, Claim, Fidelity, Figure, Table};
use crate::report::timing::Runs;
use serde::Serialize;

/// What every block gets: the bench options, how often to repeat a timing, the renderer.
pub struct Setting<'a, 'b> {
    pub opts: &'a BenchOptions<'b>,
    pub runs: Runs,
    /// The renderer line (vendor, renderer, version).
    pub renderer: String,
    /// A software rasterizer: its "GPU" passes share the CPU cores with the CPU references.
    pub software: bool,
}

impl Setting<'_, '_> {
    /// A spinner for one block's stage (hidden where progress bars are).
    pub fn stage(&self, name: &str) -> indicatif::ProgressBar {
        let bar = self
            .opts
            .progress
            .add(indicatif::ProgressBar::new_spinner());
        bar.set_message(format!("lecture 1: {name}"));
        bar
    }
}

/// One block of the section: its typed results (serialised into the section's results) and
/// what it adds to the page.
#[derive(Serialize, Default)]
pub struct Block {
    pub id: String,
    /// Every measured number of the block, machine readable.
    pub results: serde_json::Value,
    /// The machine's load while the block's timings were taken.
    pub load: Option<Load>,
    /// One or two sentences for the section's summary.
    #[serde(skip)]
    pub summary: String,
    #[serde(skip)]
    pub tables: Vec<Table>,
    #[serde(skip)]
    pub figures: Vec<Figure>,
    #[serde(skip)]
    pub claims: Vec<Claim>,
    #[serde(skip)]
    pub fidelity: Vec<Fidelity>,
}
