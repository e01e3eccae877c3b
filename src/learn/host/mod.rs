//! Host exercises (issue 51): the learner writes the GL calls themselves. Every other lesson
//! keeps the host side behind `fb.pass(..).draw_full()`; Göddeke's GPGPU::Basic Math tutorial
//! is about exactly those calls (textures, framebuffer, viewport, program, the draw, the swap,
//! the readback), and so are these exercises.
//!
//! An exercise is an example of the crate, `examples/NAME.rs`, run with
//! `cargo run --release --example NAME` against the project's build (only the example
//! compiles). It is the template: a program with numbered gaps, each a line
//! `ex.gap(N)?` (or `ex.gap_value(N)?` where the step makes a value) that stops the run naming
//! the GL step it needs. The learner replaces each gap with glow calls on the recorder the
//! exercise hands out ([`Exercise::gl`], the learner's door of the GL layer:
//! [`crate::gl::learner`]). After each gap the template checks the step ([`Exercise`]'s
//! methods: the texture holds the array, the framebuffer draws into the texture, the viewport
//! is the target's, the draw reads no texture it writes, ...), so a wrong call stops the run
//! at the step that made it, naming what is wrong. The result the program returns is checked
//! texel by texel against the lesson's CPU reference, as every lesson is
//! ([`super::LessonRun::check_texels`]).
//!
//! The shipped solution is `examples/NAME-solution.rs`: the same file with each gap filled
//! between the lines `// region: gap-N` and `// endregion`. Hints come in three grades from
//! the example's command line (`-- --hint N.1` the idea, `N.2` the call, `N.3` the line, which
//! is the solution's region, cut from the file as it is). After a run, the learner's GL calls
//! are set beside the solution's, the first difference marked ([`beside`]).
//!
//! The debugging lesson's exercise is a hunt instead ([`hunt`]): a program with faults planted
//! in it, each checked by what it leaves in the trace or in the state of a draw.

pub mod beside;
pub mod hunt;
pub mod ping_pong;
pub mod readback;
pub mod reduction;
pub mod saxpy;

use super::feedback::wrong_texels;
use super::{Grid, LessonRun};
use crate::gl::learner::{DrawFacts, FormatKind, LearnerGl, UniformValue};
use crate::gl::trace::{Gl, Id, TracedCall};
use crate::gl::Context;
use serde::Serialize;
use std::cell::{Cell, RefCell};
use std::fmt;
use std::io::Write;
use std::process::ExitCode;

/// One gap of a template: the GL step it stands for, and two hints (the third is the
/// solution's region `gap-N`).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Gap {
    /// 1, 2, ... in the order the program reaches them.
    pub number: u32,
    /// The GL step, naming its calls: what the message of an unfilled gap says.
    pub step: &'static str,
    /// The idea, then the call with its arguments.
    #[serde(skip)]
    pub hints: [&'static str; 2],
}

/// A host exercise: its example, its lesson, its gaps (or faults), and the lesson's checks of
/// what the program returns.
#[derive(Debug)]
pub struct HostExercise {
    /// The example's name: `cargo run --release --example NAME`; the solution is `NAME-solution`.
    pub example: &'static str,
    /// The id of the lesson it belongs to.
    pub lesson: &'static str,
    pub title: &'static str,
    pub gaps: &'static [Gap],
    /// The planted faults, for the hunt (empty for an exercise with gaps).
    pub faults: &'static [hunt::Fault],
    /// The solution's file, `examples/NAME-solution.rs`.
    pub solution_file: &'static str,
    /// The solution file's text, compiled in (the third hint of each gap is cut from it).
    pub solution_text: &'static str,
    /// The lesson's checks of the values the program returns, added to the run.
    pub check: fn(&mut LessonRun, &[f32]),
}

/// What `learn --list --json` says of a lesson's host exercise.
#[derive(Clone, Debug, Serialize)]
pub struct HostCard {
    pub title: &'static str,
    /// The file the learner edits, from the repository's root.
    pub template: String,
    /// The shipped solution.
    pub solution: String,
    /// The command that runs the template, from the repository's root.
    pub run: String,
    /// The command that runs the solution.
    pub run_solution: String,
    /// The GL steps the gaps stand for, in order.
    pub gaps: Vec<&'static str>,
    /// The symptoms of the planted faults (the hunt).
    pub faults: Vec<&'static str>,
}

impl HostExercise {
    pub fn template(&self) -> String {
        format!("examples/{}.rs", self.example)
    }

    pub fn solution(&self) -> String {
        self.solution_file.to_string()
    }

    pub fn run_command(&self) -> String {
        format!("cargo run --release --example {}", self.example)
    }

    pub fn run_solution_command(&self) -> String {
        format!("cargo run --release --example {}-solution", self.example)
    }

    pub fn card(&self) -> HostCard {
        HostCard {
            title: self.title,
            template: self.template(),
            solution: self.solution(),
            run: self.run_command(),
            run_solution: self.run_solution_command(),
            gaps: self.gaps.iter().map(|g| g.step).collect(),
            faults: self.faults.iter().map(|f| f.symptom).collect(),
        }
    }

