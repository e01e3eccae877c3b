//! The lecture-1 section (the tutorial's first lecture beyond paper 1's streaming AABBs):
//! self-collision of deforming meshes, pairwise triangle tests with the triangles in
//! textures, and their compute counterpart (`src/lecture1/`), each GPU path beside its CPU
//! reference. Only the abstracts and introductions of the lecture's sources are public
//! (`lecture1-sources.md`): the section says which parts are reconstructions.
//!
//! The section is a list of blocks ([`BLOCKS`]), one file each. A block measures its part
//! and brings its own summary sentence, tables, figures, claims, fidelity rows and typed
//! results; the section puts them together in the list's order. Another part of lecture 1
//! (penetration depth, distance fields, swept volumes) is one more file here with a
//! `pub fn block(setting: &Setting) -> anyhow::Result<Block>`, its `mod` line, and its line
//! in [`BLOCKS`].

pub mod avatar_ccd;
pub mod distance_field;
mod fidelity;
mod pairwise;
pub mod penetration;
mod self_collision;
pub mod swept_volume;
mod then_and_now;

use super::timing::{Load, Runs};
use super::{BenchOptions, Claim, Fidelity, Figure, NoOptions, Paper, Section, Table};
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

/// How a block is measured.
pub type Measure = fn(&Setting) -> anyhow::Result<Block>;

/// The section's blocks, in report order: `(id, measure)`. A new part of lecture 1 adds its
/// line here (after its `mod` line above).
pub const BLOCKS: &[(&str, Measure)] = &[
    ("self-collision", self_collision::block),
    ("pairwise", pairwise::block),
    ("distance-field", distance_field::block),
    ("swept-volume", swept_volume::block),
    ("then-and-now", then_and_now::block),
    ("penetration", penetration::block),
    ("avatar-ccd", avatar_ccd::block),
];

/// Everything the section measured.
#[derive(Serialize)]
pub struct Lecture1Results {
    pub renderer: String,
    pub software: bool,
    pub quick: bool,
    /// How often each repeated timing ran.
    pub runs: String,
    pub blocks: Vec<Block>,
}

/// The lecture-1 section.
pub struct Lecture1;

impl Paper for Lecture1 {
    const ID: &'static str = "lecture1";
    const TITLE: &'static str = "Lecture 1 (Kim): self-collision and pairwise triangle tests on \
                                 the GPU, beyond paper 1's streaming AABBs";
    type Options = NoOptions;
    type Results = Lecture1Results;

    fn measure(opts: &BenchOptions, _: &NoOptions) -> anyhow::Result<Lecture1Results> {
        let info = opts.gl.info();
        let setting = Setting {
            opts,
            runs: opts.runs(3),
            renderer: info.renderer_line(),
            software: info.is_software(),
        };
        let blocks = BLOCKS
            .iter()
            .map(|(id, measure)| {
                let mut block =
                    measure(&setting).map_err(|e| e.context(format!("lecture 1, block {id}")))?;
                block.id = id.to_string();
                Ok(block)
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        Ok(Lecture1Results {
            renderer: setting.renderer,
            software: setting.software,
            quick: opts.quick,
            runs: setting.runs.in_words(),
            blocks,
        })
    }

    fn section(_: &BenchOptions, results: &Lecture1Results) -> anyhow::Result<Section> {
        let mut section = Section {
            summary: summary(results),
            fidelity: fidelity::rows(),
            ..Section::default()
        };
        for block in &results.blocks {
            section.tables.extend(block.tables.iter().cloned());
            section.figures.extend(block.figures.iter().cloned());
            section.claims.extend(block.claims.iter().cloned());
            section.fidelity.extend(block.fidelity.iter().cloned());
        }
        Ok(section)
    }
}

fn summary(r: &Lecture1Results) -> String {
    let mut text = format!(
        "Lecture 1 applies rasterization, occlusion queries and texture lookups to proximity \
         problems; paper 1's streaming AABBs are their own section. Only the abstracts and \
         introductions of the lecture's other sources are public, so what runs here are \
         reconstructions (see the fidelity table): self-collision is paper 1's pipeline with one \
         model against itself, and the pairwise tests with triangles in textures follow what \
         paper 1 says of Choi, Kim & Kim 2006 (their layout, pass and test are ours). Every GPU \
         answer is compared with brute force on the CPU with the same exact predicate, in the \
         same run, on {}.",
        r.renderer
    );
    for block in &r.blocks {
        if !block.summary.is_empty() {
            text.push(' ');
            text.push_str(&block.summary);
        }
    }
    text.push_str(&format!(" Timings: {} each, medians.", r.runs));
    if r.software {
        text.push_str(
            " A software rasterizer: its 'GPU' passes run on the CPU cores the CPU references \
             use, so the comparisons by triangle count are not those of a GPU.",
        );
    }
    if r.quick {
        text.push_str(" Quick mode: small models and few frames.");
    }
    text
}
