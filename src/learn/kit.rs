//! What the lessons share beside [`super::LessonRun`]: a texture read back for its pass's
//! picture, the exercise asked for, the compute counterpart's absence, test data the CPU
//! makes, and how a lesson times its paths: warm (one untimed run first, then the median of
//! several), one clock for a whole table ([`table_clock`]), and the steps of one path in the
//! same runs ([`time_steps`]), so that a part is never timed longer than its whole.

use super::{LessonInfo, LessonOptions, PassBuffer};
use crate::gl::{Context, Texture, TextureFormat, TimerQuery};
use crate::timing::{Runs, Spread};
use anyhow::bail;
use serde::Serialize;
use std::time::Instant;

/// What `texture` holds, read back for its pass's picture: floats as they are, a byte format
/// as 0..1, a packed depth-stencil texture as its depth in 0..1, integers as their values.
pub fn buffer(texture: &Texture) -> anyhow::Result<PassBuffer> {
    let (width, height) = (texture.width(), texture.height());
    let channels = texture.format().components();
    Ok(match texture.format() {
        TextureFormat::R8 | TextureFormat::Rgba8 => {
            PassBuffer::bytes(width, height, channels, &texture.download_u8()?)
        }
        TextureFormat::Depth24Stencil8 => {
            let depth = texture.download_u32()?;
            let depth = depth.into_iter().map(|v| (v >> 8) as f32 / 16_777_215.0);
            PassBuffer::floats(width, height, 1, depth.collect())
        }
        TextureFormat::Rgba32Ui => {
            let values = texture.download_u32()?.into_iter().map(|v| v as f32);
            PassBuffer::floats(width, height, channels, values.collect())
        }
        _ => PassBuffer::floats(width, height, channels, texture.download_f32()?),
    })
}

/// The exercise `opts` asks for, checked to exist before anything runs.
pub fn exercise_asked(info: &LessonInfo, opts: &LessonOptions) -> anyhow::Result<()> {
    if let Some(n) = opts.exercise {
        if !info.exercises.iter().any(|e| e.number == n) {
            let numbers: Vec<String> = info
                .exercises
                .iter()
                .map(|e| e.number.to_string())
                .collect();
            bail!(
                "lesson {} has no exercise {n}; its exercises are: {}",
                info.id,
                numbers.join(", ")
            );
        }
    }
    Ok(())
}

/// Why the compute counterpart did not run on `ctx`, or `None` when it can.
pub fn compute_missing(ctx: &Context, what: &str) -> Option<String> {
    ctx.require_compute(what)
        .err()
        .map(|e| format!("not run: {e}"))
}

/// `n` pseudo-random values in [0, 1) from `seed` (a 32-bit xorshift): test data the CPU
/// makes, the same on every machine.
pub fn values(n: usize, seed: u32) -> Vec<f32> {
    let mut state = seed.max(1);
    (0..n)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state >> 8) as f32 / (1u32 << 24) as f32
        })
        .collect()
}

/// The largest absolute difference of two equally long arrays (infinite if the lengths
/// differ or a value is not finite).
pub fn max_abs_diff(a: &[f32], b: &[f32]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    a.iter().zip(b).fold(0.0, |m: f64, (&x, &y)| {
        let d = (x as f64 - y as f64).abs();
        if d.is_finite() {
            m.max(d)
        } else {
            f64::INFINITY
        }
    })
}

/// How many of the bytes of two float arrays differ (all of them if the lengths differ).
pub fn bytes_differing(a: &[f32], b: &[f32]) -> f64 {
    let (a, b): (&[u8], &[u8]) = (bytemuck::cast_slice(a), bytemuck::cast_slice(b));
    if a.len() != b.len() {
        return a.len().max(b.len()) as f64;
    }
    a.iter().zip(b).filter(|(x, y)| x != y).count() as f64
}

/// How the times of one table were taken: one clock for every row, so that rows compare.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Clock {
    /// A GL timer query (TIME_ELAPSED) around the passes: the GPU's own time, fragment and
    /// compute passes alike, without the CPU's share of a glFinish.
    TimerQuery,
    /// Wall clock between two glFinish calls: what a software renderer needs, whose timer
    /// query does not see the work its worker threads do.
    FinishedWall,
}

impl Clock {
    pub fn in_words(&self) -> &'static str {
        match self {
            Clock::TimerQuery => "timer query",
            Clock::FinishedWall => "glFinish wall clock",
        }
    }
}