    /// The gap numbered `n`.
    pub fn gap(&self, n: u32) -> Option<&'static Gap> {
        self.gaps.iter().find(|g| g.number == n)
    }

    /// The solution's lines for gap `n` (its region `gap-N`), or for fault `n` (`fault-N`).
    pub fn solution_region(&self, name: &str) -> Result<String, String> {
        super::regions::cut_text(self.solution_file, self.solution_text, name).map(|r| r.text)
    }
}

/// Every host exercise, in the lessons' order.
pub fn all() -> [&'static HostExercise; 5] {
    [
        &saxpy::CARD,
        &ping_pong::CARD,
        &reduction::CARD,
        &readback::CARD,
        &hunt::CARD,
    ]
}

/// The host exercise of lesson `id`, if it has one.
pub fn for_lesson(id: &str) -> Option<&'static HostExercise> {
    all().into_iter().find(|h| h.lesson == id)
}

/// Why a run stopped before its end.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Stop {
    /// Gap N is not filled.
    Gap(u32),
    /// The check after gap N failed: what is wrong.
    Step { gap: u32, problem: String },
}

impl fmt::Display for Stop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Stop::Gap(n) => write!(f, "gap {n} is not filled"),
            Stop::Step { gap, problem } => write!(f, "the check after gap {gap}: {problem}"),
        }
    }
}

impl std::error::Error for Stop {}

/// The stopwatch of an exercise: a wall clock whose start and reading are marked in the trace,
/// so a reader (and the hunt) sees where it was read among the GL calls.
#[derive(Clone, Copy, Debug)]
pub struct Stopwatch {
    started: std::time::Instant,
    /// The calls recorded when it started.
    mark: usize,
}

/// One reading of a stopwatch: the calls between its start and its reading, and the time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reading {
    /// The calls recorded when it started and when it was read: calls `from + 1 ..= to`
    /// (1-based) were made while it ran.
    pub from: usize,
    pub to: usize,
    pub ms: f64,
}

/// What a host exercise's program gets: the recorder to make its GL calls on, and the checks
/// of each step. A failed check stops the run ([`Stop::Step`]) naming the gap and what is wrong.
pub struct Exercise {
    door: LearnerGl,
    /// The highest gap whose checks have passed.
    reached: Cell<u32>,
    /// Every draw inspected so far, in order.
    draws: RefCell<Vec<DrawFacts>>,
    readings: RefCell<Vec<Reading>>,
    /// Each check made, in order: its gap and the calls recorded by then.
    checks: RefCell<Vec<(u32, usize)>>,
    /// The lesson's checks made during the run (a first level texel by texel, ...).
    run: RefCell<LessonRun>,
}

impl Exercise {
    fn new(card: &'static HostExercise, ctx: &Context) -> anyhow::Result<Exercise> {
        let lesson = super::find(card.lesson)?;
        let mut run = LessonRun::new(lesson.info(), ctx);
        run.title = card.title.to_string();
        Ok(Exercise {
            door: ctx.learner(),
            reached: Cell::new(0),
            draws: RefCell::new(Vec::new()),
            readings: RefCell::new(Vec::new()),
            checks: RefCell::new(Vec::new()),
            run: RefCell::new(run),
        })
    }

    /// The recorder, with glow's methods and signatures: make every GL call on it.
    pub fn gl(&self) -> &Gl {
        self.door.gl()
    }

    /// An unfilled gap that makes nothing: replace the line with your GL calls.
    pub fn gap(&self, n: u32) -> anyhow::Result<()> {
        self.gap_value(n)
    }

    /// An unfilled gap that makes a value (a texture, a framebuffer, an array read back):
    /// replace the line with your GL calls that make it.
    pub fn gap_value<T>(&self, n: u32) -> anyhow::Result<T> {
        Err(Stop::Gap(n).into())
    }

    /// Start the stopwatch (wall clock); its start is marked in the trace. While it runs the
    /// draws are not inspected, so that it times your calls alone.
    pub fn start_clock(&self) -> Stopwatch {
        self.door.inspect_draws(false);
        Stopwatch {
            started: std::time::Instant::now(),
            mark: self.door.calls_so_far(),
        }
    }

    /// Read the stopwatch: the milliseconds since it started, the reading marked in the trace.
    pub fn read_clock(&self, clock: &Stopwatch) -> f64 {
        let ms = clock.started.elapsed().as_secs_f64() * 1e3;
        self.door.inspect_draws(true);
        self.readings.borrow_mut().push(Reading {
            from: clock.mark,
            to: self.door.calls_so_far(),
            ms,
        });
        ms
    }

    /// Nothing more than every check makes: no GL error since the previous check, no draw
    /// that GL lets pass but leaves undefined or wrong.
    pub fn no_errors(&self, gap: u32) -> anyhow::Result<()> {
        self.step(gap, || Ok(()))
    }

    /// Texture `texture` is a sampleable float texture of `grid`'s size and channels holding
    /// exactly `values` (rows from the bottom).
    pub fn texture_holds(
        &self,
        gap: u32,
        texture: glow::Texture,
        grid: Grid,
        values: &[f32],
    ) -> anyhow::Result<()> {
        self.step(gap, || {
            let facts = self.float_facts(texture, grid)?;
            let (count, first) = wrong_texels(grid, &facts.values, values, 0.0);
            match first.first() {
                None => Ok(()),
                Some(w) => Err(format!(
                    "texture {} does not hold the array: {count} of {} values differ; the \
                     first, texel ({}, {}) channel {}: the texture holds {}, the array {}",
                    facts.id,
                    values.len(),
                    w.x,
                    w.y,
                    w.channel,
                    w.gpu,
                    w.cpu
                )),
            }
        })
    }

