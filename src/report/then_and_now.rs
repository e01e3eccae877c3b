//! "Then and now": each paper's kernels in their 2007 formulation beside a
//! compute-shader one (OpenGL 4.3) and the CPU baseline, measured in one run on the renderer
//! at hand. Each section measures its own workload (`paperN/then_and_now.rs`); this file holds
//! the shared result type and the table.

use super::Table;
use crate::timing::{self, Load, Spread};
use serde::Serialize;

/// One stage (or the whole frame) in each formulation, milliseconds; `None` where the
/// formulation has no such stage.
#[derive(Clone, Debug, Default, Serialize)]
pub struct StageRow {
    pub stage: String,
    pub classic_ms: Option<f64>,
    pub compute_ms: Option<f64>,
    pub cpu_ms: Option<f64>,
}

impl StageRow {
    pub fn new(stage: &str, classic: Option<f64>, compute: Option<f64>, cpu: Option<f64>) -> Self {
        StageRow {
            stage: stage.into(),
            classic_ms: classic,
            compute_ms: compute,
            cpu_ms: cpu,
        }
    }
}

/// What a section's then-and-now run measured.
#[derive(Clone, Debug, Default, Serialize)]
pub struct ThenAndNow {
    /// The workload, in words.
    pub workload: String,
    /// Why the compute formulation did not run (the context lacks OpenGL 4.3), if so.
    pub unavailable: Option<String>,
    /// Per stage, then the whole frame last.
    pub stages: Vec<StageRow>,
    /// Whether both formulations gave the same answer (pairs, outputs within the bound, ...).
    pub same_answer: Option<bool>,
    /// The design decisions of the paper that the compute formulation does without, and what
    /// that is worth here.
    pub verdict: String,
}

impl ThenAndNow {
    /// The result on a context without compute shaders: the classic timings alone.
    pub fn unavailable(workload: String, reason: String, verdict: &str) -> Self {
        ThenAndNow {
            workload,
            unavailable: Some(reason),
            verdict: verdict.into(),
            ..ThenAndNow::default()
        }
    }

    /// The table: per stage and per frame, classic vs compute vs CPU, and the ratio.
    pub fn table(&self, renderer: &str) -> Table {
        self.table_ending(renderer, self.frame_ratio())
    }

    /// [`ThenAndNow::table`] with the frame's comparison judged on the runs of the two
    /// formulations and the machine's load ([`timing::judge_ends`]: not judged while the
    /// machine is loaded or the runs overlap) instead of stated from the medians.
    pub fn table_judged(
        &self,
        renderer: &str,
        classic: &Spread,
        compute: &Spread,
        load: Option<Load>,
    ) -> Table {
        let Some(frame) = self.stages.last() else {
            return self.table_ending(renderer, String::new());
        };
        let verdict = timing::judge_ends(
            timing::Ends::of(|favour| timing::faster(compute, classic, favour)),
            &format!(
                "classic {}; compute {}",
                classic.in_words(" ms"),
                compute.in_words(" ms")
            ),
            "the two formulations' runs overlap",
            load,
        );
        let said = match verdict.holds {
            Some(true) => "compute is faster than classic",
            Some(false) => "compute is not faster than classic",
            None => "which formulation is faster",
        };
        self.table_ending(
            renderer,
            format!(" Timing of '{}': {said} ({}).", frame.stage, verdict.note),
        )
    }

    /// The measured ratio of the last stage from its medians, as a closing sentence.
    fn frame_ratio(&self) -> String {
        if let Some(frame) = self.stages.last() {
            if let (Some(a), Some(b)) = (frame.classic_ms, frame.compute_ms) {
                if a > 0.0 && b > 0.0 {
                    return format!(
                        " Measured here, per {}: compute takes {:.2}x the classic time.",
                        frame.stage,
                        b / a
                    );
                }
            }
        }
        String::new()
    }

    fn table_ending(&self, renderer: &str, ending: String) -> Table {
        let ms = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
        let rows = self
            .stages
            .iter()
            .map(|r| {
                let ratio = match (r.classic_ms, r.compute_ms) {
                    (Some(a), Some(b)) if b > 0.0 => format!("{:.2}x", a / b),
                    _ => "-".into(),
                };
                vec![
                    r.stage.clone(),
                    ms(r.classic_ms),
                    ms(r.compute_ms),
                    ms(r.cpu_ms),
                    ratio,
                ]
            })
            .collect();
        let mut caption = format!(
            "Then and now: {} on {renderer}, classic (the paper's formulation, OpenGL 3.3) vs \
             compute shaders (OpenGL 4.3) vs the CPU baseline, measured in one run. ",
            self.workload
        );
        match &self.unavailable {
            Some(reason) => caption += &format!("The compute formulation did not run: {reason}. "),
            None => {
                caption += "Classic GPU stages by GL timer query, compute stages by wall clock \
                            between glFinish calls (llvmpipe's timer queries read about zero \
                            around a dispatch), frames by wall clock. ";
                if let Some(same) = self.same_answer {
                    caption += if same {
                        "Both gave the same answer. "
                    } else {
                        "THE TWO FORMULATIONS DISAGREED. "
                    };
                }
            }
        }
        caption += &self.verdict;
        caption += &ending;
        Table {
            caption,
            header: [
                "stage",
                "classic ms",
                "compute ms",
                "CPU ms",
                "classic / compute",
            ]
            .map(String::from)
            .to_vec(),
            rows,
        }
    }
}

/// The median of `values` (0 for none).
pub fn median(values: Vec<f64>) -> f64 {
    crate::timing::median(values)
}
