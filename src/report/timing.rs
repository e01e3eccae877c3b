//! How many times the report times one measurement (issue 16), and what it keeps of the
//! runs: the median, and the spread so a reader can judge it.
//!
//! A measurement runs at least [`Runs::min`] times, and again, up to [`Runs::max`], only
//! while the runs so far took less than [`Runs::budget`] in all (like hyperfine's minimum
//! runs and minimum time). Short measurements, where one run is noisy, get every run;
//! measurements of seconds, where a median of three is as stable as one of five, stop at
//! three and leave the machine's time to the paper's sizes.

use serde::Serialize;
use std::time::{Duration, Instant};

/// How often one measurement is repeated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Runs {
    /// Always this many runs.
    pub min: usize,
    /// Never more than this many.
    pub max: usize,
    /// Runs past `min` only while the runs so far took less than this (wall clock).
    pub budget: Duration,
}

impl Runs {
    /// The report's default at the papers' sizes: 3 runs, up to 5 while they take under a
    /// second in all.
    pub const PAPER: Runs = Runs {
        min: 3,
        max: 5,
        budget: Duration::from_secs(1),
    };

    /// Exactly `n` runs (at least one).
    pub const fn exactly(n: usize) -> Runs {
        let n = if n == 0 { 1 } else { n };
        Runs {
            min: n,
            max: n,
            budget: Duration::ZERO,
        }
    }

    /// [`Runs::PAPER`], or `quick` runs exactly for `--quick` (smoke tests).
    pub const fn paper_or(quick: bool, quick_runs: usize) -> Runs {
        if quick {
            Runs::exactly(quick_runs)
        } else {
            Runs::PAPER
        }
    }

    /// The rules in words: "exactly 3 runs", or "3 runs, up to 5 while they took under 1 s
    /// in all".
    pub fn in_words(&self) -> String {
        if self.max > self.min {
            format!(
                "{} runs, up to {} while they took under {} s in all",
                self.min,
                self.max,
                self.budget.as_secs_f64()
            )
        } else {
            format!("exactly {} runs", self.min.max(1))
        }
    }

    /// Whether run number `done + 1` happens after `done` runs that took `spent`.
    pub fn another(&self, done: usize, spent: Duration) -> bool {
        done < self.min.max(1) || (done < self.max && spent < self.budget)
    }

    /// Runs `once` (given the run's index) as often as these rules say; the first error
    /// stops the runs.
    pub fn run<T, E>(&self, mut once: impl FnMut(usize) -> Result<T, E>) -> Result<Vec<T>, E> {
        let start = Instant::now();
        let mut out = Vec::with_capacity(self.max.max(1));
        while self.another(out.len(), start.elapsed()) {
            out.push(once(out.len())?);
        }
        Ok(out)
    }
}

/// Wall clock (ms) of `work`, run as `runs` says: median and range.
pub fn wall_ms<T>(runs: Runs, mut work: impl FnMut() -> T) -> Spread {
    let times = runs
        .run(|_| {
            let start = Instant::now();
            std::hint::black_box(work());
            Ok::<_, std::convert::Infallible>(start.elapsed().as_secs_f64() * 1e3)
        })
        .unwrap_or_else(|never| match never {});
    Spread::of(&times)
}

/// The runs of one timing: their number, median and range.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Spread {
    pub runs: usize,
    pub median: f64,
    pub min: f64,
    pub max: f64,
}

impl Spread {
    /// Of `values` (all zero for none).
    pub fn of(values: &[f64]) -> Spread {
        if values.is_empty() {
            return Spread::default();
        }
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        Spread {
            runs: sorted.len(),
            median: super::then_and_now::median(sorted.clone()),
            min: sorted[0],
            max: sorted[sorted.len() - 1],
        }
    }

    /// (max - min) / median: how far apart the runs were, relative to what is reported
    /// (0 for a zero median).
    pub fn relative_range(&self) -> f64 {
        if self.median == 0.0 {
            0.0
        } else {
            (self.max - self.min) / self.median
        }
    }
}

/// What `--runs` makes of the timings, as the report states it.
pub fn runs_policy(runs: Option<usize>, quick: bool) -> String {
    match runs {
        Some(n) => format!(
            "every repeated timing: {} (--runs {n})",
            Runs::exactly(n).in_words()
        ),
        None if quick => "--quick: each repeated timing ran a small fixed number of times, \
                          set per section"
            .into(),
        None => format!("every repeated timing: {}", Runs::PAPER.in_words()),
    }
}

/// `--runs`: how many times every repeated timing runs.
pub fn parse_runs(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!(
            "--runs takes a whole number of runs, at least 1 (got {s:?})"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slow_runs_stop_at_the_minimum_fast_ones_go_to_the_maximum() {
        let rules = Runs {
            min: 3,
            max: 5,
            budget: Duration::from_millis(30),
        };
        let slow = rules
            .run(|_| {
                std::thread::sleep(Duration::from_millis(15));
                Ok::<_, ()>(())
            })
            .unwrap();
        assert_eq!(slow.len(), 3);
        let fast = rules.run(Ok::<_, ()>).unwrap();
        assert_eq!(fast, vec![0, 1, 2, 3, 4]);
    }

    #[test]
    fn exactly_n_ignores_the_budget_and_an_error_stops_the_runs() {
        assert_eq!(Runs::exactly(2).run(Ok::<_, ()>).unwrap(), vec![0, 1]);
        assert_eq!(Runs::exactly(0).run(Ok::<_, ()>).unwrap(), vec![0]);
        let failed = Runs::PAPER.run(|i| if i == 1 { Err("second") } else { Ok(i) });
        assert_eq!(failed, Err("second"));
    }

    #[test]
    fn runs_must_be_a_positive_whole_number() {
        assert_eq!(parse_runs("5"), Ok(5));
        for bad in ["0", "-1", "three", ""] {
            let e = parse_runs(bad).unwrap_err();
            assert!(e.contains("--runs") && e.contains(bad), "{e}");
        }
        assert!(runs_policy(Some(5), true).contains("exactly 5"));
        assert!(runs_policy(None, true).contains("--quick"));
        assert_eq!(
            Runs::PAPER.in_words(),
            "3 runs, up to 5 while they took under 1 s in all"
        );
        assert_eq!(Runs::exactly(7).in_words(), "exactly 7 runs");
        assert!(runs_policy(None, false).contains("up to 5"));
    }

    #[test]
    fn spread_reports_median_and_range() {
        let s = Spread::of(&[4.0, 1.0, 2.0]);
        assert_eq!((s.runs, s.median, s.min, s.max), (3, 2.0, 1.0, 4.0));
        assert_eq!(s.relative_range(), 1.5);
        assert_eq!(Spread::of(&[]).relative_range(), 0.0);
    }
}