/// One piece of GPU work timed by both clocks in the same runs: a timer query inside, the
/// wall clock between two glFinish calls outside.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct TwoClocks {
    pub query: Spread,
    pub wall: Spread,
}

impl TwoClocks {
    /// The times on `clock`.
    pub fn on(&self, clock: Clock) -> Spread {
        match clock {
            Clock::TimerQuery => self.query,
            Clock::FinishedWall => self.wall,
        }
    }
}

/// A timer query reading under this share of the wall clock around the same work has not
/// seen the work (llvmpipe answers about zero around a compute dispatch)...
const QUERY_SEES_WORK: f64 = 0.1;
/// ...where the wall clock reads more than this (ms): below it, a glFinish's own latency (tens
/// of microseconds on a GPU) can be most of the wall clock around a small pass.
const QUERY_JUDGED_ABOVE_MS: f64 = 1.0;

/// Milliseconds of one run of `work` on both clocks: the timer query's and the wall clock's
/// between two glFinish calls.
fn once_on_both(
    ctx: &Context,
    work: &mut impl FnMut() -> anyhow::Result<()>,
) -> anyhow::Result<(f64, f64)> {
    let query = TimerQuery::new(ctx)?;
    ctx.finish_all();
    let start = Instant::now();
    query.begin();
    let done = work();
    query.end();
    ctx.finish_all();
    let wall = start.elapsed().as_secs_f64() * 1e3;
    done?;
    Ok((query.milliseconds()?, wall))
}

/// Time `work` (GPU passes, nothing read back) by both clocks: one warm-up run first (the
/// driver compiles and allocates on first use), then the runs `runs` says.
pub fn time_two_clocks(
    ctx: &Context,
    runs: Runs,
    mut work: impl FnMut() -> anyhow::Result<()>,
) -> anyhow::Result<TwoClocks> {
    work()?;
    let pairs = runs.run(|_| once_on_both(ctx, &mut work))?;
    let (queried, wall): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
    Ok(TwoClocks {
        query: Spread::of(&queried),
        wall: Spread::of(&wall),
    })
}

/// Time `a` and `b` on `clock`, one run of each in turn (after a warm-up run of both), so that
/// whatever else the machine does falls on both alike: their times, `a`'s first.
pub fn time_alternating(
    ctx: &Context,
    clock: Clock,
    runs: Runs,
    mut a: impl FnMut() -> anyhow::Result<()>,
    mut b: impl FnMut() -> anyhow::Result<()>,
) -> anyhow::Result<(Spread, Spread)> {
    a()?;
    b()?;
    let on = |(query, wall): (f64, f64)| match clock {
        Clock::TimerQuery => query,
        Clock::FinishedWall => wall,
    };
    let pairs = runs.run(|_| -> anyhow::Result<(f64, f64)> {
        let first = on(once_on_both(ctx, &mut a)?);
        Ok((first, on(once_on_both(ctx, &mut b)?)))
    })?;
    let (first, second): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
    Ok((Spread::of(&first), Spread::of(&second)))
}

/// The one clock of a table and why it was chosen.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TableClock {
    pub clock: Clock,
    pub why: String,
}

/// The clock for a table whose rows were timed by both clocks (`rows`: name and times). A
/// software renderer gets the glFinish wall clock for every row: its timer query misses what
/// its worker threads do. A GPU gets the timer query for every row, unless the query read
/// under a tenth of a wall clock of over a millisecond around some row (it missed work): then
/// the wall clock, for every row too.
pub fn table_clock(ctx: &Context, rows: &[(String, TwoClocks)]) -> TableClock {
    let info = ctx.info();
    choose_clock(&info.renderer, info.is_software(), rows)
}

