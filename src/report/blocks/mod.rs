//! The shared building blocks, measured: ping-pong reduction against reading the whole
//! buffer back and summing on the CPU (the trade-off behind paper 4 section 3.3 and paper 1
//! section 5.3), on the renderer at hand.

mod bench;
mod claims;
mod fidelity;
mod reduction_plot;
mod reduction_table;

pub use bench::{BlocksResults, ReductionRun};

use super::{BenchOptions, NoOptions, Paper, Section};

/// The building-blocks section.
pub struct Blocks;

impl Paper for Blocks {
    const ID: &'static str = "blocks";
    const CLAIMS: &'static [super::ClaimDef] = claims::CLAIMS;
    const TITLE: &'static str = "Shared building blocks: ping-pong reduction";
    type Options = NoOptions;
    type Results = BlocksResults;

    fn measure(opts: &BenchOptions, _: &NoOptions) -> anyhow::Result<BlocksResults> {
        bench::measure(opts)
    }

    fn section(opts: &BenchOptions, results: &BlocksResults) -> anyhow::Result<Section> {
        let renderer = opts.gl.info().renderer_line();
        Ok(Section {
            summary: format!(
                "Reducing an n x n buffer to one value on the GPU in log2 n passes, against \
                 reading every texel back and summing on the CPU. On a discrete GPU the readback \
                 crosses a bus; on a software renderer it is a memory copy, so the time ratio \
                 says which side of that trade-off this machine is on. Renderer: {renderer}."
            ),
            tables: vec![
                reduction_table::table(opts, results),
                super::not_built::table(
                    "the tutorial's lecture 5 (NVIDIA's G80 and CUDA) names",
                    super::not_built::LECTURE5,
                ),
            ],
            claims: claims::claims(results),
            figures: vec![reduction_plot::figure(opts, results)?],
            fidelity: fidelity::rows(),
            ..Section::default()
        })
    }
}
