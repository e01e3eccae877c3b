//! The project's timing policy, below the papers so that a paper module (the buoyancy race)
//! and the report use the same rules: how many times the report times one measurement, and what it keeps of the runs: the
//! median, and the spread so a reader can judge it; and how a claim about a time is judged
//! ([`judge`]): not at all while the machine is loaded or while its runs fall on both sides
//! of the paper's number, so that a verdict does not flip from one run of the report to the
//! next with the load of a shared machine.
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
        // Reserved for the usual few runs only: a run count is the user's, and a huge one
        // must not be asked of the allocator in one piece.
        let mut out = Vec::with_capacity(self.max.clamp(1, 64));
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
            median: median(sorted.clone()),
            min: sorted[0],
            max: sorted[sorted.len() - 1],
        }
    }

    /// "3 runs: 20.000-22.000 ms, median 21.000 ms" (`unit` follows each number).
    pub fn in_words(&self, unit: &str) -> String {
        format!(
            "{} run{}: {:.3}-{:.3}{unit}, median {:.3}{unit}",
            self.runs,
            if self.runs == 1 { "" } else { "s" },
            self.min,
            self.max,
            self.median
        )
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

/// The middle value of `values` (the mean of the two middle ones for an even count; 0 for
/// none).
pub fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

// region: rule timing-verdicts
// (What every claim judged on a timing rests on: a part of its version, report::versions.)
/// The load average above which a machine counts as loaded, per core: more runnable tasks
/// than cores means the timed work waited for a core part of the time, so a timing says as
/// much about the other work as about the paper's method.
pub const LOADED_PER_CORE: f64 = 1.0;

/// How busy the machine was when a timing was taken: the 1-minute load average of
/// `/proc/loadavg` and the cores this process may use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, serde::Deserialize)]
pub struct Load {
    pub one_minute: f64,
    pub cores: usize,
}

impl Load {
    /// Now; `None` where there is no `/proc/loadavg` (not Linux).
    pub fn now() -> Option<Load> {
        let text = std::fs::read_to_string("/proc/loadavg").ok()?;
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        Load::parse(&text, cores)
    }

    /// From the text of `/proc/loadavg` ("0.52 0.58 0.59 1/467 12345").
    pub fn parse(loadavg: &str, cores: usize) -> Option<Load> {
        let one_minute = loadavg.split_whitespace().next()?.parse::<f64>().ok()?;
        Some(Load {
            one_minute,
            cores: cores.max(1),
        })
    }

    /// The busier of two readings (either may be missing).
    pub fn worst(a: Option<Load>, b: Option<Load>) -> Option<Load> {
        [a, b]
            .into_iter()
            .flatten()
            .max_by(|x, y| x.per_core().total_cmp(&y.per_core()))
    }

    pub fn per_core(&self) -> f64 {
        self.one_minute / self.cores as f64
    }

    /// Above [`LOADED_PER_CORE`].
    pub fn is_loaded(&self) -> bool {
        self.per_core() > LOADED_PER_CORE
    }

    /// "load average 3.10 on 2 cores".
    pub fn in_words(&self) -> String {
        format!(
            "load average {:.2} on {} core{}",
            self.one_minute,
            self.cores,
            if self.cores == 1 { "" } else { "s" }
        )
    }
}

/// What a command that judges timings says at its start on a loaded machine: that the
/// timed claims will read "not judged" (`None` on a quiet machine or where the load is
/// unknown).
pub fn loaded_warning(load: Option<Load>) -> Option<String> {
    let l = load.filter(Load::is_loaded)?;
    Some(format!(
        "note: the machine is loaded ({}, {:.2} per core, above the {LOADED_PER_CORE:.1} \
         under which timings are judged): the claims judged on a timing will read \
         \"not judged\"; counts and errors are judged as usual. Run on a quiet machine to \
         have every claim judged",
        l.in_words(),
        l.per_core()
    ))
}

/// Which side of the paper's number a claim needs the measurement on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// At least this much (a rate, a speed-up).
    AtLeast(f64),
    /// At most this much (a time).
    AtMost(f64),
}

