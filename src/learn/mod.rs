//! The lessons of the basic approach, in order: from "a texture is an array" to the building
//! blocks each paper is made of (the tutorial's programme, items 2 and 3: the basic GPGPU
//! approach and its pitfalls, and development tips).
//!
//! Each lesson is one file: a small complete GPGPU program with a CPU reference, a check with a
//! stated tolerance, the step of a paper that uses the same idea (module and file), and a
//! compute-shader counterpart where OpenGL 4.3 is there. Its shaders live under `glsl/learn/`.
//!
//! Exercises: an exercise names one shader file of its lesson, `glsl/learn/X`, whose shipped
//! text is the solution; the template the learner fills is `glsl/learn/exercises/X` (the same
//! file with a marked gap). `classic-gpgpu glsl export DIR --exercises` writes the templates at
//! `DIR/glsl/learn/X`, and `learn <id> --exercise N --glsl-dir DIR` runs the lesson with the
//! learner's file in place of the solution ([`crate::gl::Context::set_glsl_dir`]).
//!
//! A lesson is a [`Lesson`]; [`all`] lists them in teaching order.
//!
//! The course's pages live here too, beside the lessons they show: the offline guide
//! ([`guide`]: a page per lesson, made by running it, with the reduction ladder's section),
//! the papers walked pass by pass ([`walks`]), and the named regions of the files that both
//! cut their code from ([`regions`]). They are written with the page layer ([`crate::page`]).
//!
//! Host exercises ([`host`]): for lessons 1, 2, 3 and 8, an example of the crate in which the
//! learner writes the host side's GL calls with glow (textures, framebuffer, program, viewport,
//! draw, swap, readback), and for lesson 11 a program with faults planted to hunt down.

// One file per lesson ([`all`] lists them in teaching order), and `kit`: what several share.
pub mod bench;
mod compute_reduction;
mod count_and_mask;
mod debugging;
mod depth_peeling;
mod feedback;
mod histogram_pyramid;
mod kit;
pub mod ladder;
mod ping_pong;
mod quad_is_loop;
mod readback_and_upload;
mod reduction;
mod render_to_vertex_buffer;
mod scatter_and_blend;
mod several_outputs;
mod texture_is_array;

// The lessons' pages: the guide (a page per lesson, the ladder's section), the papers walked
// pass by pass, and the named regions of the files that both show.
pub mod guide;
pub mod regions;
pub mod walks;

// The host exercises: programs in `examples/` whose GL calls the learner writes, checked step
// by step, their calls beside the solution's; and the debugging lesson's hunt.
pub mod host;

use crate::gl::picture::{self, Panel, Scale};
use crate::gl::Context;
pub use feedback::{Grid, WrongTexel, FIRST_WRONG};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// How often a lesson times a path in its own run (not `--bench`), after one untimed warm-up
/// run: its explanation quotes the median of these, never one cold sample.
pub const LESSON_RUNS: usize = 5;

/// A paper step that uses the lesson's idea: where to read next.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct PaperStep {
    /// "Paper 4, section 3.3" or "Lecture 3, image pyramid".
    pub paper: &'static str,
    /// The step in the paper's words ("sum of the integrands by reduction").
    pub step: &'static str,
    /// The file that implements it, e.g. `src/mass/reduce.rs`.
    pub file: &'static str,
}

/// One exercise: a shader with a marked gap.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Exercise {
    /// 1, 2, ... within the lesson.
    pub number: u32,
    /// What to do, in a sentence or two.
    pub task: &'static str,
    /// The solution's path, `glsl/learn/X`; the template is `glsl/learn/exercises/X`.
    pub shader: &'static str,
    /// Three hints, each closer to the answer (`learn <id> --hint 1`, `2`, `3`): the idea,
    /// the formula, the line. The first is shown when the learner's shader fails the check.
    pub hints: [&'static str; 3],
}