/// [`table_clock`] for a renderer named `renderer`, `software` or not.
fn choose_clock(renderer: &str, software: bool, rows: &[(String, TwoClocks)]) -> TableClock {
    let share = |t: &TwoClocks| t.query.median / t.wall.median;
    // The row where the query saw least of the work, among those whose wall clock is over
    // `above` ms: the evidence either way.
    let least = |above: f64| {
        rows.iter()
            .filter(|(_, t)| t.wall.median > above)
            .min_by(|a, b| share(&a.1).total_cmp(&share(&b.1)))
    };
    let words = |(name, t): &(String, TwoClocks)| {
        format!(
            " (around {name} the query read {:.3} ms against {:.3} ms of wall clock)",
            t.query.median, t.wall.median
        )
    };
    let missed = least(QUERY_JUDGED_ABOVE_MS).filter(|(_, t)| share(t) < QUERY_SEES_WORK);
    let evidence = missed.or(least(0.0)).map_or(String::new(), words);
    let query_sees_all = missed.is_none();
    if software {
        TableClock {
            clock: Clock::FinishedWall,
            why: format!(
                "{renderer} is a software renderer: its GL timer query (TIME_ELAPSED) misses \
                 the work its worker threads do{evidence}, so every row is timed by the wall \
                 clock between two glFinish calls"
            ),
        }
    } else if query_sees_all {
        TableClock {
            clock: Clock::TimerQuery,
            why: format!(
                "GL timer queries (TIME_ELAPSED) time fragment and compute passes alike on \
                 {renderer}, without the CPU's share of a glFinish; every row by timer query"
            ),
        }
    } else {
        TableClock {
            clock: Clock::FinishedWall,
            why: format!(
                "the GL timer query of {renderer} missed part of the work{evidence}, so every \
                 row is timed by the wall clock between two glFinish calls"
            ),
        }
    }
}

/// The steps of one path timed in the same runs: each step's times and the whole's. Each run's
/// whole is the sum of its steps, so no step, and no part made of steps ([`Steps::part`]), is
/// ever timed longer than the whole: not in any run, so not in the median, the minimum or the
/// maximum either (the k-th smallest of values each below its partner is below the k-th
/// smallest of the partners).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Steps {
    pub steps: Vec<Spread>,
    pub whole: Spread,
    /// Each run's step times, kept for [`Steps::part`].
    #[serde(skip)]
    samples: Vec<Vec<f64>>,
}

impl Steps {
    /// From each run's step times (milliseconds, each run the same number of steps).
    pub fn of(runs: &[Vec<f64>]) -> Steps {
        let count = runs.first().map_or(0, Vec::len);
        let steps = (0..count)
            .map(|k| Spread::of(&runs.iter().map(|r| r[k]).collect::<Vec<f64>>()))
            .collect();
        let wholes: Vec<f64> = runs.iter().map(|r| r.iter().sum()).collect();
        Steps {
            steps,
            whole: Spread::of(&wholes),
            samples: runs.to_vec(),
        }
    }

    /// The times of `steps` together: in each run, the sum of those steps.
    pub fn part(&self, steps: &[usize]) -> Spread {
        let sums: Vec<f64> = self
            .samples
            .iter()
            .map(|r| steps.iter().filter_map(|&k| r.get(k)).sum())
            .collect();
        Spread::of(&sums)
    }
}

/// When the steps of a timed path wait for the GPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wait {
    /// glFinish after every step: each step's time is its work done.
    AfterEachStep,
    /// glFinish after the last step only: a step's time is how long its calls took to return
    /// (a queued call returns at once), and the last step's includes the wait for all of it.
    AtTheEnd,
}

/// Time `count` steps of one path (`step(k)` runs step k) by the wall clock, glFinish before the
/// first and after each: one warm-up run of every step first, then the runs `runs` says.
pub fn time_steps(
    ctx: &Context,
    runs: Runs,
    count: usize,
    step: impl FnMut(usize) -> anyhow::Result<()>,
) -> anyhow::Result<Steps> {
    time_steps_with(ctx, runs, count, Wait::AfterEachStep, step)
}

