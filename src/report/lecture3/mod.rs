//! The lecture-3 section (the tutorial's third lecture, beside paper 3): the image pyramid,
//! pyramidal displacement mapping with its minification prefilter, an octree ray cast, the
//! light hierarchy's quadtree search with its uses (indirect light, subsurface scattering,
//! environment light), and the lecture's texture and debugging techniques, each GPU path
//! beside its CPU reference (`src/lecture3/`). The sources' texts are not available; the
//! fidelity table says what is reconstructed and the "not built" table what is not done.
//!
//! The summary names the checks from one list ([`CHECKS`]); [`checks_made`] reads from the
//! results which of them the run made, and [`paths_taken`] which paths it took, and
//! [`crate::report::run_section`] fails the section when they disagree with the list or a
//! path has no fidelity row.

mod bench;
mod claims;
mod depth_mask_table;
mod displacement_artifacts;
mod displacement_speed;
mod fidelity;
mod function_table;
mod histogram_table;
pub mod images;
mod light;
pub mod light_uses;
mod light_uses_table;
mod octree;
mod octree_table;
mod prefilter;
mod prefilter_table;
mod pyramid_table;
mod random_table;
mod results;
mod scene;
mod timed;

pub use bench::*;
pub use octree::OctreeRow;
pub use prefilter::{prefilter_quality, PrefilterQuality, PrefilterRow};
pub use results::*;
pub use scene::*;
pub use timed::*;

use super::checks::{self, Check};
use super::{BenchOptions, Fidelity, Paper, Section};
use std::path::PathBuf;

/// The lecture-3 section.
pub struct Lecture3;

/// What `lecture3-bench` can change.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct Lecture3Options {
    /// A greyscale PNG height map for the displacement-mapping views [default: the shipped
    /// assets/lecture3/height.png].
    #[arg(long)]
    pub height: Option<PathBuf>,
}

impl Paper for Lecture3 {
    const ID: &'static str = "lecture3";
    const CLAIMS: &'static [super::ClaimDef] = claims::CLAIMS;
    const TITLE: &'static str = "Lecture 3 (Oh): image pyramids, pyramidal displacement mapping, \
                                 octrees, quadtree search of a light hierarchy, and texture \
                                 tricks";
    type Options = Lecture3Options;
    type Results = Lecture3Results;

    fn measure(opts: &BenchOptions, options: &Lecture3Options) -> anyhow::Result<Lecture3Results> {
        bench::measure(opts, options.height.as_deref())
    }

    fn section(opts: &BenchOptions, results: &Lecture3Results) -> anyhow::Result<Section> {
        let mut figures = vec![pyramid_table::figure()];
        figures.extend(displacement_artifacts::figures(opts, results)?);
        figures.push(displacement_speed::figure());
        figures.extend(light::figures(opts, results)?);
        figures.push(light_uses::figure());
        figures.extend(random_table::figures(opts, results)?);
        figures.extend(depth_mask_table::figures(opts, results)?);
        Ok(Section {
            summary: summary(results),
            tables: vec![
                pyramid_table::table(results),
                displacement_artifacts::table(results),
                displacement_speed::table(results),
                prefilter_table::table(results),
                octree_table::table(results),
                light::table(results),
                light_uses_table::clustering_table(results),
                light_uses_table::uses_table(results),
                function_table::error_table(results),
                function_table::speed_table(results),
                random_table::table(results),
                depth_mask_table::table(results),
                histogram_table::table(results),
            ],
            claims: claims::claims(results),
            figures,
            fidelity: fidelity::rows(),
            checks_listed: checks::ids(CHECKS),
            checks_made: checks_made(results).into_iter().map(String::from).collect(),
            paths: paths_taken(results).into_iter().map(String::from).collect(),
            ..Section::default()
        })
        .map(|mut s| {
            s.tables.push(super::not_built::table(
                "the sources of lecture 3 name",
                super::not_built::LECTURE3,
            ));
            s
        })
    }
}

/// Every check of the section, in the summary's order.
pub const CHECKS: &[Check] = &[
    Check {
        id: "pyramid vs CPU",
        says: "the max, min and mean image pyramids against the CPU's (max and min bit for bit)",
    },
    Check {
        id: "displacement vs exact tracer",
        says: "pyramidal displacement mapping and relief mapping against an exact f64 ray \
               tracer of the same bilinear height field",
    },
    Check {
        id: "prefilter vs CPU rule",
        says: "the minification prefilter against the CPU reference of the same rule",
    },
    Check {
        id: "octree vs CPU",
        says: "the octree's levels and its ray cast (and the flat voxel walk) against the CPU",
    },
    Check {
        id: "light tree vs brute force",
        says: "the light hierarchy's quadtree search against the brute-force sum of every \
               light, for indirect light, subsurface scattering and environment light",
    },
    Check {
        id: "function vs computed",
        says: "a function in a 1D texture against computing it",
    },
    Check {
        id: "random vs CPU",
        says: "the random numbers generated into a texture against the CPU generator, bit \
               for bit",
    },
    Check {
        id: "depth mask vs CPU",
        says: "the if removed with the depth buffer: its picture against the CPU's and its \
               shader runs counted",
    },
    Check {
        id: "histogram vs CPU",
        says: "the histogram by additive blending against the CPU's",
    },
];