    /// Texture `texture` is a sampleable float texture of `grid`'s size and channels.
    pub fn float_texture(
        &self,
        gap: u32,
        texture: glow::Texture,
        grid: Grid,
    ) -> anyhow::Result<()> {
        self.step(gap, || self.float_facts(texture, grid).map(|_| ()))
    }

    /// Framebuffer `framebuffer` is complete, with `texture` as its colour attachment 0.
    pub fn framebuffer_on(
        &self,
        gap: u32,
        framebuffer: glow::Framebuffer,
        texture: glow::Texture,
    ) -> anyhow::Result<()> {
        self.step(gap, || {
            let f = self.door.framebuffer(framebuffer)?;
            match f.color0 {
                Some(t) if t == texture.id() => {}
                Some(t) => {
                    return Err(format!(
                        "framebuffer {} draws into texture {t} (its GL_COLOR_ATTACHMENT0), not \
                         texture {} (glFramebufferTexture2D)",
                        f.id,
                        texture.id()
                    ))
                }
                None => {
                    return Err(format!(
                        "framebuffer {} has no texture as GL_COLOR_ATTACHMENT0: attach texture \
                         {} (glFramebufferTexture2D)",
                        f.id,
                        texture.id()
                    ))
                }
            }
            if f.complete {
                Ok(())
            } else {
                Err(format!(
                    "framebuffer {} is not complete: glCheckFramebufferStatus says {}",
                    f.id, f.status
                ))
            }
        })
    }

    /// Program `program` is linked.
    pub fn linked(&self, gap: u32, program: glow::Program) -> anyhow::Result<()> {
        self.step(gap, || {
            let p = self.door.program(program);
            if p.linked {
                Ok(())
            } else {
                Err(format!(
                    "program {} is not linked (glLinkProgram), its log: {}",
                    p.id,
                    p.log.trim()
                ))
            }
        })
    }

    /// Program `program` is in use.
    pub fn in_use(&self, gap: u32, program: glow::Program) -> anyhow::Result<()> {
        self.step(gap, || match self.door.program_in_use() {
            id if id == program.id() => Ok(()),
            0 => Err(format!(
                "no program is in use: make program {} current (glUseProgram)",
                program.id()
            )),
            id => Err(format!(
                "program {id} is in use, not program {} (glUseProgram)",
                program.id()
            )),
        })
    }

    /// Sampler `name` of the program in use reads `texture`: it is set to a unit, and the
    /// texture is bound to `GL_TEXTURE_2D` on that unit.
    pub fn sampler_reads(
        &self,
        gap: u32,
        name: &str,
        texture: glow::Texture,
    ) -> anyhow::Result<()> {
        self.step(gap, || {
            let unit = match self.door.uniform(name)? {
                UniformValue::Sampler(unit) => unit,
                other => return Err(format!("{name} is not a sampler: it holds {other:?}")),
            };
            match self.door.texture_on_unit(unit) {
                t if t == texture.id() => Ok(()),
                0 => Err(format!(
                    "sampler {name} reads texture unit {unit} (glUniform1i), where no texture \
                     is bound: bind texture {} there (glActiveTexture, glBindTexture)",
                    texture.id()
                )),
                t => Err(format!(
                    "sampler {name} reads texture unit {unit} (glUniform1i), where texture {t} \
                     is bound, not texture {} (glActiveTexture, glBindTexture)",
                    texture.id()
                )),
            }
        })
    }

    /// Uniform `name` of the program in use holds `values` (floats).
    pub fn uniform_f32(&self, gap: u32, name: &str, values: &[f32]) -> anyhow::Result<()> {
        self.step(gap, || match self.door.uniform(name)? {
            UniformValue::Float(v) if v == values => Ok(()),
            other => Err(format!(
                "uniform {name} holds {}, not {} (glUniform* while the program is in use)",
                shown(&other),
                list(values)
            )),
        })
    }

    /// Uniform `name` of the program in use holds `values` (integers; a sampler its unit).
    pub fn uniform_i32(&self, gap: u32, name: &str, values: &[i32]) -> anyhow::Result<()> {
        self.step(gap, || match self.door.uniform(name)? {
            UniformValue::Int(v) if v == values => Ok(()),
            UniformValue::Sampler(u) if values == [u] => Ok(()),
            other => Err(format!(
                "uniform {name} holds {}, not {} (glUniform* while the program is in use)",
                shown(&other),
                list(values)
            )),
        })
    }

    /// The viewport is `texture`'s whole rectangle.
    pub fn viewport_covers(&self, gap: u32, texture: glow::Texture) -> anyhow::Result<()> {
        self.step(gap, || {
            let t = self.door.texture(texture)?;
            let v = self.door.viewport();
            if v == [0, 0, t.width as i32, t.height as i32] {
                Ok(())
            } else {
                Err(format!(
                    "the viewport is {}, {}, {} x {}, but the target, texture {}, is {} x {}: \
                     the viewport is the range of the loop (glViewport)",
                    v[0], v[1], v[2], v[3], t.id, t.width, t.height
                ))
            }
        })
    }

