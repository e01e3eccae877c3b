//! The debugging lesson's exercise (issue 51, item 4): a hunt. `examples/debug-hunt.rs` runs
//! lesson 2's Jacobi steps with the GL calls written out, times one step as a benchmark does
//! (the same draw made [`REPEATS`] times, the time divided), and reads the grid back; four
//! faults are planted in it. The lesson (`learn debugging`) shows seven faults found by
//! the project's tools and fixed; here the learner does the finding and the fixing, in host
//! code, with the same kind of tools: the texel-by-texel comparison with the CPU, the GL call
//! trace (`-- --trace`, the stopwatch's start and reading marked among the calls), the state of
//! each draw (`-- --inspect`) and the GL errors left pending.
//!
//! 1. a time taken without waiting for the GPU (no `glFinish`, no timer query): the calls
//!    return when the work is queued, so the stopwatch stops before the steps are done;
//! 2. a texture read while it is the target being drawn (a feedback loop, the lesson's fault
//!    3, now in the learner's own pairing of textures and framebuffers);
//! 3. a target whose format clamps (`GL_RGBA8` for floats, the lesson's fault 2, now one
//!    argument of `glTexImage2D`);
//! 4. a uniform set before its program is in use: GL raises `GL_INVALID_OPERATION`, the
//!    uniform keeps its old value, and the boundary of the grid is no longer held.
//!
//! Each fault is checked by what it leaves behind, not by the result alone (two of them spoil
//! the same grid): the trace between the stopwatch's start and reading, the state of each draw
//! as [`crate::gl::learner`] inspects it, the program in use at each `glUniform`. The run
//! passes when every fault is fixed and the grid is the CPU's.

use super::{Attempt, Body, Gap, HostExercise, Outcome};
use crate::gl::learner::DrawProblem;
use crate::gl::trace::TracedCall;
use crate::learn::ping_pong::{initial_grid, jacobi_cpu, tolerance};
use crate::learn::{Grid, LessonRun};
use serde::Serialize;

