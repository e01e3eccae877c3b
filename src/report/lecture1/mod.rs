//! The lecture-1 section (the tutorial's first lecture beyond paper 1's streaming AABBs):
//! self-collision of deforming meshes, pairwise triangle tests with the triangles in
//! textures and their compute counterpart, distance fields and 2D generalized Voronoi
//! diagrams, swept volumes, penetration depth and continuous collision for an avatar
//! (`src/lecture1/`). Only the abstracts and introductions of the lecture's sources are public
//! (`lecture1-sources.md`): the fidelity table says which parts are reconstructions, and the
//! "not built" table what the sources name that the project does not do.
//!
//! The section is a list of blocks ([`BLOCKS`]), one file each. A block measures its part
//! and brings its own summary sentence, tables, figures, claims and typed results, and
//! records the checks it made ([`CHECKS`]) and the paths it took ([`paths`]); the fidelity
//! rows are in one file, `fidelity.rs`, and [`crate::report::run_section`] fails the section
//! when a listed check was not made or a path taken has no row. Another part of lecture 1 is
//! one more file here with a `pub fn block(setting: &Setting) -> anyhow::Result<Block>`, its
//! `mod` line, its line in [`BLOCKS`], its checks and paths, and its fidelity rows.

pub mod avatar_ccd;
pub mod distance_field;
mod fidelity;
mod pairwise;
pub mod penetration;
mod self_collision;
pub mod swept_volume;
mod then_and_now;

use super::checks::{self, Check};
use super::{BenchOptions, Claim, Fidelity, Figure, NoOptions, Paper, Section, Table};
use crate::timing::{Load, Runs};
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
    /// The checks of [`CHECKS`] the block made, recorded where it made them.
    pub checks_made: Vec<&'static str>,
    /// The paths ([`paths`]) the block took.
    pub paths: Vec<&'static str>,
}

/// The paths a lecture-1 run can take; each is covered by a fidelity row.
pub mod paths {
    pub const SELF_COLLISION: &str = "self-collision: streaming AABBs, one model against itself";
    pub const PAIRWISE: &str = "pairwise: triangles in textures, the pair quad";
    pub const PAIRWISE_COMPUTE: &str = "pairwise: one compute dispatch";
    pub const FIELD_SLICES: &str = "distance field: slices, exact distances, GL_MIN";
    pub const FIELD_COMPUTE: &str = "distance field: one compute dispatch";
    pub const FIELD_MESHES: &str = "distance field: Hoff's distance meshes, depth test";
    pub const FIELD_PARRY3D: &str = "distance field: parry3d's closest points as reference";
    pub const VORONOI_EXACT: &str = "voronoi: exact distances as depth";
    pub const VORONOI_MESH: &str = "voronoi: Hoff's distance meshes";
    pub const SWEPT_VOLUME: &str = "swept volume: field, flood fill, marching tetrahedra";
    pub const PENETRATION: &str = "penetration depth: Minkowski sums on a cube map";
    pub const AVATAR_CCD: &str = "avatar CCD: swept capsules, BVH, occlusion culling";
    pub const AVATAR_SCENE: &str = "avatar CCD: the 13-link figure in the room";
    pub const AVATAR_PUBLISHED: &str =
        "avatar CCD: the published scale, 16 links among 102k generated triangles";
}

/// Every check the section can make; the summary names the ones a run made from this list
/// (those of [`NEEDS_COMPUTE`] only where OpenGL 4.3 runs).
pub const CHECKS: &[Check] = &[
    Check {
        id: "self-collision vs brute force",
        says: "every self-collision frame's pairs from the GPU against brute force on the CPU \
               with paper 1's exact triangle predicate",
    },
    Check {
        id: "pairwise vs brute force",
        says: "the pair quad's pairs against the same brute force, by triangle count and on two \
               models, and against streaming AABBs on the two models",
    },
    Check {
        id: "pairwise compute vs classic",
        says: "the compute dispatch's pairs against the pair quad's and brute force's",
    },
    Check {
        id: "distance field vs f64",
        says: "the distance field of the slices (and of the compute pass) against the same \
               point-triangle distance in f64 on the CPU, which checks the GPU, not the method",
    },
    Check {
        id: "distance field vs parry3d",
        says: "the slices' distance field against parry3d's closest-point query on the mesh \
               (an independent library)",
    },
    Check {
        id: "distance meshes vs exact field",
        says: "the distance field by Hoff's distance meshes against the exact field (brute \
               force in f64), every voxel within the meshes' stated bound (the tessellation \
               error asked, plus the rasterizer's coverage error)",
    },
    Check {
        id: "voronoi vs brute force",
        says: "the 2D Voronoi distances, exact and by Hoff's distance meshes, against brute \
               force per pixel in f64",
    },
    Check {
        id: "swept volume vs closed form",
        says: "the swept volumes of three motions against their volumes in closed form",
    },
    Check {
        id: "penetration vs exact depth",
        says: "the penetration depth's upper bound and refined depth against the exact depth \
               (a closed form, or the nearest face of one convex Minkowski sum)",
    },
    Check {
        id: "avatar vs sampled parry3d",
        says: "the avatar's time of contact against the first contact found by bisection on \
               parry3d's distances",
    },
];