impl Target {
    fn value(self) -> f64 {
        match self {
            Target::AtLeast(t) | Target::AtMost(t) => t,
        }
    }

    fn met_by(self, v: f64) -> bool {
        match self {
            Target::AtLeast(t) => v >= t,
            Target::AtMost(t) => v <= t,
        }
    }
}

/// A verdict on a timing and the words that go with it.
#[derive(Clone, Debug, PartialEq)]
pub struct TimedVerdict {
    /// `None`: not judged (the note says why).
    pub holds: Option<bool>,
    /// The runs and the load, and the reason when not judged, to append to the measured text.
    pub note: String,
}

/// Judges a timed quantity against `target`: not judged while `load` is above
/// [`LOADED_PER_CORE`] ("not judged: machine loaded") or while the runs fall on both sides of
/// the target ("not judged: the runs fall on both sides ..."); otherwise by the runs. The note
/// always gives the runs' range and the load (or says it is unknown). `unit` follows each
/// number.
pub fn judge(spread: &Spread, target: Target, load: Option<Load>, unit: &str) -> TimedVerdict {
    let t = target.value();
    judge_ends(
        Ends {
            at_best: target.met_by(spread.min).max(target.met_by(spread.max)),
            at_worst: target.met_by(spread.min).min(target.met_by(spread.max)),
        },
        &spread.in_words(unit),
        &format!("the runs fall on both sides of {t}{unit}"),
        load,
    )
}

/// A claim evaluated twice on the runs of its timings: with every timing at the end of its
/// runs that favours the claim, and at the end that goes against it. Where the two agree the
/// runs decide the claim; where they differ the runs cannot, and the claim is not judged
/// rather than decided by whichever median a busy machine gave.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ends {
    pub at_best: bool,
    pub at_worst: bool,
}

impl Ends {
    /// Evaluates `claim` at both ends: `claim(true)` must take each timing at its end that
    /// favours the claim, `claim(false)` at the end against it.
    pub fn of(claim: impl Fn(bool) -> bool) -> Ends {
        Ends {
            at_best: claim(true),
            at_worst: claim(false),
        }
    }
}

/// The verdict of a claim on timings whose runs are kept ([`Ends`]): not judged while `load`
/// is above [`LOADED_PER_CORE`], nor while the two ends disagree (`undecided` says how); else
/// what both ends say. The note gives `runs` (the runs in words) and the load.
pub fn judge_ends(ends: Ends, runs: &str, undecided: &str, load: Option<Load>) -> TimedVerdict {
    let load_words = load.map_or("load average unknown".to_string(), |l| l.in_words());
    let (holds, reason) = if let Some(l) = load.filter(Load::is_loaded) {
        (
            None,
            format!(
                "not judged: machine loaded ({:.2} per core, above the {LOADED_PER_CORE:.1} \
                 this report judges timings under)",
                l.per_core()
            ),
        )
    } else if ends.at_best != ends.at_worst {
        (None, format!("not judged: {undecided}"))
    } else {
        (Some(ends.at_worst), String::new())
    };
    let mut note = format!("{runs}; {load_words}");
    if !reason.is_empty() {
        note = format!("{note}; {reason}");
    }
    TimedVerdict { holds, note }
}

/// Of two timings (ms) with their runs kept: whether `a` is faster than `b`, taken at the end
/// of the runs that favours "faster" (`favour`: `a`'s fastest run against `b`'s slowest) or
/// at the end against it.
pub fn faster(a: &Spread, b: &Spread, favour: bool) -> bool {
    if favour {
        a.min < b.max
    } else {
        a.max < b.min
    }
}

/// The end of a spread a claim takes: its low end or its high end.
pub fn end(spread: &Spread, high: bool) -> f64 {
    if high {
        spread.max
    } else {
        spread.min
    }
}