/// A planted fault: what the learner sees, two hints (the third is the solution's region
/// `fault-N`), and the check that says whether it is still there.
#[derive(Debug, Serialize)]
pub struct Fault {
    pub number: u32,
    /// What the learner can see of it, without its cause.
    pub symptom: &'static str,
    /// The idea, then the tool and the call.
    #[serde(skip)]
    pub hints: [&'static str; 2],
    /// `Some(evidence)` while the fault is still in the program.
    #[serde(skip)]
    pub still_there: fn(&Attempt) -> Option<String>,
}

pub use super::ping_pong::{FRAGMENT, STEP_COUNT, VERTEX};

/// The grid's side: large enough that one step is real work to time.
pub const SIDE: u32 = 128;
/// How many times the timed step is made.
pub const REPEATS: u32 = 100;

/// The start: lesson 2's grid at this side (zero inside, the top row held at 1).
pub fn start() -> Vec<f32> {
    initial_grid(SIDE)
}

/// The calls that queue GPU work.
fn is_work(call: &TracedCall) -> bool {
    call.function.starts_with("glDraw") && !call.function.starts_with("glDrawBuffer")
        || call.function == "glDispatchCompute"
        || call.function == "glBlitFramebuffer"
        || call.function.starts_with("glClear")
        || call.function == "glReadPixels" && call.args.contains("pack buffer offset")
}

/// The calls after which the CPU has waited for the work queued before them.
fn waits(call: &TracedCall) -> bool {
    match call.function {
        "glFinish" | "glGetBufferSubData" => true,
        "glReadPixels" | "glGetTexImage" => !call.args.contains("pack buffer offset"),
        f if f.starts_with("glGetQueryObject") => {
            call.args.contains("GL_QUERY_RESULT") && !call.args.contains("AVAILABLE")
        }
        _ => false,
    }
}

/// Fault 1: a stopwatch read while work it timed was only queued.
fn unwaited_clock(attempt: &Attempt) -> Option<String> {
    if attempt.readings.is_empty() {
        return Some(
            "the program no longer reads the stopwatch (ex.read_clock): it must still time its \
             steps"
                .into(),
        );
    }
    attempt.readings.iter().find_map(|r| {
        let timed = attempt.calls.get(r.from..r.to)?;
        let last_work = timed.iter().rposition(is_work)?;
        let waited = timed[last_work + 1..].iter().any(waits);
        (!waited).then(|| {
            format!(
                "the stopwatch was read after call {} with the work of call {} ({}) only \
                 queued: no glFinish, finished timer query or waiting read between them",
                r.to,
                r.from + last_work + 1,
                timed[last_work].function
            )
        })
    })
}

/// The first draw with a problem `pick` keeps, described.
fn draw_with(attempt: &Attempt, pick: fn(&DrawProblem) -> bool) -> Option<String> {
    attempt.draws.iter().find_map(|d| {
        let problem = d.problems().into_iter().find(pick)?;
        Some(format!(
            "the draw at call {} ({}): {problem}",
            d.call, d.function
        ))
    })
}

/// Fault 2: a draw that samples its own target.
fn feedback_loop(attempt: &Attempt) -> Option<String> {
    draw_with(attempt, |p| matches!(p, DrawProblem::FeedbackLoop { .. }))
}

/// Fault 3: a draw into a target that is not a float format.
fn clamping_target(attempt: &Attempt) -> Option<String> {
    draw_with(attempt, |p| matches!(p, DrawProblem::NotFloat { .. }))
}

/// Fault 4: a glUniform call with no program in use.
fn uniform_without_program(attempt: &Attempt) -> Option<String> {
    let mut in_use = "0";
    for (k, call) in attempt.calls.iter().enumerate() {
        if call.function == "glUseProgram" {
            in_use = &call.args;
        } else if call.function.starts_with("glUniform") && in_use == "0" {
            return Some(format!(
                "call {} ({call}) was made with no program in use",
                k + 1
            ));
        }
    }
    None
}

/// Lesson 2's check of the grid read back after the steps, texel by texel.
fn check(run: &mut LessonRun, grid: &[f32]) {
    run.check_texels(
        &format!("after {STEP_COUNT} steps the grid = the CPU's Jacobi iterate"),
        Grid::new(SIDE, SIDE, 1),
        grid,
        &jacobi_cpu(&start(), SIDE, STEP_COUNT),
        tolerance(STEP_COUNT),
    );
}

pub static CARD: HostExercise = HostExercise {
    example: "debug-hunt",
    lesson: "debugging",
    title: "the debug hunt: four faults planted in a Jacobi program",
    gaps: &[] as &[Gap],
    faults: &[
        Fault {
            number: 1,
            symptom: "the time printed for one step is far shorter than a step takes",
            hints: [
                "A GL call returns when its work is queued, not when it is done; the GPU (here \
                 the CPU threads of llvmpipe) works after. A wall clock read right after the \
                 last draw measures how fast the calls were queued.",
                "Look at `-- --trace`: what comes between the last draw and the stopwatch's \
                 reading? Wait for the work before reading the clock: glFinish (gl.finish()), \
                 or time the draws with a GL_TIME_ELAPSED query and read its result.",
            ],
            still_there: unwaited_clock,
        },
        Fault {
            number: 2,
            symptom: "the grid is wrong, and wrong differently on another renderer or size",
            hints: [
                "A pass that samples the texture it draws into is a feedback loop: fragments \
                 run in any order, so a neighbour may be read before or after it is written, \
                 and GL leaves the result undefined (the debugging lesson's fault 3).",
                "`-- --inspect` lists what each draw samples and what it draws into. Each step \
                 must read one texture and draw into the other one's framebuffer: check the \
                 (texture, framebuffer) pairs the loop picks.",
            ],
            still_there: feedback_loop,
        },
        Fault {
            number: 3,
            symptom: "values come back in steps of 1/255",
            hints: [
                "A texture's internal format decides what a texel keeps of what the shader \
                 writes: 8-bit normalized formats clamp to [0, 1] and round to 1/255 (the \
                 debugging lesson's fault 2).",
                "`-- --inspect` names each target's format, and `-- --trace` shows the internal \
                 format each glTexImage2D asked for: both iterates must be GL_R32F (with \
                 GL_RED and GL_FLOAT for the data's layout).",
            ],
            still_there: clamping_target,
        },
        Fault {
            number: 4,
            symptom: "the top row, held at 1, drifts: the boundary is not held",
            hints: [
                "glUniform sets a uniform of the program in use; with none in use it does \
                 nothing but raise GL_INVALID_OPERATION, which nobody sees unless glGetError \
                 is asked. The shader then finds the boundary with a size of 0 x 0.",
                "The run lists the GL errors left pending. In `-- --trace`, find the glUniform \
                 calls and the glUseProgram before them: a uniform is set after \
                 gl.use_program(Some(program)).",
            ],
            still_there: uniform_without_program,
        },
    ],
    solution_file: "examples/debug-hunt-solution.rs",
    solution_text: include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/debug-hunt-solution.rs"
    )),
    check,
};

/// Each fault of `card` and whether it is still there (with the evidence).
pub fn verdicts(
    card: &'static HostExercise,
    attempt: &Attempt,
) -> Vec<(&'static Fault, Option<String>)> {
    card.faults
        .iter()
        .map(|f| (f, (f.still_there)(attempt)))
        .collect()
}