/// The checks of [`CHECKS`] whose comparisons are in `r`.
pub fn checks_made(r: &Lecture3Results) -> Vec<&'static str> {
    let mut made = Vec::new();
    let mut add = |cond: bool, id: &'static str| {
        if cond {
            made.push(id);
        }
    };
    add(!r.pyramid.is_empty(), "pyramid vs CPU");
    add(
        !r.displacement.artifacts.is_empty(),
        "displacement vs exact tracer",
    );
    add(!r.prefilter.is_empty(), "prefilter vs CPU rule");
    add(!r.octree.is_empty(), "octree vs CPU");
    add(
        !r.light.rows.is_empty()
            && !r.light_uses.subsurface.rows.is_empty()
            && !r.light_uses.environment.rows.is_empty(),
        "light tree vs brute force",
    );
    add(!r.function.errors.is_empty(), "function vs computed");
    add(!r.random.values.is_empty(), "random vs CPU");
    add(!r.depth_mask.rows.is_empty(), "depth mask vs CPU");
    add(!r.histogram.is_empty(), "histogram vs CPU");
    made
}

/// The paths every run of the section takes (each has a fidelity row).
pub mod paths {
    pub const PYRAMID: &str = "image pyramid by level passes, read from an atlas";
    pub const PYRAMID_TRACE: &str = "displacement: top-down traversal of the max pyramid";
    pub const RELIEF: &str = "displacement: relief mapping's linear + binary search";
    pub const PREFILTER: &str = "displacement: minification prefilter";
    pub const OCTREE: &str = "octree: built by reduction passes, ray cast per pixel";
    pub const LIGHT_TREE: &str = "light hierarchy: VPL pyramid, quadtree gather";
    pub const SUBSURFACE: &str = "light hierarchy: subsurface scattering";
    pub const ENVIRONMENT: &str = "light hierarchy: environment light";
    pub const FUNCTION: &str = "function in a 1D texture";
    pub const RANDOM: &str = "random numbers in an integer texture";
    pub const DEPTH_MASK: &str = "if removed by the depth test";
    pub const HISTOGRAM: &str = "histogram by additive blending";
}

/// The paths the run in `r` took.
pub fn paths_taken(r: &Lecture3Results) -> Vec<&'static str> {
    let mut taken = Vec::new();
    let mut add = |cond: bool, path: &'static str| {
        if cond {
            taken.push(path);
        }
    };
    add(!r.pyramid.is_empty(), paths::PYRAMID);
    add(!r.displacement.artifacts.is_empty(), paths::PYRAMID_TRACE);
    add(!r.displacement.artifacts.is_empty(), paths::RELIEF);
    add(!r.prefilter.is_empty(), paths::PREFILTER);
    add(!r.octree.is_empty(), paths::OCTREE);
    add(!r.light.rows.is_empty(), paths::LIGHT_TREE);
    add(!r.light_uses.subsurface.rows.is_empty(), paths::SUBSURFACE);
    add(
        !r.light_uses.environment.rows.is_empty(),
        paths::ENVIRONMENT,
    );
    add(!r.function.errors.is_empty(), paths::FUNCTION);
    add(!r.random.values.is_empty(), paths::RANDOM);
    add(!r.depth_mask.rows.is_empty(), paths::DEPTH_MASK);
    add(!r.histogram.is_empty(), paths::HISTOGRAM);
    taken
}

/// Every path a run can take.
pub const ALL_PATHS: &[&str] = &[
    paths::PYRAMID,
    paths::PYRAMID_TRACE,
    paths::RELIEF,
    paths::PREFILTER,
    paths::OCTREE,
    paths::LIGHT_TREE,
    paths::SUBSURFACE,
    paths::ENVIRONMENT,
    paths::FUNCTION,
    paths::RANDOM,
    paths::DEPTH_MASK,
    paths::HISTOGRAM,
];

/// Every fidelity row of the section.
pub fn fidelity_rows() -> Vec<Fidelity> {
    fidelity::rows()
}

/// The section's summary: the techniques, the checks made (from [`CHECKS`]), how timed.
pub fn summary(r: &Lecture3Results) -> String {
    format!(
        "The techniques of lecture 3 beyond paper 3's network, each run on the GPU: (1) max, \
         min and mean image pyramids, (2) pyramidal displacement mapping (Oh, Ki & Lee, VRST \
         2006) with a minification prefilter, beside relief mapping's linear + binary search, \
         (3) an octree of a point set built by reduction passes and ray cast per pixel, (4) a \
         light hierarchy of virtual point lights searched as a quadtree in the fragment shader \
         (Ki & Oh 2008), for indirect light, subsurface scattering and environment light, (5) a \
         function in a 1D texture, (6) random numbers generated into a texture, (7) an if \
         removed with the depth buffer, (8) a histogram by additive blending. {} The sources' \
         full texts are not available: the algorithms are reconstructed from their abstracts \
         and the standard formulations (see the fidelity table). Times are medians ({} per timing; results.json \
         gives each timing's runs, min and max) on {}, GPU times by {}{}.{}",
        checks::sentence(CHECKS),
        r.runs,
        r.renderer,
        r.gpu_timing,
        if r.software {
            ", a software rasterizer: its 'GPU' passes run on the same CPU cores as the CPU \
             references, so GPU/CPU ratios are not those of a GPU"
        } else {
            ""
        },
        if r.quick {
            " Quick mode: smaller maps, images and counts."
        } else {
            ""
        }
    )
}