/// [`time_steps`], waiting for the GPU as `wait` says.
pub fn time_steps_with(
    ctx: &Context,
    runs: Runs,
    count: usize,
    wait: Wait,
    mut step: impl FnMut(usize) -> anyhow::Result<()>,
) -> anyhow::Result<Steps> {
    for k in 0..count {
        step(k)?;
    }
    let times = runs.run(|_| -> anyhow::Result<Vec<f64>> {
        ctx.finish_all();
        let mut times = Vec::with_capacity(count);
        for k in 0..count {
            let start = Instant::now();
            step(k)?;
            if wait == Wait::AfterEachStep || k + 1 == count {
                ctx.finish_all();
            }
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
        Ok(times)
    })?;
    Ok(Steps::of(&times))
}

/// Wall-clock milliseconds of `work` between two glFinish calls (a path that reads back: the
/// CPU's wait is part of it): one warm-up run first, then the runs `runs` says.
pub fn time_finished(
    ctx: &Context,
    runs: Runs,
    mut work: impl FnMut() -> anyhow::Result<()>,
) -> anyhow::Result<Spread> {
    Ok(time_steps(ctx, runs, 1, |_| work())?.whole)
}

/// Wall-clock milliseconds until `call` returns, the GPU idle before it (glFinish) but not
/// waited for after: what a queued call costs the CPU. One warm-up call first.
pub fn time_call(
    ctx: &Context,
    runs: Runs,
    mut call: impl FnMut() -> anyhow::Result<()>,
) -> anyhow::Result<Spread> {
    call()?;
    let times = runs.run(|_| -> anyhow::Result<f64> {
        ctx.finish_all();
        let start = Instant::now();
        call()?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        ctx.finish_all();
        Ok(ms)
    })?;
    Ok(Spread::of(&times))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clocks(query: f64, wall: f64) -> TwoClocks {
        let at = |ms: f64| Spread {
            runs: 3,
            median: ms,
            min: ms,
            max: ms,
        };
        TwoClocks {
            query: at(query),
            wall: at(wall),
        }
    }

    /// One clock per table: the wall clock on a software renderer, the timer query on a GPU
    /// unless it clearly missed work (under a tenth of a wall clock over 1 ms), whatever the
    /// glFinish latency around small passes.
    #[test]
    fn a_table_gets_one_clock_and_says_why() {
        let rows = |pairs: &[(f64, f64)]| -> Vec<(String, TwoClocks)> {
            pairs
                .iter()
                .enumerate()
                .map(|(k, &(q, w))| (format!("row {k}"), clocks(q, w)))
                .collect()
        };
        // llvmpipe: wall clock, the blindest row named, even where the query saw all.
        let c = choose_clock("llvmpipe", true, &rows(&[(0.0, 8.0), (0.9, 1.0)]));
        assert_eq!(c.clock, Clock::FinishedWall);
        assert!(
            c.why.contains("software renderer") && c.why.contains("around row 0"),
            "{}",
            c.why
        );
        // A GPU: tiny passes where glFinish's latency is most of the wall clock keep the query.
        let c = choose_clock("H200", false, &rows(&[(0.01, 0.06), (0.268, 0.31)]));
        assert_eq!(c.clock, Clock::TimerQuery, "{}", c.why);
        // A GPU whose query read nothing around 5 ms of work: the wall clock, for every row.
        let c = choose_clock("odd", false, &rows(&[(0.01, 0.06), (0.0, 5.0), (2.0, 2.1)]));
        assert_eq!(c.clock, Clock::FinishedWall);
        assert!(c.why.contains("around row 1"), "{}", c.why);
    }

    /// The property the steps' timing promises, by construction: whatever each run measured,
    /// no step's median, minimum or maximum exceeds the whole's.
    #[test]
    fn no_step_is_ever_timed_longer_than_its_whole() {
        // Runs where the pass alone was slow in one run and the transfers in another: timed
        // apart, the pass's median could come out above the whole's (0.422 > 0.395 ms).
        let shapes: [&[[f64; 3]]; 3] = [
            &[[0.1, 0.422, 0.1], [0.05, 0.2, 0.05], [0.3, 0.1, 0.3]],
            &[[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
            &[
                [2.0, 0.5, 0.1],
                [0.1, 0.9, 0.1],
                [0.1, 0.4, 2.0],
                [0.1, 0.3, 0.1],
            ],
        ];
        for runs in shapes {
            let runs: Vec<Vec<f64>> = runs.iter().map(|r| r.to_vec()).collect();
            let steps = Steps::of(&runs);
            assert_eq!(steps.whole.runs, runs.len());
            let parts = steps.steps.iter().copied().chain([steps.part(&[0, 2])]);
            for s in parts {
                assert!(s.median <= steps.whole.median, "{s:?} {:?}", steps.whole);
                assert!(s.min <= steps.whole.min && s.max <= steps.whole.max);
            }
        }
        // Many random runs: the same, every time.
        let noise = values(4 * 6 * 200, 5);
        for case in noise.chunks_exact(4 * 6) {
            // 6 runs of 4 steps (an even count: the median is a mean of two).
            let runs: Vec<Vec<f64>> = case
                .chunks_exact(4)
                .map(|r| r.iter().map(|&v| v as f64).collect())
                .collect();
            let steps = Steps::of(&runs);
            let parts = steps.steps.iter().copied().chain([steps.part(&[1, 3])]);
            for s in parts {
                assert!(s.median <= steps.whole.median && s.max <= steps.whole.max);
                assert!(s.min <= steps.whole.min);
            }
        }
    }
}