/// What `learn --list` shows of a lesson.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct LessonInfo {
    /// The id `learn <id>` takes, e.g. `texture-is-array`.
    pub id: &'static str,
    /// 0, 1, 2, ... the teaching order.
    pub number: u32,
    pub title: &'static str,
    /// The idea, a short paragraph.
    pub idea: &'static str,
    /// The paper steps that use the same idea.
    pub paper_steps: &'static [PaperStep],
    /// Every shader file the lesson runs (its compute counterpart's too).
    pub shaders: &'static [&'static str],
    pub exercises: &'static [Exercise],
}

/// How a lesson is run.
#[derive(Clone, Debug, Default)]
pub struct LessonOptions {
    /// Write each pass's buffer as a PNG (and `.npy` for float buffers) here.
    pub png_dir: Option<PathBuf>,
    /// Run exercise N's shader (the learner's, through `--glsl-dir`, or the shipped solution)
    /// instead of the lesson's own.
    pub exercise: Option<u32>,
}

/// One pass as the lesson explains it.
#[derive(Clone, Debug, Serialize)]
pub struct PassNote {
    /// The pass, e.g. "level 1: 4x4 -> 2x2".
    pub name: String,
    /// The shader file it runs (empty for an upload or readback).
    pub shader: String,
    /// What the pass does, in a sentence.
    pub what: String,
    /// The picture of its output, relative to the PNG folder, when one was written.
    pub picture: Option<String>,
}

/// One comparison with the CPU reference.
#[derive(Clone, Debug, Serialize)]
pub struct Check {
    pub what: String,
    pub max_error: f64,
    pub tolerance: f64,
    pub passed: bool,
    /// For a check made texel by texel ([`LessonRun::check_texels`]): how many values are off
    /// by more than the tolerance.
    pub wrong: Option<usize>,
    /// The first few of them, with the GPU's value and the CPU's.
    pub first_wrong: Vec<WrongTexel>,
    /// What one cell of the checked grid is: "texel", "pixel", "block", "work group", "slot".
    pub unit: &'static str,
    /// The index in [`LessonRun::buffers`] of the buffer it checked (`view learn <id>
    /// --buffer K` shows it), when a pass recorded it.
    pub buffer: Option<usize>,
    /// The difference picture written for a failed check, relative to the PNG folder.
    pub difference_picture: Option<String>,
    /// GPU - CPU for a failed check made texel by texel (not in the JSON: the picture is).
    #[serde(skip)]
    pub difference: Option<PassBuffer>,
}

/// What running a lesson gives: its passes, its checks against the CPU, and the verdict.
#[derive(Clone, Debug, Serialize)]
pub struct LessonRun {
    pub id: String,
    pub title: String,
    /// "llvmpipe ... via egl-surfaceless, OpenGL 4.5".
    pub renderer: String,
    pub passes: Vec<PassNote>,
    pub checks: Vec<Check>,
    /// Every check passed.
    pub passed: bool,
    /// The largest error over the checks (each is also in `checks`).
    pub max_error: f64,
    /// The shader files that ran.
    pub shaders: Vec<String>,
    /// Facts the lesson measured that are not checks (bits kept by a format, bytes read back,
    /// a timing with its renderer): name and value as text.
    pub notes: Vec<(String, String)>,
    /// Whether the compute counterpart ran (false without OpenGL 4.3, and why).
    pub compute: Option<String>,
    /// The first hint of the exercise that was run, when it failed.
    pub hint: Option<String>,
    /// The number of that exercise (its further hints: `learn <id> --exercise N --hint 2`).
    pub hint_exercise: Option<u32>,
    /// With `--exercise N`: whose shader ran, the learner's file (from `--glsl-dir`) or the
    /// shipped solution, in a sentence.
    pub exercise_ran: Option<String>,
    /// The buffers the passes wrote, as read back (what `--png` writes and `view learn`
    /// shows); not in the JSON, whose passes name the pictures instead.
    #[serde(skip)]
    pub buffers: Vec<PassBuffer>,
}