    /// At least one draw was made since the last check, and none did what GL lets pass but
    /// leaves undefined or wrong (every check looks at the draws made since the one before).
    pub fn drew(&self, gap: u32) -> anyhow::Result<()> {
        let before = self.draws.borrow().len();
        self.step(gap, || {
            if self.draws.borrow().len() > before {
                Ok(())
            } else {
                Err("no draw was made since the previous check (glDrawArrays)".into())
            }
        })
    }

    /// [`Exercise::drew`], the last draw into framebuffer `framebuffer`.
    pub fn drew_into(&self, gap: u32, framebuffer: glow::Framebuffer) -> anyhow::Result<()> {
        self.drew(gap)?;
        self.step(gap, || {
            let last = self.last_draw();
            if last.framebuffer == framebuffer.id() {
                Ok(())
            } else {
                Err(format!(
                    "the draw (call {}) went into framebuffer {}, not framebuffer {} \
                     (glBindFramebuffer before the draw)",
                    last.call,
                    last.framebuffer,
                    framebuffer.id()
                ))
            }
        })
    }

    /// [`Exercise::drew`], the last draw's sampler `sampler` reading `texture`.
    pub fn drew_reading(
        &self,
        gap: u32,
        sampler: &str,
        texture: glow::Texture,
    ) -> anyhow::Result<()> {
        self.drew(gap)?;
        self.step(gap, || {
            let last = self.last_draw();
            match last.samplers.iter().find(|s| s.name == sampler) {
                Some(s) if s.texture == texture.id() => Ok(()),
                Some(s) => Err(format!(
                    "the draw (call {}) read texture {} through {sampler} (unit {}), not \
                     texture {} (glActiveTexture, glBindTexture before the draw)",
                    last.call,
                    s.texture,
                    s.unit,
                    texture.id()
                )),
                None => Err(format!(
                    "the program of the draw (call {}) has no sampler {sampler}",
                    last.call
                )),
            }
        })
    }

    /// The texture the next step reads, `texture`, is the one the last draw wrote (the
    /// ping-pong's swap).
    pub fn reads_what_was_drawn(&self, gap: u32, texture: glow::Texture) -> anyhow::Result<()> {
        self.step(gap, || {
            let last = self.last_draw();
            let written = last.targets.iter().find(|t| t.color).map(|t| t.texture);
            match written {
                Some(w) if w == texture.id() => Ok(()),
                Some(w) => Err(format!(
                    "the next step would read texture {}, but the step just drawn (call {}) \
                     wrote texture {w}: what one step writes, the next reads",
                    texture.id(),
                    last.call
                )),
                None => Err("the last draw wrote no texture".into()),
            }
        })
    }

    /// The framebuffer bound for reading is `framebuffer`.
    pub fn reading_from(&self, gap: u32, framebuffer: glow::Framebuffer) -> anyhow::Result<()> {
        self.step(gap, || match self.door.read_framebuffer() {
            id if id == framebuffer.id() => Ok(()),
            id => Err(format!(
                "glReadPixels reads framebuffer {id}, not framebuffer {} (glBindFramebuffer \
                 with GL_READ_FRAMEBUFFER or GL_FRAMEBUFFER)",
                framebuffer.id()
            )),
        })
    }

    /// `got` (what the program read, `grid`'s values) is `expected`, exactly.
    pub fn same_values(
        &self,
        gap: u32,
        what: &str,
        grid: Grid,
        got: &[f32],
        expected: &[f32],
    ) -> anyhow::Result<()> {
        self.step(gap, || {
            if got.len() != expected.len() {
                return Err(format!(
                    "{what}: {} values, not {}",
                    got.len(),
                    expected.len()
                ));
            }
            let (count, first) = wrong_texels(grid, got, expected, 0.0);
            match first.first() {
                None => Ok(()),
                Some(w) => Err(format!(
                    "{what}: {count} of {} values differ; the first, texel ({}, {}) channel {}: \
                     read {}, the array holds {}",
                    got.len(),
                    w.x,
                    w.y,
                    w.channel,
                    w.gpu,
                    w.cpu
                )),
            }
        })
    }

    /// Run the check of gap `gap`: GL errors raised since the last check, and the draws made
    /// since then, first; then `check`. A failure stops the run.
    fn step(&self, gap: u32, check: impl FnOnce() -> Result<(), String>) -> anyhow::Result<()> {
        let calls = self.door.calls_so_far();
        self.checks.borrow_mut().push((gap, calls));
        let problem = self.errors().or_else(|| self.draw_problem());
        match problem.map_or_else(check, Err) {
            Ok(()) => {
                self.reached.set(self.reached.get().max(gap));
                Ok(())
            }
            Err(problem) => Err(Stop::Step { gap, problem }.into()),
        }
    }

    /// The GL errors raised since the last check, with what they usually mean.
    fn errors(&self) -> Option<String> {
        let errors = self.door.take_errors();
        let first = errors.first()?;
        Some(format!(
            "GL reported {} since the previous check: {}",
            errors.join(", "),
            error_meaning(first)
        ))
    }

