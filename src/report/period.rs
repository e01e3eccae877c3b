//! The "period" block of a paper's section: which steps of the paper's main path fit the
//! GPU the paper ran on (`gl::period`), which needed the period's way, which it refuses, and
//! the results at the period's precision beside today's. Every report carries it (it adds
//! little to a section's time: the blocks run small, fixed scenes); `reproduce --no-period`
//! (and `--no-period` on a `*-bench` command) leaves it out. Each paper's section reads
//! [`requested`] and adds [`PeriodResults::tables`].

use super::Table;
use crate::gl::{Context, PeriodGpu};
use serde::Serialize;
use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(true);

/// Ask every section run from now on for its period block, or not (`--no-period`).
pub fn set_requested(on: bool) {
    REQUESTED.store(on, Ordering::Relaxed);
}

/// Whether the sections add their period block.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// How a step of the paper's path fares on the period GPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// Ran as built, under every check.
    Fits,
    /// Ran the way the period did it (the paper's own order, fp16 where it had to blend).
    PeriodsWay,
    /// The GL layer refused it, naming the limit.
    Refused,
}

impl Verdict {
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Fits => "fits",
            Verdict::PeriodsWay => "period's way",
            Verdict::Refused => "refused",
        }
    }
}

/// One step and its verdict.
#[derive(Clone, Debug, Serialize)]
pub struct Step {
    pub step: String,
    pub verdict: Verdict,
    /// What the step asks of the GPU, the way taken, or the refusal's text.
    pub detail: String,
}

/// One result today and at the period's precision.
#[derive(Clone, Debug, Serialize)]
pub struct Comparison {
    pub result: String,
    pub today: String,
    pub period: String,
    /// By how much it changes, and why.
    pub change: String,
}

/// A paper's period block.
#[derive(Clone, Debug, Serialize)]
pub struct PeriodResults {
    /// The period GPU's name.
    pub gpu: String,
    pub steps: Vec<Step>,
    pub comparisons: Vec<Comparison>,
}

impl PeriodResults {
    pub fn new(gpu: &PeriodGpu) -> PeriodResults {
        PeriodResults {
            gpu: gpu.name.clone(),
            steps: Vec::new(),
            comparisons: Vec::new(),
        }
    }

    pub fn step(&mut self, step: &str, verdict: Verdict, detail: impl Into<String>) {
        self.steps.push(Step {
            step: step.into(),
            verdict,
            detail: detail.into(),
        });
    }

    /// `Fits` with `detail` when `run` succeeded, else `Refused` with its error.
    pub fn step_from<T, E: std::fmt::Display>(
        &mut self,
        step: &str,
        run: &Result<T, E>,
        detail: &str,
    ) {
        match run {
            Ok(_) => self.step(step, Verdict::Fits, detail),
            Err(e) => self.step(step, Verdict::Refused, first_line(e)),
        }
    }

    pub fn compare(&mut self, result: &str, today: String, period: String, change: String) {
        self.comparisons.push(Comparison {
            result: result.into(),
            today,
            period,
            change,
        });
    }

    /// The steps table and the results table.
    pub fn tables(&self) -> Vec<Table> {
        let steps = Table {
            caption: format!(
                "Period: each step of the paper's path on the {} (assets/period_gpus.toml), \
                 run under its limits",
                self.gpu
            ),
            header: vec!["step".into(), "on the period GPU".into(), "detail".into()],
            rows: self
                .steps
                .iter()
                .map(|s| vec![s.step.clone(), s.verdict.name().into(), s.detail.clone()])
                .collect(),
        };
        let results = Table {
            caption: format!(
                "Period: results at the {}'s precision beside today's",
                self.gpu
            ),
            header: vec![
                "result".into(),
                "today (fp32)".into(),
                "period".into(),
                "change and why".into(),
            ],
            rows: self
                .comparisons
                .iter()
                .map(|c| {
                    vec![
                        c.result.clone(),
                        c.today.clone(),
                        c.period.clone(),
                        c.change.clone(),
                    ]
                })
                .collect(),
        };
        vec![steps, results]
    }
}

/// The whole error chain on one line (anyhow's `{:#}`), or the error's text.
fn first_line(e: &impl std::fmt::Display) -> String {
    format!("{e:#}").replace('\n', " ")
}

/// Run `f` with `ctx` under `gpu`'s limits, then put back the profile it had.
pub fn under<T>(ctx: &Context, gpu: &'static PeriodGpu, f: impl FnOnce() -> T) -> T {
    let before = ctx.period();
    ctx.set_period(Some(gpu));
    let out = f();
    ctx.set_period(before);
    out
}

/// A section's results with its period block (`None` unless [`requested`]), serialised as
/// the section's own fields plus `period`.
#[derive(Clone, Debug, Serialize)]
pub struct WithPeriod<R> {
    #[serde(flatten)]
    pub results: R,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub period: Option<PeriodResults>,
}

impl<R> WithPeriod<R> {
    /// `results`, with the period block `measure` makes when it is [`requested`].
    pub fn measure(
        results: R,
        opts: &super::BenchOptions,
        measure: impl FnOnce(&super::BenchOptions) -> anyhow::Result<PeriodResults>,
    ) -> anyhow::Result<WithPeriod<R>> {
        let period = if requested() {
            Some(measure(opts)?)
        } else {
            None
        };
        Ok(WithPeriod { results, period })
    }

    /// The period block's tables (none when it was not asked for).
    pub fn period_tables(&self) -> Vec<Table> {
        self.period
            .as_ref()
            .map(PeriodResults::tables)
            .unwrap_or_default()
    }
}

impl<R> std::ops::Deref for WithPeriod<R> {
    type Target = R;
    fn deref(&self) -> &R {
        &self.results
    }
}
