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

pub mod compute_reduction;
pub mod count_and_mask;
pub mod depth_peeling;
pub mod guide;
mod kit;
pub mod readback_and_upload;
pub mod render_to_vertex_buffer;

use crate::gl::Context;
use serde::Serialize;
use std::path::PathBuf;

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
    /// Shown when the learner's shader fails the check.
    pub hint: &'static str,
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
    /// The hint of the exercise that was run, when it failed.
    pub hint: Option<String>,
}

impl LessonRun {
    /// An empty run of `info` on `ctx`, to be filled pass by pass.
    pub fn new(info: &LessonInfo, ctx: &Context) -> LessonRun {
        LessonRun {
            id: info.id.into(),
            title: info.title.into(),
            renderer: ctx.info().renderer_line(),
            passes: Vec::new(),
            checks: Vec::new(),
            passed: true,
            max_error: 0.0,
            shaders: Vec::new(),
            notes: Vec::new(),
            compute: None,
            hint: None,
        }
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
        });
    }
}

/// A lesson: its card and how to run it.
pub trait Lesson {
    fn info(&self) -> &'static LessonInfo;
    /// Run the lesson on `ctx`: every pass, every check against the CPU reference.
    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun>;
}

/// Every lesson, in teaching order.
pub fn all() -> Vec<&'static dyn Lesson> {
    vec![
        &count_and_mask::CountAndMask,
        &depth_peeling::DepthPeeling,
        &readback_and_upload::ReadbackAndUpload,
        &render_to_vertex_buffer::RenderToVertexBuffer,
        &compute_reduction::ComputeReduction,
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