/// A buffer one pass wrote, read back: rows from the bottom, `channels` values per texel.
#[derive(Clone, Debug)]
pub struct PassBuffer {
    /// The index of its pass in [`LessonRun::passes`].
    pub pass: usize,
    /// The file stem its pictures get, e.g. `3-level-2`.
    pub stem: String,
    pub width: u32,
    pub height: u32,
    pub channels: usize,
    pub values: Vec<f32>,
    /// A float buffer (also written as `.npy`); false for a byte format read as 0..1.
    pub float: bool,
    /// The set of related buffers it shares one colour scale with (all levels of a
    /// reduction, all steps of a ping-pong); empty: a set of its own.
    pub set: &'static str,
    /// What the CPU reference computes for the same texels, where the lesson has it per
    /// texel: the viewer's probe shows it beside the GPU's value.
    pub reference: Option<Vec<f32>>,
    /// What each channel holds, for the panel titles (empty: "channel 0", ...).
    pub channel_names: &'static [&'static str],
}

impl PassBuffer {
    /// A float buffer of `width x height` texels of `channels` values each.
    pub fn floats(width: u32, height: u32, channels: usize, values: Vec<f32>) -> PassBuffer {
        PassBuffer {
            pass: 0,
            stem: String::new(),
            width,
            height,
            channels,
            values,
            float: true,
            set: "",
            reference: None,
            channel_names: &[],
        }
    }

    /// A byte buffer (`channels` bytes per texel), as 0..1.
    pub fn bytes(width: u32, height: u32, channels: usize, bytes: &[u8]) -> PassBuffer {
        let values = bytes.iter().map(|&b| b as f32 / 255.0).collect();
        PassBuffer {
            float: false,
            ..PassBuffer::floats(width, height, channels, values)
        }
    }

    /// The same buffer, sharing its colour scale with the other buffers of `set`.
    pub fn in_set(self, set: &'static str) -> PassBuffer {
        PassBuffer { set, ..self }
    }

    /// The same buffer, its channels named.
    pub fn named(self, channel_names: &'static [&'static str]) -> PassBuffer {
        PassBuffer {
            channel_names,
            ..self
        }
    }

    /// The same buffer, with the CPU reference's values of its texels.
    pub fn with_reference(self, reference: Vec<f32>) -> PassBuffer {
        PassBuffer {
            reference: Some(reference),
            ..self
        }
    }

    /// Channel `c`'s values.
    fn channel(&self, c: usize) -> impl Iterator<Item = f32> + '_ {
        self.values.iter().skip(c).step_by(self.channels).copied()
    }
}

/// The size of the picture of a `width x height` buffer with `channels` panels: small
/// buffers enlarged (nearest texel) to about 256 pixels a panel, with room for titles and
/// keys; a one-row strip gets a quarter of that in height.
fn picture_size(width: u32, height: u32, channels: usize) -> (u32, u32) {
    let longer = width.max(height).max(1);
    let side = longer.clamp(256, 512);
    let panel_w = side * width / longer;
    let panel_h = (side * height / longer).max(side / 4);
    let columns = channels.clamp(1, 4) as u32;
    let rows = (channels.max(1) as u32).div_ceil(columns);
    ((panel_w * columns).max(256), (panel_h + 48) * rows)
}

impl LessonRun {
    /// An empty run of `info` on `ctx`, to be filled pass by pass.
    pub fn new(info: &LessonInfo, ctx: &Context) -> LessonRun {
        LessonRun::named(info.id, info.title, ctx.info().renderer_line())
    }

    /// An empty run called `id` and `title`, on `renderer`.
    fn named(id: &str, title: &str, renderer: String) -> LessonRun {
        LessonRun {
            id: id.into(),
            title: title.into(),
            renderer,
            passes: Vec::new(),
            checks: Vec::new(),
            passed: true,
            max_error: 0.0,
            shaders: Vec::new(),
            notes: Vec::new(),
            compute: None,
            hint: None,
            hint_exercise: None,
            exercise_ran: None,
            buffers: Vec::new(),
        }
    }