    /// The first problem of the draws made since the last check.
    fn draw_problem(&self) -> Option<String> {
        let new = self.door.take_draws();
        let problem = new.iter().find_map(|d| {
            d.problems()
                .first()
                .map(|p| format!("the draw at call {} ({}): {p}", d.call, d.function))
        });
        self.draws.borrow_mut().extend(new);
        problem
    }

    fn last_draw(&self) -> DrawFacts {
        self.draws
            .borrow()
            .last()
            .cloned()
            .expect("checked by drew() first")
    }

    /// A texture's facts, checked to be a float texture of `grid`'s shape that can be sampled.
    fn float_facts(
        &self,
        texture: glow::Texture,
        grid: Grid,
    ) -> Result<crate::gl::learner::TextureFacts, String> {
        let f = self.door.texture(texture)?;
        let formats = ["GL_R32F", "GL_RG32F", "GL_RGB32F", "GL_RGBA32F"];
        let wanted = formats[grid.channels.clamp(1, 4) - 1];
        if f.kind != FormatKind::Float {
            return Err(format!(
                "texture {} is {}: {}; make it {wanted} (glTexImage2D's internal format)",
                f.id,
                f.format,
                match f.kind {
                    FormatKind::Normalized =>
                        "a format that clamps to [0, 1] and keeps 8 or 16 bits",
                    _ => "an integer format, not an array of floats",
                }
            ));
        }
        if f.channels != grid.channels {
            return Err(format!(
                "texture {} is {} ({} channels); this array has {} a texel: {wanted}",
                f.id, f.format, f.channels, grid.channels
            ));
        }
        if (f.width, f.height) != (grid.width, grid.height) {
            return Err(format!(
                "texture {} is {} x {}; the array is {} x {}",
                f.id, f.width, f.height, grid.width, grid.height
            ));
        }
        if let Some(why) = self.door.sampling_incomplete(texture) {
            return Err(why);
        }
        Ok(f)
    }

    /// What the run recorded besides the calls.
    fn into_parts(self) -> Parts {
        let mut draws = self.draws.into_inner();
        draws.extend(self.door.take_draws());
        Parts {
            run: self.run.into_inner(),
            draws,
            readings: self.readings.into_inner(),
            checks: self.checks.into_inner(),
            reached: self.reached.get(),
        }
    }

    /// The lesson's run the checks of this exercise go into.
    pub(crate) fn run_mut(&self) -> std::cell::RefMut<'_, LessonRun> {
        self.run.borrow_mut()
    }

    /// The door, for an exercise's own checks.
    pub(crate) fn door(&self) -> &LearnerGl {
        &self.door
    }

    /// A check of an exercise's own (in its file): errors and draws first, as every check.
    pub(crate) fn check_step(
        &self,
        gap: u32,
        check: impl FnOnce() -> Result<(), String>,
    ) -> anyhow::Result<()> {
        self.step(gap, check)
    }
}

/// What a run recorded besides its calls.
struct Parts {
    run: LessonRun,
    draws: Vec<DrawFacts>,
    readings: Vec<Reading>,
    checks: Vec<(u32, usize)>,
    reached: u32,
}

/// A uniform's value as the messages show it.
fn shown(value: &UniformValue) -> String {
    match value {
        UniformValue::Float(v) => list(v),
        UniformValue::Int(v) => list(v),
        UniformValue::Sampler(u) => format!("texture unit {u}"),
    }
}

fn list<T: fmt::Display>(values: &[T]) -> String {
    let shown: Vec<String> = values.iter().map(|v| v.to_string()).collect();
    match shown.as_slice() {
        [one] => one.clone(),
        _ => format!("({})", shown.join(", ")),
    }
}

/// What a GL error usually means in these exercises.
fn error_meaning(name: &str) -> &'static str {
    match name {
        "GL_INVALID_ENUM" => "an enum argument is not one the call takes (a target, a format)",
        "GL_INVALID_VALUE" => {
            "a number is out of range (a size, a level, a texture unit, an id GL did not make)"
        }
        "GL_INVALID_OPERATION" => {
            "the call is not allowed as things stand: a glUniform with no program in use, a \
             format and type that do not go together, an object of the wrong kind, a draw \
             with no vertex array bound, a read past the end of a pixel buffer"
        }
        "GL_INVALID_FRAMEBUFFER_OPERATION" => {
            "a draw or a read through a framebuffer that is not complete"
        }
        "GL_OUT_OF_MEMORY" => "GL could not allocate what was asked",
        _ => "see the GL reference page of the calls made since the previous check",
    }
}

/// How a run of a program ended.
#[derive(Debug)]
pub enum Outcome {
    /// It returned its result, checked by the lesson (the run holds the checks).
    Ran,
    /// It stopped at a gap or a failed check.
    Stopped(Stop),
    /// The program stopped itself with an error (its own check, a GL object not made).
    Failed(String),
}

/// One run of an exercise's program on a fresh context, traced.
pub struct Attempt {
    pub outcome: Outcome,
    /// The lesson's checks (complete when the outcome is [`Outcome::Ran`]).
    pub run: LessonRun,
    /// Every GL call the program made, in order.
    pub calls: Vec<TracedCall>,
    pub draws: Vec<DrawFacts>,
    pub readings: Vec<Reading>,
    /// Each check made, in order: its gap and how many calls had been recorded by then.
    pub checks: Vec<(u32, usize)>,
    /// The highest gap whose checks passed.
    pub reached: u32,
    /// The GL errors still pending when the program ended (nobody asked glGetError).
    pub errors_left: Vec<String>,
}

