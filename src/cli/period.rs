//! `--period`: run a paper's command under the limits of the GPU the paper ran on
//! (`gl::period`, the table `assets/period_gpus.toml`).

use classic_gpgpu::gl::{period, Context};

/// The `--period` flag of a paper's commands.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct PeriodArg {
    /// Run under the limits of the paper's own GPU (the GeForce 7800 GTX for papers 1, 2
    /// and 4; assets/period_gpus.toml): a step that chip could not run is an error naming
    /// the limit, and where the paper says how the period did a step, that way is taken.
    #[arg(long)]
    pub period: bool,
}

impl PeriodArg {
    /// Put `ctx` under paper `paper`'s GPU when `--period` is given, and say so on stderr.
    pub fn apply(&self, ctx: &Context, paper: u8) {
        if self.period {
            let gpu = period::for_paper(paper);
            ctx.set_period(Some(gpu));
            eprintln!(
                "period: under the limits of the {} ({}), paper {paper}'s GPU",
                gpu.name, gpu.chip
            );
        }
    }
}
