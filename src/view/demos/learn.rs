//! A lesson live (`view learn <id>`): the buffer of each pass that wrote one (Tab cycles them),
//! the pass and the checks against the CPU in the overlay, and for a lesson that iterates
//! (ping-pong) one more iteration per step.
//!
//! A lesson that iterates runs again at each step, and so reads its shaders again. With a
//! `--glsl-dir`, the demo therefore runs from its own copy of that folder's shader files,
//! taken when it was built (and checked by the first run): a file saved broken while it runs
//! does not reach its steps. The live reload builds a new demo from the saved files; when that
//! fails, this one keeps stepping with the last good shaders, and the window draws the error.

use crate::gl::Context;
use crate::learn::{self, Lesson, LessonOptions, LessonRun};
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};

pub struct LearnDemo {
    ctx: Context,
    /// The copy of the `--glsl-dir` shader files this demo runs with (none without one).
    shaders: Option<ShaderCopy>,
    lesson: &'static dyn Lesson,
    run: LessonRun,
    /// Iterations of the last run (lessons that iterate).
    iterations: u32,
    /// The buffer the last frame showed, for the overlay.
    shown: usize,
}

impl LearnDemo {
    pub fn new(ctx: &Context, id: &str) -> anyhow::Result<Self> {
        let lesson = learn::find(id)?;
        let iterations = 1;
        let shaders = match ctx.glsl_dir() {
            Some(dir) => Some(ShaderCopy::of(&dir)?),
            None => None,
        };
        // The first run reads the given folder itself, so that its errors name the
        // learner's files; the copy was taken just before, of the same files.
        let run = Self::run_lesson(ctx, None, lesson, iterations)?;
        Ok(LearnDemo {
            ctx: ctx.clone(),
            shaders,
            lesson,
            run,
            iterations,
            shown: 0,
        })
    }

    /// Run the lesson (`iterations` steps of one that iterates), its shaders read from
    /// `shaders` when the demo has its own copy.
    fn run_lesson(
        ctx: &Context,
        shaders: Option<&ShaderCopy>,
        lesson: &'static dyn Lesson,
        iterations: u32,
    ) -> anyhow::Result<LessonRun> {
        let opts = LessonOptions::default();
        let given = ctx.glsl_dir();
        if let Some(copy) = shaders {
            ctx.set_glsl_dir(Some(copy.dir.clone()));
        }
        let run = if lesson.iterates() {
            lesson.run_iterations(ctx, &opts, iterations)
        } else {
            lesson.run(ctx, &opts)
        };
        ctx.set_glsl_dir(given);
        run
    }
}

/// A private copy of the project's shader files found in a `--glsl-dir` folder, removed when
/// the demo goes.
struct ShaderCopy {
    dir: std::path::PathBuf,
}

impl ShaderCopy {
    fn of(given: &std::path::Path) -> anyhow::Result<ShaderCopy> {
        use std::sync::atomic::{AtomicUsize, Ordering};
        static MADE: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "classic-gpgpu-view-learn-{}-{}",
            std::process::id(),
            MADE.fetch_add(1, Ordering::Relaxed)
        ));
        let copy = ShaderCopy { dir };
        for shader in crate::gl::shaders::ALL {
            let from = given.join(shader.name);
            if from.is_file() {
                let text = std::fs::read(&from)
                    .map_err(|e| anyhow::anyhow!("reading {}: {e}", from.display()))?;
                crate::files::write_bytes(&copy.dir.join(shader.name), &text)?;
            }
        }
        Ok(copy)
    }
}

impl Drop for ShaderCopy {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

impl Demo for LearnDemo {
    /// One more iteration of a lesson that iterates; the others ran once and stay.
    fn step(&mut self) -> anyhow::Result<()> {
        if self.lesson.iterates() {
            self.iterations += 1;
            self.run = Self::run_lesson(
                &self.ctx,
                self.shaders.as_ref(),
                self.lesson,
                self.iterations,
            )?;
        }
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.1, 0.1, 0.12, 1.0])?;
        let buffers = &self.run.buffers;
        if buffers.is_empty() {
            return Ok(());
        }
        self.shown = view.shown % buffers.len();
        let b = &buffers[self.shown];
        // Each channel a panel on its set's scale, probed against the CPU where the lesson
        // keeps its reference per texel.
        let shown: Vec<Shown> = self
            .run
            .panels(self.shown)
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

    fn buffers(&self) -> Vec<String> {
        self.run
            .buffers
            .iter()
            .map(|b| self.run.passes[b.pass].name.clone())
            .collect()
    }

    fn overlay(&self) -> Vec<String> {
        let r = &self.run;
        let info = self.lesson.info();
        let mut lines = vec![format!("lesson {}: {} ({})", info.number, r.title, r.id)];
        if self.lesson.iterates() {
            lines.push(format!("{} iterations [right: one more]", self.iterations));
        }
        if let Some(b) = r.buffers.get(self.shown) {
            let pass = &r.passes[b.pass];
            let shader = if pass.shader.is_empty() {
                String::new()
            } else {
                format!(" [{}]", pass.shader)
            };
            lines.push(format!("pass {}: {}{shader}", b.pass, pass.name));
            lines.extend(crate::gl::picture::wrap(&pass.what, 90));
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
        self.shown = shown % self.run.buffers.len().max(1);
    }
}
