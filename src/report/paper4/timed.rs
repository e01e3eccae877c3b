//! How the section repeats its timings and when it starts them, for the bench and the
//! buoyancy then-and-now block alike.

/// Timed runs per measurement under `--quick` (the median is kept); at the papers' sizes
/// the report's policy ([`crate::report::BenchOptions::runs`]).
pub const QUICK_RUNS: usize = 3;

/// Steps from the drop before the buoyancy scene is timed (1 s, past the first plunge).
pub const SETTLE_STEPS: usize = 60;