/// The checks that need OpenGL 4.3 (compute).
pub const NEEDS_COMPUTE: &[&str] = &["pairwise compute vs classic"];

/// The checks a run on a context with or without compute claims.
pub fn listed_checks(compute: bool) -> Vec<Check> {
    CHECKS
        .iter()
        .filter(|c| compute || !NEEDS_COMPUTE.contains(&c.id))
        .copied()
        .collect()
}

/// Every fidelity row of the section.
pub fn fidelity_rows() -> Vec<Fidelity> {
    fidelity::rows()
}

/// The paths every run can take.
pub const ALL_PATHS: &[&str] = &[
    paths::SELF_COLLISION,
    paths::PAIRWISE,
    paths::PAIRWISE_COMPUTE,
    paths::FIELD_SLICES,
    paths::FIELD_COMPUTE,
    paths::FIELD_MESHES,
    paths::FIELD_PARRY3D,
    paths::VORONOI_EXACT,
    paths::VORONOI_MESH,
    paths::SWEPT_VOLUME,
    paths::PENETRATION,
    paths::AVATAR_CCD,
    paths::AVATAR_SCENE,
    paths::AVATAR_PUBLISHED,
];

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
    /// Whether OpenGL 4.3 (compute) ran, so that its checks are claimed.
    pub compute: bool,
    pub blocks: Vec<Block>,
}

/// The lecture-1 section.
pub struct Lecture1;

impl Paper for Lecture1 {
    const ID: &'static str = "lecture1";
    const CLAIMS: &'static [super::ClaimDef] = &[pairwise::PAIRWISE];
    const TITLE: &'static str = "Lecture 1 (Kim): self-collision, pairwise triangle tests, \
                                 distance fields and Voronoi diagrams, swept volumes, \
                                 penetration depth and avatar CCD on the GPU, beyond paper 1's \
                                 streaming AABBs";
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
        crate::timing::mark("lecture1: start");
        let blocks = BLOCKS
            .iter()
            .map(|(id, measure)| {
                let mut block =
                    measure(&setting).map_err(|e| e.context(format!("lecture 1, block {id}")))?;
                block.id = id.to_string();
                crate::timing::mark(&format!("lecture1: {id}"));
                Ok(block)
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        Ok(Lecture1Results {
            renderer: setting.renderer,
            software: setting.software,
            quick: opts.quick,
            runs: setting.runs.in_words(),
            compute: opts
                .gl
                .require_compute("lecture 1's compute checks")
                .is_ok(),
            blocks,
        })
    }

    fn section(_: &BenchOptions, results: &Lecture1Results) -> anyhow::Result<Section> {
        let mut section = Section {
            summary: summary(results),
            fidelity: fidelity::rows(),
            checks_listed: checks::ids(&listed_checks(results.compute)),
            ..Section::default()
        };
        for block in &results.blocks {
            section.tables.extend(block.tables.iter().cloned());
            section.figures.extend(block.figures.iter().cloned());
            section.claims.extend(block.claims.iter().cloned());
            section.fidelity.extend(block.fidelity.iter().cloned());
            section
                .checks_made
                .extend(block.checks_made.iter().map(|c| c.to_string()));
            section
                .paths
                .extend(block.paths.iter().map(|p| p.to_string()));
        }
        section.tables.push(super::not_built::table(
            "the sources of lecture 1 name",
            super::not_built::LECTURE1,
        ));
        Ok(section)
    }
}

/// The section's summary: what runs, the checks made (from [`CHECKS`]), each block's result.
pub fn summary(r: &Lecture1Results) -> String {
    let mut text = format!(
        "Lecture 1 applies rasterization, occlusion queries and texture lookups to proximity \
         problems; paper 1's streaming AABBs are their own section. Only the abstracts and \
         introductions of the lecture's other sources are public, so what runs here are \
         reconstructions (see the fidelity table, and the 'not built' table for what the \
         sources name that is not done): self-collision is paper 1's pipeline with one model \
         against itself, the pairwise tests with triangles in textures follow what paper 1 \
         says of Choi, Kim & Kim 2006 (their layout, pass and test are ours), and distance \
         fields, Voronoi diagrams, swept volumes, penetration depth and avatar CCD follow \
         their abstracts, on {}. {}",
        r.renderer,
        checks::sentence(&listed_checks(r.compute))
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
