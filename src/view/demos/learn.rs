//! A lesson live (`view learn <id>`): the buffer of each pass that wrote one (Tab cycles them),
//! the pass and the checks against the CPU in the overlay, and for a lesson that iterates
//! (ping-pong) one more iteration per step.
//!
//! A lesson that iterates is held between steps ([`learn::Iteration`]): a step is one more
//! iteration from the current iterate, never the lesson run again from the start, and its
//! buffers keep their numbers at every iteration ([`learn::Slot`]), the ones a later iteration
//! makes included, so that `--buffer K` names any of them from the first frame. The viewer
//! opens on the first buffer that changes with each iteration (the latest iterate).
//!
//! The demo's programs are compiled once, when it is built (from `--glsl-dir` when there is
//! one), so a file saved broken while it runs does not reach its steps: the live reload
//! ([`crate::view::live`]) builds a new demo from the saved files, and when that fails this
//! one keeps stepping with the last good shaders while the window draws the error.

use crate::gl::Context;
use crate::learn::{self, Iteration, Lesson, LessonOptions, LessonRun, Slot};
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};

pub struct LearnDemo {
    lesson: &'static dyn Lesson,
    /// A lesson that iterates, held between steps; `None` for one that ran once.
    iteration: Option<Box<dyn Iteration>>,
    /// The run as it stands, and its buffers as the viewer numbers them.
    run: LessonRun,
    slots: Vec<Slot>,
    /// The slot the last frame showed, for the overlay.
    shown: usize,
}

impl LearnDemo {
    /// The lesson `id` run on `ctx`; one that iterates is at its first iteration.
    pub fn new(ctx: &Context, id: &str) -> anyhow::Result<Self> {
        let lesson = learn::find(id)?;
        let opts = LessonOptions::default();
        let mut demo = match lesson.iteration(ctx, &opts)? {
            Some(mut iteration) => {
                iteration.advance(1)?;
                let (run, slots) = iteration.record()?;
                LearnDemo {
                    lesson,
                    iteration: Some(iteration),
                    run,
                    slots,
                    shown: 0,
                }
            }
            None => {
                let run = lesson.run(ctx, &opts)?;
                LearnDemo {
                    lesson,
                    iteration: None,
                    slots: Slot::each(&run),
                    run,
                    shown: 0,
                }
            }
        };
        demo.shown = demo.first_buffer();
        Ok(demo)
    }

    /// The buffer of the run that slot `shown` holds now, if it is made yet.
    fn buffer(&self, shown: usize) -> Option<usize> {
        self.slots.get(shown).and_then(|s| s.buffer)
    }
}

impl Demo for LearnDemo {
    /// One more iteration of a lesson that iterates, from the current one; the others ran
    /// once and stay.
    fn step(&mut self) -> anyhow::Result<()> {
        self.advance(1)
    }

    /// `steps` iterations at once, the run recorded (read back, checked) once at the end.
    fn advance(&mut self, steps: usize) -> anyhow::Result<()> {
        let Some(iteration) = self.iteration.as_mut() else {
            return Ok(());
        };
        if steps == 0 {
            return Ok(());
        }
        iteration.advance(u32::try_from(steps)?)?;
        (self.run, self.slots) = iteration.record()?;
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.1, 0.1, 0.12, 1.0])?;
        self.show(view.shown);
        // A buffer a later iteration makes: nothing to draw yet (the overlay says so).
        let Some(i) = self.buffer(self.shown) else {
            return Ok(());
        };
        let b = &self.run.buffers[i];
        // Each channel a panel on its set's scale, probed against the CPU where the lesson
        // keeps its reference per texel.
        let shown: Vec<Shown> = self
            .run
            .panels(i)
            .into_iter()
            .enumerate()
            .map(|(c, panel)| Shown {
                panel,
                probe_values: None,
                reference: b
                    .reference
                    .as_ref()
                    .map(|r| r.iter().skip(c).step_by(b.channels).copied().collect()),
            })
            .collect();
        inset::draw_picture(canvas, shown, canvas.below_text())?;
        Ok(())
    }

    /// Every buffer the lesson makes, the ones a later iteration makes included.
    fn buffers(&self) -> Vec<String> {
        self.slots.iter().map(|s| s.name.clone()).collect()
    }

    fn overlay(&self) -> Vec<String> {
        let r = &self.run;
        let info = self.lesson.info();
        let mut lines = vec![format!("lesson {}: {} ({})", info.number, r.title, r.id)];
        if let Some(iteration) = &self.iteration {
            let k = iteration.iterations();
            let done = format!("{k} iteration{}", if k == 1 { "" } else { "s" });
            lines.push(match iteration.stopped() {
                Some(why) => format!("{done}, the last: {why}"),
                None => format!("{done} [right: one more]"),
            });
        }
        match (self.slots.get(self.shown), self.buffer(self.shown)) {
            (Some(_), Some(i)) => {
                let b = &r.buffers[i];
                let pass = &r.passes[b.pass];
                let shader = if pass.shader.is_empty() {
                    String::new()
                } else {
                    format!(" [{}]", pass.shader)
                };
                lines.push(format!("pass {}: {}{shader}", b.pass, pass.name));
                lines.extend(crate::gl::picture::wrap(&pass.what, 90));
            }
            (Some(slot), None) => lines.push(format!(
                "{}: not made yet; a later iteration makes it [right: one more]",
                slot.name
            )),
            (None, _) => {}
        }
        let passed = r.checks.iter().filter(|c| c.passed).count();
        lines.push(format!(
            "checks against the CPU: {passed} of {} passed, largest error {:.2e}",
            r.checks.len(),
            r.max_error
        ));
        for c in r.checks.iter().filter(|c| !c.passed) {
            lines.push(format!(
                "FAIL {}: {:.2e} > {:.2e}",
                c.what, c.max_error, c.tolerance
            ));
        }
        lines
    }

    fn timings(&self) -> String {
        format!("lesson {} on {}", self.run.id, self.run.renderer)
    }

    fn show(&mut self, shown: usize) {
        self.shown = shown % self.slots.len().max(1);
    }

    /// The latest iterate of a lesson that iterates (the first buffer that changes); the
    /// first buffer of one that ran once.
    fn first_buffer(&self) -> usize {
        self.slots.iter().position(|s| s.changes).unwrap_or(0)
    }
}