impl Attempt {
    /// Every check passed and the program ran to its end.
    pub fn passed(&self) -> bool {
        matches!(self.outcome, Outcome::Ran) && self.run.passed
    }
}

/// A program of a host exercise: the body of its example.
pub type Body = fn(&Exercise) -> anyhow::Result<Vec<f32>>;

/// Run `body` on a fresh context (so that object ids start where the solution's do), every
/// call traced, every draw inspected; then the lesson's checks of what it returned.
pub fn attempt(card: &'static HostExercise, body: Body) -> anyhow::Result<Attempt> {
    let ctx = Context::from_env()?;
    let ex = Exercise::new(card, &ctx)?;
    ctx.trace_start();
    let result = body(&ex);
    let calls = ctx.trace_stop();
    let errors_left = ex.door.take_errors();
    let Parts {
        mut run,
        draws,
        readings,
        checks,
        reached,
    } = ex.into_parts();
    let outcome = match result {
        Ok(values) => {
            (card.check)(&mut run, &values);
            if run.checks.is_empty() {
                run.passed = false;
            }
            Outcome::Ran
        }
        Err(e) => match e.downcast::<Stop>() {
            Ok(stop) => Outcome::Stopped(stop),
            Err(e) => Outcome::Failed(format!("{e:#}")),
        },
    };
    if !matches!(outcome, Outcome::Ran) {
        run.passed = false;
    }
    Ok(Attempt {
        outcome,
        run,
        calls,
        draws,
        readings,
        checks,
        reached,
        errors_left,
    })
}

impl Attempt {
    /// How many of the solution's calls (`reference`) stand beside this run's: all of them
    /// when the run reached its end; else those the solution had made by the same check as the
    /// one this run stopped at (or by the check of the gap it was making).
    pub fn calls_to_compare(&self, reference: &Attempt) -> usize {
        let gap = match &self.outcome {
            Outcome::Ran => return reference.calls.len(),
            Outcome::Stopped(Stop::Step { gap, .. }) => *gap,
            Outcome::Stopped(Stop::Gap(gap)) => *gap,
            Outcome::Failed(_) => self.reached + 1,
        };
        let made = self.checks.iter().filter(|(g, _)| *g == gap).count().max(1);
        reference
            .checks
            .iter()
            .filter(|(g, _)| *g == gap)
            .nth(made - 1)
            .map_or(reference.calls.len(), |&(_, calls)| calls)
    }
}

/// The example's command line.
#[derive(clap::Parser, Debug)]
#[command(about = "A host exercise of classic-gpgpu: fill the gaps with GL calls, run, compare")]
struct Args {
    /// Print a hint and stop: G.K is hint K of gap G (1 the idea, 2 the call, 3 the line);
    /// in the debug hunt, hint K of fault G.
    #[arg(long, value_name = "G.K")]
    hint: Option<String>,
    /// Show every GL call of the run (beside the solution's, nothing folded).
    #[arg(long)]
    trace: bool,
    /// Show the state of each draw: what its program samples, what it draws into, the
    /// viewport, and what is wrong with it.
    #[arg(long)]
    inspect: bool,
}

/// The `main` of a template: hints, or a run of the learner's program (and of the solution,
/// for the trace beside), its messages, and an exit status that says whether it passed.
pub fn main(card: &'static HostExercise, yours: Body, solution: Body) -> ExitCode {
    report(card, yours, Some(solution))
}

/// The `main` of a shipped solution: the same run, with nothing to compare it with.
pub fn solution_main(card: &'static HostExercise, solution: Body) -> ExitCode {
    report(card, solution, None)
}

/// The `main` of the debug hunt (the planted program and its solution alike).
pub fn hunt_main(card: &'static HostExercise, body: Body) -> ExitCode {
    report(card, body, None)
}