/// The verdict of a claim judged on timings whose runs are not kept one by one (ratios of
/// medians): not judged while `load` is above [`LOADED_PER_CORE`], else `holds`. The note
/// gives the load.
pub fn judge_under_load(holds: bool, load: Option<Load>) -> TimedVerdict {
    match load {
        Some(l) if l.is_loaded() => TimedVerdict {
            holds: None,
            note: format!(
                "{}; not judged: machine loaded ({:.2} per core, above the \
                 {LOADED_PER_CORE:.1} this report judges timings under)",
                l.in_words(),
                l.per_core()
            ),
        },
        Some(l) => TimedVerdict {
            holds: Some(holds),
            note: l.in_words(),
        },
        None => TimedVerdict {
            holds: Some(holds),
            note: "load average unknown".into(),
        },
    }
}
// endregion

/// The environment variable that turns on [`mark`]: `CLASSIC_GPGPU_MARKS=1`.
pub const MARKS_ENV: &str = "CLASSIC_GPGPU_MARKS";

/// With `CLASSIC_GPGPU_MARKS=1` set, prints to stderr the wall clock and the process's CPU
/// time (every thread: the software renderer's too) since the previous mark, labelled
/// `what`: where a section's time goes, step by step, counted in CPU seconds (less
/// sensitive than wall time to other work on a shared machine). Nothing without the
/// variable.
pub fn mark(what: &str) {
    use std::sync::Mutex;
    static LAST: Mutex<Option<(Instant, f64)>> = Mutex::new(None);
    if std::env::var_os(MARKS_ENV).is_none() {
        return;
    }
    let now = (Instant::now(), process_cpu_s());
    let mut last = LAST.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((wall, cpu)) = *last {
        eprintln!(
            "mark {what}: {:.2} s wall, {:.2} s CPU",
            now.0.duration_since(wall).as_secs_f64(),
            now.1 - cpu
        );
    } else {
        eprintln!("mark {what}: first mark");
    }
    *last = Some(now);
}