    /// Record one pass: its note, the shader it ran (once in `shaders`), and the buffer it
    /// wrote when there is one to look at.
    pub fn pass(&mut self, name: &str, shader: &str, what: &str, buffer: Option<PassBuffer>) {
        let index = self.passes.len();
        self.passes.push(PassNote {
            name: name.into(),
            shader: shader.into(),
            what: what.into(),
            picture: None,
        });
        if !shader.is_empty() && !self.shaders.iter().any(|s| s == shader) {
            self.shaders.push(shader.into());
        }
        if let Some(mut buffer) = buffer {
            buffer.pass = index;
            buffer.stem = format!("{index}-{}", file_stem(name));
            self.buffers.push(buffer);
        }
    }

    /// Record a measured fact that is not a check.
    pub fn note(&mut self, name: &str, value: impl Into<String>) {
        self.notes.push((name.into(), value.into()));
    }

    /// Finish a run: the exercise's hint when a check failed, and the pictures when
    /// `opts.png_dir` asks for them (overwriting: the command line checks its folder first).
    pub fn finish(
        &mut self,
        info: &LessonInfo,
        ctx: &Context,
        opts: &LessonOptions,
    ) -> anyhow::Result<()> {
        // A run that checked nothing has shown nothing.
        if self.checks.is_empty() {
            self.passed = false;
        }
        if !self.passed {
            let exercise = failed_exercise(info, ctx, opts);
            self.hint = exercise.map(|e| e.hints[0].to_string());
            self.hint_exercise = exercise.map(|e| e.number);
        }
        self.exercise_ran = exercise_ran(info, ctx, opts);
        match &opts.png_dir {
            Some(dir) => self.write_pictures(dir),
            None => Ok(()),
        }
    }

    /// The files [`LessonRun::write_pictures`] writes into `dir`.
    pub fn picture_files(&self, dir: &Path) -> Vec<PathBuf> {
        let mut files = Vec::new();
        for b in &self.buffers {
            files.push(dir.join(format!("{}.png", b.stem)));
            if b.float {
                files.push(dir.join(format!("{}.npy", b.stem)));
            }
        }
        for (k, c) in self.checks.iter().enumerate() {
            if c.difference.is_some() {
                files.push(dir.join(LessonRun::difference_file(k)));
            }
        }
        files
    }

    /// Write each pass's buffer as `DIR/<pass>-<name>.png` (and `.npy` for float buffers),
    /// and name the picture in its pass's note.
    pub fn write_pictures(&mut self, dir: &Path) -> anyhow::Result<()> {
        for i in 0..self.buffers.len() {
            let b = &self.buffers[i];
            let (png, npy) = (format!("{}.png", b.stem), format!("{}.npy", b.stem));
            if b.float {
                let shape = [b.height as usize, b.width as usize, b.channels];
                crate::files::write_npy(&dir.join(npy), &shape, &b.values)?;
            }
            let image = image::DynamicImage::ImageRgba8(self.picture(i));
            crate::files::write_image(&dir.join(&png), &image)?;
            let pass = self.buffers[i].pass;
            self.passes[pass].picture = Some(png);
        }
        // A failed check made texel by texel: its difference GPU - CPU, with its key.
        for k in 0..self.checks.len() {
            let Some(d) = &self.checks[k].difference else {
                continue;
            };
            let size = picture::legible_size(picture_size(d.width, d.height, d.channels));
            let panels = self.checks[k].difference_panels();
            let image = image::DynamicImage::ImageRgba8(picture::picture(&panels, size).0);
            let png = LessonRun::difference_file(k);
            crate::files::write_image(&dir.join(&png), &image)?;
            self.checks[k].difference_picture = Some(png);
        }
        Ok(())
    }

