//! The lecture-3 section (the tutorial's third lecture, beside paper 3): the image pyramid,
//! pyramidal displacement mapping, the light hierarchy's quadtree search, and the lecture's
//! texture and debugging techniques, each GPU path beside its CPU reference
//! (`src/lecture3/`). The sources' texts are not available; the fidelity table says what is
//! reconstructed.

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
mod octree;
mod prefilter;
mod pyramid_table;
mod random_table;
mod results;

pub use bench::*;
pub use octree::OctreeRow;
pub use prefilter::{prefilter_quality, PrefilterQuality, PrefilterRow};
pub use results::*;

use super::{BenchOptions, Paper, Section};
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
    const TITLE: &'static str = "Lecture 3 (Oh): image pyramids, pyramidal displacement mapping, \
                                 quadtree search of a light hierarchy, and texture tricks";
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
                prefilter::table(results),
                octree::table(results),
                light::table(results),
                light_uses::clustering_table(results),
                light_uses::uses_table(results),
                function_table::error_table(results),
                function_table::speed_table(results),
                random_table::table(results),
                depth_mask_table::table(results),
                histogram_table::table(results),
            ],
            claims: claims::claims(results),
            figures,
            fidelity: fidelity::rows(),
            ..Section::default()
        })
    }
}

fn summary(r: &Lecture3Results) -> String {
    format!(
        "The seven techniques of lecture 3 beyond paper 3's network, each run on the GPU and \
         checked against its CPU reference in the same run: (1) max, min and mean image pyramids, (2) \
         pyramidal displacement mapping (Oh, Ki & Lee, VRST 2006) against an exact f64 ray \
         tracer of the same bilinear height field and against relief mapping's linear + binary \
         search, (3) a light hierarchy of virtual point lights searched as a quadtree in the \
         fragment shader (Ki & Oh 2008) against the brute-force sum, (4) a function in a 1D \
         texture, (5) random numbers generated into a texture, (6) an if removed with the depth \
         buffer, (7) a histogram by additive blending. The sources' full texts are not \
         available: the algorithms are reconstructed from their abstracts and the standard \
         formulations (see the fidelity table). Times are medians ({} per timing; results.json \
         gives each timing's runs, min and max) on {}, GPU times by {}{}.{}",
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