/// CPU time of this process so far (user + system, all threads), s, from `/proc/self/stat`
/// (USER_HZ ticks, 100 per second on Linux); 0 where there is no such file.
pub fn process_cpu_s() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // The fields after the command name (which may hold spaces) follow its ')'.
    let Some((_, rest)) = stat.rsplit_once(')') else {
        return 0.0;
    };
    // utime and stime: fields 14 and 15 of the line, 11 and 12 after the name.
    let ticks: f64 = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|f| f.parse::<f64>().ok())
        .sum();
    ticks / 100.0
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
    fn runs_must_be_a_whole_number_in_range() {
        let runs = crate::values::ranges::RUNS;
        assert_eq!(runs.parse("--runs", "5"), Ok(5));
        for bad in ["0", "-1", "three", "", "1e11", "18446744073709551615"] {
            let e = runs.parse("--runs", bad).unwrap_err();
            assert!(e.contains("--runs") && e.contains("from 1 to 1000"), "{e}");
        }
        // A run count is never reserved whole: the runs grow as they happen.
        assert_eq!(
            Runs::exactly(usize::MAX).run(|_| Err::<(), _>("stop")),
            Err("stop")
        );
        assert!(runs_policy(Some(5), true).contains("exactly 5"));
        assert!(runs_policy(None, true).contains("--quick"));
        assert_eq!(
            Runs::PAPER.in_words(),
            "3 runs, up to 5 while they took under 1 s in all"
        );
        assert_eq!(Runs::exactly(7).in_words(), "exactly 7 runs");
        assert!(runs_policy(None, false).contains("up to 5"));
    }

    fn load(one_minute: f64, cores: usize) -> Option<Load> {
        Some(Load { one_minute, cores })
    }

    #[test]
    fn a_loaded_machine_gives_not_judged() {
        let runs = Spread::of(&[20.0, 21.0, 22.0]);
        // 15 runnable tasks on 2 cores: loaded, whichever side of the target the runs fall.
        for target in [Target::AtLeast(16.0), Target::AtLeast(30.0)] {
            let v = judge(&runs, target, load(15.0, 2), " steps/s");
            assert_eq!(v.holds, None);
            assert!(v.note.contains("not judged: machine loaded"), "{}", v.note);
            assert!(
                v.note.contains("load average 15.00 on 2 cores"),
                "{}",
                v.note
            );
        }
        // The same runs on a quiet machine are judged by them.
        let quiet = judge(&runs, Target::AtLeast(16.0), load(0.5, 2), " steps/s");
        assert_eq!(quiet.holds, Some(true));
        assert!(
            quiet.note.contains("20.000-22.000 steps/s"),
            "{}",
            quiet.note
        );
        assert_eq!(
            judge(&runs, Target::AtLeast(30.0), load(0.5, 2), "").holds,
            Some(false)
        );
        assert_eq!(judge_under_load(true, load(4.1, 4)).holds, None);
        assert_eq!(judge_under_load(false, load(3.9, 4)).holds, Some(false));
        assert_eq!(judge_under_load(true, None).holds, Some(true));
    }

    #[test]
    fn runs_on_both_sides_of_the_target_are_not_judged() {
        let runs = Spread::of(&[12.8, 20.0, 36.2]);
        let v = judge(&runs, Target::AtLeast(16.0), load(0.2, 8), " steps/s");
        assert_eq!(v.holds, None);
        assert!(v.note.contains("both sides of 16 steps/s"), "{}", v.note);
        let v = judge(&runs, Target::AtMost(12.8), load(0.2, 8), " ms");
        assert_eq!(v.holds, None, "{}", v.note);
        assert_eq!(
            judge(&runs, Target::AtMost(36.2), load(0.2, 8), " ms").holds,
            Some(true)
        );
    }

    #[test]
    fn a_claim_the_ends_of_its_runs_disagree_on_is_not_judged() {
        let (gpu, cpu) = (
            Spread::of(&[8.0, 9.0, 12.0]),
            Spread::of(&[10.0, 11.0, 11.5]),
        );
        let ends = Ends::of(|favour| faster(&gpu, &cpu, favour));
        assert_eq!(
            ends,
            Ends {
                at_best: true,
                at_worst: false
            }
        );
        let v = judge_ends(ends, &gpu.in_words(" ms"), "the runs overlap", load(0.3, 2));
        assert_eq!(v.holds, None);
        assert!(
            v.note.contains("not judged: the runs overlap"),
            "{}",
            v.note
        );
        assert!(v.note.contains("3 runs: 8.000-12.000 ms"), "{}", v.note);
        // Runs apart: decided, and the same way whichever end is taken.
        let slow = Spread::of(&[13.0, 14.0, 20.0]);
        let ends = Ends::of(|favour| faster(&gpu, &slow, favour));
        assert_eq!(judge_ends(ends, "", "", load(0.3, 2)).holds, Some(true));
        let ends = Ends::of(|favour| faster(&slow, &gpu, favour));
        assert_eq!(judge_ends(ends, "", "", load(0.3, 2)).holds, Some(false));
        // A loaded machine is never judged, whatever the runs say.
        assert_eq!(judge_ends(ends, "", "", load(9.0, 2)).holds, None);
        assert_eq!((end(&gpu, true), end(&gpu, false)), (12.0, 8.0));
    }

    #[test]
    fn a_loaded_machine_is_said_at_the_start() {
        let w = loaded_warning(load(5.0, 2)).expect("loaded");
        assert!(w.contains("load average 5.00 on 2 cores") && w.contains("2.50 per core"));
        assert!(w.contains("not judged"), "{w}");
        assert_eq!(loaded_warning(load(1.9, 2)), None);
        assert_eq!(loaded_warning(None), None);
    }

    #[test]
    fn the_load_is_read_from_loadavg() {
        let l = Load::parse("3.10 2.00 1.00 2/345 678\n", 2).unwrap();
        assert_eq!(
            l,
            Load {
                one_minute: 3.1,
                cores: 2
            }
        );
        assert!(l.is_loaded());
        assert!(Load::parse("", 2).is_none());
        if std::path::Path::new("/proc/loadavg").exists() {
            assert!(Load::now().is_some());
        }
    }

    #[test]
    fn spread_reports_median_and_range() {
        let s = Spread::of(&[4.0, 1.0, 2.0]);
        assert_eq!((s.runs, s.median, s.min, s.max), (3, 2.0, 1.0, 4.0));
        assert_eq!(s.relative_range(), 1.5);
        assert_eq!(Spread::of(&[]).relative_range(), 0.0);
    }
}