    /// Buffer `i` as panels, one per channel, as `gl::dump` states the mapping: a float
    /// channel on one scale over the same channel of every buffer of its set, bytes on 0..1.
    pub fn panels(&self, i: usize) -> Vec<Panel> {
        let b = &self.buffers[i];
        let set: Vec<&PassBuffer> = if b.set.is_empty() {
            vec![b]
        } else {
            let same = |o: &&PassBuffer| o.set == b.set && o.channels == b.channels;
            self.buffers.iter().filter(same).collect()
        };
        let name = &self.passes[b.pass].name;
        (0..b.channels)
            .map(|c| {
                let scale = if b.float {
                    let values: Vec<Vec<f32>> =
                        set.iter().map(|m| m.channel(c).collect()).collect();
                    Scale::of(values.iter().map(Vec::as_slice))
                } else {
                    Scale::fixed(0.0, 1.0)
                };
                let title = match (b.channel_names.get(c), b.channels) {
                    (Some(channel), _) => format!("{name}: {channel}"),
                    (None, 1) => name.clone(),
                    (None, _) => format!("{name}: channel {c}"),
                };
                Panel::channel(title, &b.values, b.channels, c, (b.width, b.height), scale)
            })
            .collect()
    }

    /// Buffer `i`'s picture: its panels with titles and colour keys.
    pub fn picture(&self, i: usize) -> image::RgbaImage {
        let b = &self.buffers[i];
        let size = picture::legible_size(picture_size(b.width, b.height, b.channels));
        picture::picture(&self.panels(i), size).0
    }

    /// Record a comparison: passes when `max_error <= tolerance` (and is finite).
    pub fn check(&mut self, what: &str, max_error: f64, tolerance: f64) {
        let passed = max_error.is_finite() && max_error <= tolerance;
        self.passed &= passed;
        if max_error.is_finite() {
            self.max_error = self.max_error.max(max_error);
        } else {
            self.max_error = f64::INFINITY;
        }
        self.checks.push(Check {
            what: what.into(),
            max_error,
            tolerance,
            passed,
            wrong: None,
            first_wrong: Vec::new(),
            unit: "texel",
            buffer: None,
            difference_picture: None,
            difference: None,
        });
    }
}

/// A lesson: its card and how to run it.
pub trait Lesson {
    fn info(&self) -> &'static LessonInfo;
    /// Run the lesson on `ctx`: every pass, every check against the CPU reference.
    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun>;
    /// A lesson that iterates (ping-pong), started on `ctx` at iteration 0, for the viewer's
    /// live loop to advance a step at a time; `None` for a lesson that runs once.
    fn iteration(
        &self,
        _ctx: &Context,
        _opts: &LessonOptions,
    ) -> anyhow::Result<Option<Box<dyn Iteration>>> {
        Ok(None)
    }
}

/// A lesson that iterates, held between iterations: its textures keep the current iterate, so
/// that one more iteration is one more pass (`view learn`'s step), not the lesson run again
/// from the start.
pub trait Iteration {
    /// Iterations run so far.
    fn iterations(&self) -> u32;
    /// `steps` more iterations, from the current iterate (fewer once it has stopped).
    fn advance(&mut self, steps: u32) -> anyhow::Result<()>;
    /// Why the iterations have stopped, once they have (the iterate reached a fixed point):
    /// from then on [`Iteration::advance`] changes nothing.
    fn stopped(&self) -> Option<String> {
        None
    }
    /// The run as it stands, as `learn <id>` records it after this many iterations, and the
    /// lesson's buffers as the viewer numbers them.
    fn record(&self) -> anyhow::Result<(LessonRun, Vec<Slot>)>;
}

/// One buffer of a lesson that iterates as the viewer numbers it. The list is the same at
/// every iteration and in the order `learn <id>` records its buffers, so that a number (`view
/// learn <id> --buffer K`, as a failed check names it) means the same buffer at any iteration.
#[derive(Clone, Debug, PartialEq)]
pub struct Slot {
    /// What it holds, e.g. "step 2" or "step 7 (the latest)".
    pub name: String,
    /// Its index in [`LessonRun::buffers`] of the run as it stands; `None` before the
    /// iteration that makes it.
    pub buffer: Option<usize>,
    /// It changes with each iteration (the viewer opens on the first that does).
    pub changes: bool,
}

