//! `--profile`: the per-pass table of `gl::profile` after a paper command.

use classic_gpgpu::gl::{profile, Context};

/// The `--profile` flag of the paper commands.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct ProfileArg {
    /// After the run, print a per-pass table to stderr: GPU time of each pass (timestamp
    /// queries, read after the run), its wall time, and the time spent waiting for the GPU
    /// (glFinish, readbacks, query results).
    #[arg(long)]
    pub profile: bool,
}

impl ProfileArg {
    /// Start profiling on `ctx` if `--profile` was given.
    pub fn start(&self, ctx: &Context) {
        start(ctx, self.profile);
    }
}

/// Start profiling on `ctx` if `on`.
pub fn start(ctx: &Context, on: bool) {
    if on {
        profile::start(ctx);
    }
}

/// Print the table of the profile running on `ctx`, if any (stderr: stdout keeps the results).
pub fn print(ctx: &Context) {
    if let Some(table) = profile::finish(ctx) {
        eprintln!("{table}");
    }
}