/// The hunt's run as text: the run's checks, the GL errors left pending, each fault fixed or
/// still there (by its symptom only), and where the hints and tools are. The flag: passed
/// (every fault fixed, every check passed).
pub(super) fn run_lines(
    card: &'static HostExercise,
    body: Body,
    trace: bool,
    inspect: bool,
) -> anyhow::Result<(Vec<String>, bool)> {
    let attempt = super::attempt(card, body)?;
    let mut lines = vec![format!(
        "debug hunt ({}, lesson {}) on {}: {} faults planted",
        card.template(),
        card.lesson,
        attempt.run.renderer,
        card.faults.len()
    )];
    match &attempt.outcome {
        Outcome::Ran => lines.extend(super::check_lines(&attempt.run)),
        Outcome::Failed(e) => lines.push(format!("the program stopped with an error: {e}")),
        Outcome::Stopped(stop) => lines.push(format!("the program stopped: {stop}")),
    }
    if !attempt.errors_left.is_empty() {
        lines.push(format!(
            "  GL errors left pending at the end, never asked for (glGetError): {}",
            attempt.errors_left.join(", ")
        ));
    }
    let verdicts = verdicts(card, &attempt);
    for (fault, evidence) in &verdicts {
        lines.push(format!(
            "  fault {} [{}]: {}",
            fault.number,
            if evidence.is_some() {
                "still there"
            } else {
                "fixed"
            },
            fault.symptom
        ));
    }
    let left = verdicts.iter().filter(|(_, e)| e.is_some()).count();
    let passed = left == 0 && attempt.passed();
    if passed {
        lines.push(format!(
            "passed: all {} faults found and fixed, and the grid is the CPU's",
            card.faults.len()
        ));
    } else {
        lines.push(format!(
            "{left} of {} faults still there{}; a hint for fault F: {} -- --hint F.1 (.2 the tool \
             and the call, .3 the solution's line)",
            card.faults.len(),
            if left == 0 {
                ", but the grid is not the CPU's"
            } else {
                ""
            },
            card.run_command()
        ));
        lines.push(
            "your tools: -- --trace (every GL call, the stopwatch's start and reading among \
             them), -- --inspect (each draw: what it samples, what it draws into, the viewport, \
             and what is wrong with it)"
                .into(),
        );
    }
    if inspect {
        lines.extend(super::inspect_lines(&attempt.draws));
    }
    if trace {
        lines.extend(trace_lines(&attempt));
    }
    Ok((lines, passed))
}

/// Every call of the run, numbered, the stopwatch's start and readings marked between them.
fn trace_lines(attempt: &Attempt) -> Vec<String> {
    let mut lines = vec![format!("{} GL calls:", attempt.calls.len())];
    let marks_at = |k: usize| {
        let mut marks = Vec::new();
        for r in &attempt.readings {
            if r.from == k {
                marks.push("  ---- stopwatch started ----".to_string());
            }
            if r.to == k {
                marks.push(format!("  ---- stopwatch read: {:.3} ms ----", r.ms));
            }
        }
        marks
    };
    for (k, call) in attempt.calls.iter().enumerate() {
        lines.extend(marks_at(k));
        lines.push(format!("  {:>5}  {call}", k + 1));
    }
    lines.extend(marks_at(attempt.calls.len()));
    lines
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::learn::host::Reading;

    fn call(function: &'static str, args: &str) -> TracedCall {
        TracedCall {
            pass: None,
            function,
            args: args.into(),
            result: None,
        }
    }

    fn attempt(calls: Vec<TracedCall>, readings: Vec<Reading>) -> Attempt {
        Attempt {
            outcome: Outcome::Ran,
            run: LessonRun::named("debugging", "hunt", String::new()),
            calls,
            draws: Vec::new(),
            readings,
            checks: Vec::new(),
            reached: 0,
            errors_left: Vec::new(),
        }
    }

    fn reading(from: usize, to: usize) -> Reading {
        Reading { from, to, ms: 0.1 }
    }

    #[test]
    fn a_clock_read_after_queued_draws_is_caught_and_a_finish_clears_it() {
        let draws = vec![
            call("glBindFramebuffer", "GL_FRAMEBUFFER, 2"),
            call("glDrawArrays", "GL_TRIANGLE_STRIP, 0, 4"),
        ];
        let caught = attempt(draws.clone(), vec![reading(0, 2)]);
        assert!(unwaited_clock(&caught).unwrap().contains("call 2"));
        let mut finished = draws.clone();
        finished.push(call("glFinish", ""));
        assert!(unwaited_clock(&attempt(finished, vec![reading(0, 3)])).is_none());
        let mut queued_read = draws.clone();
        queued_read.push(call(
            "glReadPixels",
            "0, 0, 1, 1, GL_RED, GL_FLOAT, <pack buffer offset 0>",
        ));
        assert!(unwaited_clock(&attempt(queued_read, vec![reading(0, 3)])).is_some());
        assert!(unwaited_clock(&attempt(draws, Vec::new())).is_some());
    }

    #[test]
    fn a_uniform_before_use_program_is_caught() {
        let early = vec![call("glUniform2i", "2, 16, 16"), call("glUseProgram", "3")];
        assert!(uniform_without_program(&attempt(early, Vec::new()))
            .unwrap()
            .contains("call 1"));
        let late = vec![call("glUseProgram", "3"), call("glUniform2i", "2, 16, 16")];
        assert!(uniform_without_program(&attempt(late, Vec::new())).is_none());
    }
}
