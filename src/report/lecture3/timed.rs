//! How the section times its work, for every measurement of it and the `lecture3` commands:
//! how often a timing repeats, GPU passes by timer query (or to glFinish on a software
//! rasterizer, and why), and CPU references by the wall clock.

use crate::gl::{Context, TimerQuery};
use crate::report::BenchOptions;
use crate::timing::{Runs, Spread};
use std::time::Instant;

/// How many times the section repeats one timing: `--runs` when given, else exactly 3
/// under `--quick`, else the report's policy ([`Runs::PAPER`]).
pub fn runs(opts: &BenchOptions) -> Runs {
    opts.runs(3)
}

/// How [`gpu_ms`] times GPU work on this renderer.
pub fn gpu_timing(ctx: &Context) -> &'static str {
    if ctx.info().is_software() {
        "wall clock to glFinish"
    } else {
        "GL timer query"
    }
}

/// GPU time of `work` (its runs as [`Runs`] says: median and range), after one warm-up run:
/// a GL timer query on a GPU; on a software rasterizer the wall clock from glFinish to
/// glFinish, because llvmpipe's TIME_ELAPSED queries miss most of the rasterisation, which
/// runs in its worker threads when the scene is flushed (measured here: 5 ms by the query for
/// a pass that took 22 ms to finish).
pub fn gpu_ms(
    ctx: &Context,
    runs: Runs,
    mut work: impl FnMut() -> anyhow::Result<()>,
) -> anyhow::Result<Spread> {
    work()?;
    gpu_ms_warm(ctx, runs, work)
}

/// [`gpu_ms`] without its warm-up run, for work whose programs have just run in the same
/// state (their shader variants compiled, their targets allocated): a section's untimed run
/// of the same pass (the one whose result it checks) or the previous point of a sweep.
pub fn gpu_ms_warm(
    ctx: &Context,
    runs: Runs,
    mut work: impl FnMut() -> anyhow::Result<()>,
) -> anyhow::Result<Spread> {
    ctx.finish_all();
    let software = ctx.info().is_software();
    let query = TimerQuery::new(ctx)?;
    let times = runs.run(|_| -> anyhow::Result<f64> {
        if software {
            ctx.finish_all();
            let start = Instant::now();
            work()?;
            ctx.finish_all();
            Ok(start.elapsed().as_secs_f64() * 1e3)
        } else {
            query.begin();
            let done = work();
            query.end();
            done?;
            Ok(query.milliseconds()?)
        }
    })?;
    Ok(Spread::of(&times))
}

/// Wall clock of one run of `work`, for CPU references of seconds timed once.
pub fn wall_once_ms<T>(work: impl FnOnce() -> T) -> f64 {
    let start = Instant::now();
    std::hint::black_box(work());
    start.elapsed().as_secs_f64() * 1e3
}