impl Slot {
    /// Each buffer of `run` in its own slot: a lesson that runs once.
    pub fn each(run: &LessonRun) -> Vec<Slot> {
        run.buffers
            .iter()
            .enumerate()
            .map(|(i, b)| Slot {
                name: run.passes[b.pass].name.clone(),
                buffer: Some(i),
                changes: false,
            })
            .collect()
    }
}

/// The exercise `opts.exercise` names, or an error listing the lesson's exercises.
pub fn chosen_exercise(
    info: &LessonInfo,
    opts: &LessonOptions,
) -> anyhow::Result<Option<&'static Exercise>> {
    let Some(n) = opts.exercise else {
        return Ok(None);
    };
    match info.exercises.iter().find(|e| e.number == n) {
        Some(e) => Ok(Some(e)),
        None => {
            let numbers: Vec<String> = info
                .exercises
                .iter()
                .map(|e| e.number.to_string())
                .collect();
            anyhow::bail!(
                "--exercise {n}: lesson {} has exercise{} {}",
                info.id,
                if numbers.len() == 1 { "" } else { "s" },
                numbers.join(", ")
            )
        }
    }
}

/// The exercise whose hint a failed run shows: the one run with `--exercise`, else the
/// first whose shader the `--glsl-dir` folder replaces, else the lesson's first.
fn failed_exercise(
    info: &LessonInfo,
    ctx: &Context,
    opts: &LessonOptions,
) -> Option<&'static Exercise> {
    if let Some(n) = opts.exercise {
        return info.exercises.iter().find(|e| e.number == n);
    }
    let replaced = |e: &&Exercise| {
        ctx.glsl_dir()
            .is_some_and(|dir| dir.join(e.shader).is_file())
    };
    info.exercises
        .iter()
        .find(replaced)
        .or(info.exercises.first())
}

/// With `--exercise N`, whose shader ran: the learner's file in the `--glsl-dir` folder, or
/// the shipped solution.
fn exercise_ran(info: &LessonInfo, ctx: &Context, opts: &LessonOptions) -> Option<String> {
    let e = info
        .exercises
        .iter()
        .find(|e| Some(e.number) == opts.exercise)?;
    let yours = ctx.glsl_dir().map(|dir| dir.join(e.shader));
    Some(match yours.filter(|p| p.is_file()) {
        Some(path) => format!("exercise {}: ran your file {}", e.number, path.display()),
        None => format!(
            "exercise {}: ran the shipped solution {} (yours runs with --glsl-dir DIR once DIR/{} \
             exists: `classic-gpgpu glsl export DIR --exercises`)",
            e.number, e.shader, e.shader
        ),
    })
}

/// A pass name as a file name: lower case, words joined by `-`.
fn file_stem(name: &str) -> String {
    let mut stem = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            stem.push(c.to_ascii_lowercase());
        } else if !stem.ends_with('-') && !stem.is_empty() {
            stem.push('-');
        }
    }
    stem.trim_end_matches('-').to_string()
}

/// The exercise templates of the lessons (`glsl/learn/exercises/X`): every file the shader
/// registry has there, so a new template needs no list.
pub fn templates() -> Vec<crate::gl::ShaderSource<'static>> {
    crate::gl::shaders::ALL
        .iter()
        .filter(|s| s.name.starts_with(crate::gl::shaders::EXERCISES))
        .copied()
        .collect()
}