fn report(card: &'static HostExercise, yours: Body, solution: Option<Body>) -> ExitCode {
    let args = <Args as clap::Parser>::parse();
    let lines = match &args.hint {
        Some(hint) => hint_lines(card, hint).map(|lines| (lines, true)),
        None if !card.faults.is_empty() => hunt::run_lines(card, yours, args.trace, args.inspect),
        None => run_lines(card, yours, solution, args.trace, args.inspect),
    };
    match lines {
        Ok((lines, passed)) => {
            // A reader that stops early (`| head`) ends the listing, not the program.
            let mut out = std::io::stdout().lock();
            for line in lines {
                if writeln!(out, "{line}").is_err() {
                    break;
                }
            }
            if passed {
                ExitCode::SUCCESS
            } else {
                ExitCode::FAILURE
            }
        }
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

/// Hint `G.K` of a gap (or of a fault, in the hunt), with the command of the next.
pub fn hint_lines(card: &'static HostExercise, hint: &str) -> anyhow::Result<Vec<String>> {
    let parsed = hint
        .split_once('.')
        .and_then(|(g, k)| Some((g.parse::<u32>().ok()?, k.parse::<u32>().ok()?)));
    let (what, count) = if card.faults.is_empty() {
        ("gap", card.gaps.len())
    } else {
        ("fault", card.faults.len())
    };
    let Some((g, k)) = parsed.filter(|&(g, k)| (1..=3).contains(&k) && g >= 1) else {
        anyhow::bail!(
            "--hint {hint}: say which {what} and which hint, as G.K: G a {what} (1 to {count}), \
             K 1 (the idea), 2 (the call) or 3 (the line); e.g. --hint 1.1"
        );
    };
    let (title, hints, region) = if card.faults.is_empty() {
        let gap = card.gap(g).ok_or_else(|| {
            anyhow::anyhow!("--hint {hint}: {} has gaps 1 to {count}", card.example)
        })?;
        (gap.step, gap.hints, format!("gap-{g}"))
    } else {
        let fault = card.faults.iter().find(|f| f.number == g).ok_or_else(|| {
            anyhow::anyhow!("--hint {hint}: {} has faults 1 to {count}", card.example)
        })?;
        (fault.symptom, fault.hints, format!("fault-{g}"))
    };
    let grade = ["the idea", "the call", "the line"][k as usize - 1];
    let mut lines = vec![format!(
        "{} {what} {g} of {count} ({title}), hint {k} of 3 ({grade}):",
        card.example
    )];
    let text = match k {
        1 | 2 => hints[k as usize - 1].to_string(),
        _ => {
            let region = card.solution_region(&region).map_err(anyhow::Error::msg)?;
            format!("the solution's lines ({}):\n{region}", card.solution())
        }
    };
    for paragraph in text.lines() {
        if k == 3 && !paragraph.starts_with("the solution's") {
            lines.push(format!("    {paragraph}"));
        } else {
            lines.extend(
                crate::gl::picture::wrap(paragraph, 90)
                    .into_iter()
                    .map(|l| format!("  {l}")),
            );
        }
    }
    if k < 3 {
        lines.push(format!(
            "next hint: {} -- --hint {g}.{}",
            card.run_command(),
            k + 1
        ));
    }
    Ok(lines)
}

/// A template's run as text: stopped at a gap, stopped by a check, or ran and checked; then
/// its calls beside the solution's. The flag: passed.
fn run_lines(
    card: &'static HostExercise,
    yours: Body,
    solution: Option<Body>,
    full: bool,
    inspect: bool,
) -> anyhow::Result<(Vec<String>, bool)> {
    let reference = match solution {
        Some(body) => {
            let reference = attempt(card, body)?;
            anyhow::ensure!(
                reference.passed(),
                "the shipped solution {} failed on this renderer, so there is nothing to compare \
                 with:\n{}",
                card.solution(),
                outcome_lines(card, &reference).join("\n")
            );
            Some(reference)
        }
        None => None,
    };
    let yours = attempt(card, yours)?;
    let mut lines = vec![format!(
        "host exercise {} ({}, lesson {}) on {}",
        card.example, card.title, card.lesson, yours.run.renderer
    )];
    lines.extend(outcome_lines(card, &yours));
    if inspect {
        lines.extend(inspect_lines(&yours.draws));
    }
    match (&reference, &yours.outcome) {
        (Some(_), Outcome::Stopped(Stop::Gap(_))) if yours.calls.is_empty() => {}
        (Some(reference), Outcome::Stopped(Stop::Gap(_))) => {
            lines.push(beside::so_far(
                &yours.calls,
                &reference.calls,
                &card.solution(),
            ));
        }
        (Some(reference), _) => {
            let compared = yours.calls_to_compare(reference);
            lines.push(String::new());
            if compared < reference.calls.len() {
                lines.push(format!(
                    "(the solution's first {compared} calls: those it makes up to the same check)"
                ));
            }
            lines.extend(beside::lines(
                &yours.calls,
                &reference.calls[..compared],
                &card.solution(),
                full,
            ));
        }
        (None, _) if full => {
            lines.push(String::new());
            lines.extend(crate::gl::trace::lines(&yours.calls));
        }
        (None, _) => lines.push(format!(
            "this is the shipped solution: {} GL calls (--trace lists them)",
            yours.calls.len()
        )),
    }
    Ok((lines, yours.passed()))
}

/// What stopped a run, or its checks, with the hint to take next.
pub fn outcome_lines(card: &'static HostExercise, attempt: &Attempt) -> Vec<String> {
    let count = card.gaps.len();
    let more = |g: u32| {
        format!(
            "more: {} -- --hint {g}.2 (then {g}.3; the solution: {})",
            card.run_command(),
            card.solution()
        )
    };
    let mut lines = Vec::new();
    match &attempt.outcome {
        Outcome::Stopped(Stop::Gap(n)) => {
            let step = card.gap(*n).map_or("", |g| g.step);
            lines.push(format!("gap {n} of {count} is not filled: {step}"));
            lines.push(format!(
                "  in {}, under the comment `// Gap {n}.`, replace the line `ex.gap({n})?` (or \
                 `ex.gap_value({n})?`) with your code, its GL calls made on `gl`; a hint: {} -- \
                 --hint {n}.1",
                card.template(),
                card.run_command()
            ));
        }
        Outcome::Stopped(Stop::Step { gap, problem }) => {
            let step = card.gap(*gap).map_or("", |g| g.step);
            lines.push(format!(
                "gap {gap} of {count} ({step}) is filled, but wrong:"
            ));
            lines.extend(
                crate::gl::picture::wrap(problem, 90)
                    .into_iter()
                    .map(|l| format!("  {l}")),
            );
            if let Some(g) = card.gap(*gap) {
                lines.push(format!("hint 1 of 3 (gap {gap}): {}", g.hints[0]));
                lines.push(more(*gap));
            }
        }
        Outcome::Failed(error) => {
            lines.push(format!(
                "your program stopped with an error after gap {} of {count} had passed its \
                 checks:",
                attempt.reached
            ));
            lines.push(format!("  {error}"));
            let next = attempt.reached + 1;
            if card.gap(next).is_some() {
                lines.push(format!(
                    "  the step being made was gap {next}: a hint: {} -- --hint {next}.1",
                    card.run_command()
                ));
            }
        }
        Outcome::Ran => {
            lines.extend(check_lines(&attempt.run));
            lines.push(if attempt.run.passed {
                format!(
                    "passed: every gap filled, the result is the CPU's (largest error {:.3e})",
                    attempt.run.max_error
                )
            } else {
                "FAILED: the program ran to its end, but its result is not the CPU's; the first \
                 difference of your calls from the solution's (below) is the place to look"
                    .into()
            });
        }
    }
    lines
}

/// A run's checks: verdict, error, tolerance, and where a failed one went wrong.
pub(crate) fn check_lines(run: &LessonRun) -> Vec<String> {
    let mut lines = Vec::new();
    for check in &run.checks {
        lines.push(format!(
            "  {} {}: error {:.3e} (tolerance {:.3e})",
            if check.passed { "ok  " } else { "FAIL" },
            check.what,
            check.max_error,
            check.tolerance
        ));
        if !check.passed {
            let wrong = check.where_wrong();
            if wrong.is_empty() && check.max_error.is_infinite() {
                lines.push(
                    "       the values returned are not the array's: another count of values \
                     (a format with more channels than the array's?), or one that is not finite"
                        .into(),
                );
            }
            lines.extend(wrong.into_iter().map(|l| format!("       {l}")));
        }
    }
    lines
}

/// `--inspect`: each draw's state and problems.
pub(crate) fn inspect_lines(draws: &[DrawFacts]) -> Vec<String> {
    let mut lines = vec![format!("the state of each draw ({}):", draws.len())];
    for d in draws {
        let v = d.viewport;
        let samples: Vec<String> = d
            .samplers
            .iter()
            .map(|s| format!("{} <- unit {} (texture {})", s.name, s.unit, s.texture))
            .collect();
        let writes: Vec<String> = d
            .targets
            .iter()
            .map(|t| {
                format!(
                    "{} = texture {} ({} x {}, {})",
                    t.attachment, t.texture, t.width, t.height, t.format
                )
            })
            .collect();
        lines.push(format!(
            "  call {} {}: program {}, framebuffer {}, viewport {}, {}, {} x {}; samples [{}]; \
             draws into [{}]",
            d.call,
            d.function,
            d.program,
            d.framebuffer,
            v[0],
            v[1],
            v[2],
            v[3],
            samples.join(", "),
            writes.join(", ")
        ));
        for p in d.problems() {
            lines.push(format!("      problem: {p}"));
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_card_names_a_lesson_and_numbers_its_gaps_from_one() {
        for card in all() {
            assert!(super::super::find(card.lesson).is_ok(), "{}", card.lesson);
            for (k, gap) in card.gaps.iter().enumerate() {
                assert_eq!(gap.number, k as u32 + 1, "{}", card.example);
                assert!(gap.step.ends_with(')'), "{}: {}", card.example, gap.step);
            }
            for (k, fault) in card.faults.iter().enumerate() {
                assert_eq!(fault.number, k as u32 + 1, "{}", card.example);
            }
            assert!(card.gaps.is_empty() != card.faults.is_empty());
            assert_eq!(
                card.solution_file,
                format!("examples/{}-solution.rs", card.example)
            );
        }
    }

    #[test]
    fn every_gap_and_fault_has_its_region_in_the_solution() {
        for card in all() {
            for gap in card.gaps {
                let region = card.solution_region(&format!("gap-{}", gap.number));
                assert!(region.is_ok(), "{}: {region:?}", card.example);
            }
            for fault in card.faults {
                let region = card.solution_region(&format!("fault-{}", fault.number));
                assert!(region.is_ok(), "{}: {region:?}", card.example);
            }
        }
    }

    #[test]
    fn hints_are_graded_and_the_third_is_the_solutions_lines() {
        let idea = hint_lines(&saxpy::CARD, "3.1").unwrap();
        assert!(idea[0].contains("gap 3 of 7") && idea[0].contains("the idea"));
        assert!(idea.last().unwrap().contains("--hint 3.2"));
        let line = hint_lines(&saxpy::CARD, "3.3").unwrap().join("\n");
        assert!(line.contains("gl.link_program"), "{line}");
        for bad in ["3", "9.1", "1.4", "x.y"] {
            let e = hint_lines(&saxpy::CARD, bad).unwrap_err().to_string();
            assert!(e.contains(&format!("--hint {bad}")), "{e}");
        }
    }
}
