//! `learn <id> --bench`: the lessons where speed is part of the lesson, timed by the report's
//! policy ([`crate::timing`]: runs, median, spread, load) and printed as plain tables naming
//! the renderer and the load. Lesson 1 sweeps saxpy over sizes against the CPU (Göddeke's
//! benchmark mode); lessons 3 and 10 time the reduction ladder after Harris
//! ([`super::ladder`]); lesson 8 times the whole, the PBO and the compacted readback. Every
//! path is checked against the CPU before it is timed, and timed warm (one untimed run, then
//! the runs' median and range). No test asserts a time.

use super::ladder::{self, LadderBench};
pub use super::quad_is_loop::SaxpyBench;
pub use super::readback_and_upload::ReadbackBench;
use crate::gl::Context;
use crate::timing::Runs;
use serde::Serialize;

/// The lessons with a bench, and what it times.
pub const WITH_BENCH: [(&str, &str); 4] = [
    (
        "quad-is-loop",
        "saxpy over sizes against the CPU loop (--size: elements)",
    ),
    (
        "reduction",
        "the reduction ladder after Harris (--size: values)",
    ),
    (
        "readback-and-upload",
        "whole, PBO and compacted readback (--size: the array's side)",
    ),
    (
        "compute-reduction",
        "the reduction ladder after Harris (--size: values)",
    ),
];

/// What a bench measured.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "bench", rename_all = "snake_case")]
pub enum Bench {
    Saxpy(SaxpyBench),
    Ladder(LadderBench),
    Readback(ReadbackBench),
}

/// Whether lesson `id` has a bench; else the error that lists those that do.
pub fn has_bench(id: &str) -> anyhow::Result<()> {
    if WITH_BENCH.iter().any(|(l, _)| *l == id) {
        return Ok(());
    }
    let list: Vec<String> = WITH_BENCH
        .iter()
        .map(|(l, what)| format!("{l} ({what})"))
        .collect();
    anyhow::bail!(
        "lesson {id} has no --bench (speed is not what it teaches); the lessons with one are: {}",
        list.join("; ")
    )
}

/// Run lesson `id`'s bench: its default sizes, or `size` alone.
pub fn run(ctx: &Context, id: &str, size: Option<u32>, runs: Runs) -> anyhow::Result<Bench> {
    has_bench(id)?;
    Ok(match id {
        "quad-is-loop" => {
            let sizes = size.map_or(super::quad_is_loop::BENCH_SIZES.to_vec(), |n| vec![n]);
            Bench::Saxpy(super::quad_is_loop::bench(ctx, &sizes, runs)?)
        }
        "readback-and-upload" => {
            let sides = size.map_or(super::readback_and_upload::BENCH_SIDES.to_vec(), |n| {
                vec![n]
            });
            Bench::Readback(super::readback_and_upload::bench(ctx, &sides, runs)?)
        }
        _ => {
            if let Some(n) = size {
                anyhow::ensure!(
                    (1..=ladder::MAX_SIZE).contains(&n),
                    "--size {n}: the ladder sums 1 to {} values (3 x 2^22 < 2^24 keeps every \
                     partial sum exact in fp32)",
                    ladder::MAX_SIZE
                );
            }
            let sizes = size.map_or(ladder::SIZES.to_vec(), |n| vec![n]);
            Bench::Ladder(ladder::bench(ctx, &sizes, runs)?)
        }
    })
}

impl Bench {
    /// The bench as plain-text tables.
    pub fn table(&self) -> String {
        match self {
            Bench::Saxpy(b) => b.table(),
            Bench::Ladder(b) => b.table(),
            Bench::Readback(b) => b.table(),
        }
    }
}