/// Every lesson, in teaching order.
pub fn all() -> Vec<&'static dyn Lesson> {
    vec![
        &texture_is_array::TextureIsArray,
        &quad_is_loop::QuadIsLoop,
        &ping_pong::PingPong,
        &reduction::Reduction,
        &several_outputs::SeveralOutputs,
        &scatter_and_blend::ScatterAndBlend,
        &count_and_mask::CountAndMask,
        &depth_peeling::DepthPeeling,
        &readback_and_upload::ReadbackAndUpload,
        &render_to_vertex_buffer::RenderToVertexBuffer,
        &compute_reduction::ComputeReduction,
        &debugging::Debugging,
    ]
}

/// The lesson `id` (or its number), or an error listing the ids.
pub fn find(id: &str) -> anyhow::Result<&'static dyn Lesson> {
    let lessons = all();
    lessons
        .iter()
        .find(|l| l.info().id == id || l.info().number.to_string() == id)
        .copied()
        .ok_or_else(|| {
            let ids: Vec<&str> = lessons.iter().map(|l| l.info().id).collect();
            anyhow::anyhow!("no lesson '{id}'; the lessons are: {}", ids.join(", "))
        })
}

/// Why a lesson's compute counterpart cannot run here, or `None` when it can (OpenGL 4.3).
pub(crate) fn no_compute(ctx: &Context) -> Option<String> {
    let (major, minor) = ctx.info().gl_version;
    (!ctx.has_compute()).then(|| {
        format!("not run: this context is OpenGL {major}.{minor}; compute shaders need 4.3")
    })
}

/// The largest `|a[i] - b[i]|`, infinite when a value is not finite or the lengths differ.
pub(crate) fn max_difference(a: &[f32], b: &[f32]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    a.iter()
        .zip(b)
        .map(|(&x, &y)| (x as f64 - y as f64).abs())
        .fold(
            0.0,
            |m: f64, d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
        )
}

/// `n` values drawn uniformly from `[lo, hi)` by a seeded generator: the same data each run.
pub(crate) fn random_values(n: usize, seed: u64, lo: f32, hi: f32) -> Vec<f32> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| rng.gen_range(lo..hi)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run_of(buffers: Vec<PassBuffer>) -> LessonRun {
        let mut run = LessonRun::named("test", "test", String::new());
        for (k, b) in buffers.into_iter().enumerate() {
            run.pass(&format!("pass {k}"), "", "", Some(b));
        }
        run
    }

    #[test]
    fn a_set_shares_one_scale_per_channel_and_zero_is_neutral() {
        let run = run_of(vec![
            PassBuffer::floats(2, 1, 2, vec![0.0, 1.0, 2.0, -1.0]).in_set("levels"),
            PassBuffer::floats(1, 1, 2, vec![8.0, 0.5]).in_set("levels"),
            PassBuffer::floats(2, 1, 1, vec![0.0, 3.0]),
        ]);
        let (first, second, alone) = (run.panels(0), run.panels(1), run.panels(2));
        assert_eq!(first.len(), 2);
        // Channel 0 over both levels: 0..8; channel 1 signed: -1..1.
        assert_eq!(first[0].scale, second[0].scale);
        assert_eq!(first[0].scale.hi, 8.0);
        assert_eq!(first[1].scale, second[1].scale);
        assert!(first[1].scale.is_signed());
        // A buffer of no set keeps its own scale.
        assert_eq!(alone[0].scale.hi, 3.0);
        assert_eq!(alone[0].scale.colour(0.0), picture::NEUTRAL);
        // Bytes are on 0..1 whatever they hold.
        let bytes = run_of(vec![PassBuffer::bytes(2, 1, 1, &[0, 128])]);
        assert_eq!(bytes.panels(0)[0].scale, Scale::fixed(0.0, 1.0));
    }

    #[test]
    fn small_buffers_are_enlarged_and_strips_get_height() {
        assert_eq!(picture_size(8, 8, 1), (256, 304));
        let (w, h) = picture_size(256, 1, 1);
        assert!(w >= 256 && h >= 64 + 48, "{w}x{h}");
        let (w, _) = picture_size(24, 20, 2);
        assert_eq!(w, 512);
    }
}
