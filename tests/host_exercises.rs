//! Host exercises (issue 51, items 1 and 4): every shipped solution passes its step checks and
//! the lesson's texel-by-texel check; every template, unfilled, stops at its first gap naming
//! the GL step; a template is its solution with each gap left open; a wrong call stops the
//! run at its step naming what is wrong (a clamping format, an incomplete texture, a feedback
//! loop, a uniform set with no program in use, a viewport left at 0 x 0); a result that is not
//! the CPU's fails naming its texels; the trace beside the solution's marks the first difference; the debug hunt finds its four planted faults and
//! none in its solution; `learn --list --json` gives each such lesson its host exercise.
//!
//! The examples are compiled into this test as modules (`#[path]`), so the test runs the code
//! a learner runs, whatever `cargo test` was asked to build (a template also includes its
//! solution that way, to set the traces side by side).

// The examples are modules here, each with the files it includes (a template its solution,
// which is also compiled on its own; most of them `given`).
#![allow(clippy::duplicate_mod)]

mod common;

#[allow(dead_code)]
#[path = "../examples/saxpy.rs"]
mod saxpy;

#[allow(dead_code)]
#[path = "../examples/saxpy-solution.rs"]
mod saxpy_solution;

#[allow(dead_code)]
#[path = "../examples/ping-pong.rs"]
mod ping_pong;

#[allow(dead_code)]
#[path = "../examples/ping-pong-solution.rs"]
mod ping_pong_solution;

#[allow(dead_code)]
#[path = "../examples/reduction.rs"]
mod reduction;

#[allow(dead_code)]
#[path = "../examples/reduction-solution.rs"]
mod reduction_solution;

#[allow(dead_code)]
#[path = "../examples/readback.rs"]
mod readback;

#[allow(dead_code)]
#[path = "../examples/readback-solution.rs"]
mod readback_solution;

#[allow(dead_code)]
#[path = "../examples/debug-hunt.rs"]
mod debug_hunt;

#[allow(dead_code)]
#[path = "../examples/debug-hunt-solution.rs"]
mod debug_hunt_solution;

#[path = "../examples/common/given.rs"]
mod given;

use classic_gpgpu::learn::host::{
    self, attempt, beside, hunt, outcome_lines, Attempt, Body, Exercise, HostExercise, Outcome,
    Stop,
};
use classic_gpgpu::learn::Grid;
use std::path::Path;

/// Each exercise with gaps: its card, its template's program, its solution's.
fn exercises() -> [(&'static HostExercise, Body, Body); 4] {
    [
        (
            &host::saxpy::CARD,
            saxpy::exercise,
            saxpy_solution::exercise,
        ),
        (
            &host::ping_pong::CARD,
            ping_pong::exercise,
            ping_pong_solution::exercise,
        ),
        (
            &host::reduction::CARD,
            reduction::exercise,
            reduction_solution::exercise,
        ),
        (
            &host::readback::CARD,
            readback::exercise,
            readback_solution::exercise,
        ),
    ]
}

fn text(card: &'static HostExercise, attempt: &Attempt) -> String {
    outcome_lines(card, attempt).join("\n")
}

#[test]
fn every_solution_passes_each_step_and_the_lessons_check() {
    for (card, _, solution) in exercises() {
        let run = attempt(card, solution).unwrap();
        assert!(run.passed(), "{}:\n{}", card.example, text(card, &run));
        assert_eq!(run.reached, card.gaps.len() as u32, "{}", card.example);
        assert!(run.run.checks.iter().all(|c| c.passed));
        assert!(run.errors_left.is_empty(), "{:?}", run.errors_left);
        assert!(
            run.draws.iter().all(|d| d.problems().is_empty()),
            "{}",
            card.example
        );
    }
}

#[test]
fn every_unfilled_template_stops_at_its_first_gap_naming_the_gl_step() {
    for (card, template, _) in exercises() {
        let run = attempt(card, template).unwrap();
        assert!(
            matches!(run.outcome, Outcome::Stopped(Stop::Gap(1))),
            "{}: {:?}",
            card.example,
            run.outcome
        );
        assert!(!run.passed());
        let said = text(card, &run);
        let first = format!(
            "gap 1 of {} is not filled: {}",
            card.gaps.len(),
            card.gaps[0].step
        );
        assert!(said.contains(&first), "{said}");
        assert!(said.contains(&format!("--example {} -- --hint 1.1", card.example)));
    }
    let saxpy = attempt(&host::saxpy::CARD, saxpy::exercise).unwrap();
    assert!(text(&host::saxpy::CARD, &saxpy).contains("(glGenTextures, glBindTexture"));
}

/// The lines of `file` from the doc comment of `pub fn exercise` to the end.
fn body(file: &str) -> Vec<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    let text = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<String> = text.lines().map(String::from).collect();
    let mut start = lines
        .iter()
        .position(|l| l.starts_with("pub fn exercise("))
        .unwrap_or_else(|| panic!("{file}: no `pub fn exercise(`"));
    while start > 0
        && ["///", "#[", "// "]
            .iter()
            .any(|p| lines[start - 1].starts_with(p))
    {
        start -= 1;
    }
    lines[start..].to_vec()
}

#[test]
fn a_template_is_its_solution_with_each_gap_left_open() {
    for (card, _, _) in exercises() {
        let (template, solution) = (body(&card.template()), body(&card.solution()));
        let (mut t, mut s) = (0, 0);
        let mut gaps = Vec::new();
        while s < solution.len() {
            let line = solution[s].trim();
            if let Some(name) = line.strip_prefix("// region: gap-") {
                let n: u32 = name.parse().unwrap();
                gaps.push(n);
                // The solution's region ...
                s += 1;
                while solution[s].trim() != "// endregion" {
                    s += 1;
                }
                s += 1;
                // ... is the template's statement that ends in the gap.
                let open = [format!("ex.gap({n})?"), format!("ex.gap_value({n})?")];
                while !open.iter().any(|o| template[t].contains(o.as_str())) {
                    t += 1;
                    assert!(t < template.len(), "{}: no gap {n}", card.template());
                }
                t += 1;
                continue;
            }
            assert_eq!(
                template.get(t).map(String::as_str),
                Some(solution[s].as_str()),
                "{} line {} differs from {} line {}",
                card.template(),
                t,
                card.solution(),
                s
            );
            t += 1;
            s += 1;
        }
        assert_eq!(
            t,
            template.len(),
            "{}: lines after the solution's end",
            card.example
        );
        let numbers: Vec<u32> = card.gaps.iter().map(|g| g.number).collect();
        let mut sorted = gaps.clone();
        sorted.sort();
        assert_eq!(sorted, numbers, "{}", card.example);
        // Templates do not carry the answer: no region markers, no solution's line.
        let template = template.join("\n");
        assert!(!template.contains("// region:"), "{}", card.template());
    }
}

/// The first texture of every test body below: 4 x 2 floats, made as `internal` says.
const SIDE: (u32, u32) = (4, 2);

unsafe fn texture(ex: &Exercise, internal: u32, nearest: bool) -> anyhow::Result<glow::Texture> {
    let gl = ex.gl();
    let t = gl.create_texture().map_err(anyhow::Error::msg)?;
    gl.bind_texture(glow::TEXTURE_2D, Some(t));
    if nearest {
        gl.tex_parameter_i32(
            glow::TEXTURE_2D,
            glow::TEXTURE_MIN_FILTER,
            glow::NEAREST as i32,
        );
    }
    let values = vec![0.5f32; 8];
    gl.tex_image_2d(
        glow::TEXTURE_2D,
        0,
        internal as i32,
        SIDE.0 as i32,
        SIDE.1 as i32,
        0,
        glow::RED,
        glow::FLOAT,
        glow::PixelUnpackData::Slice(Some(bytemuck::cast_slice(&values))),
    );
    Ok(t)
}

fn grid() -> Grid {
    Grid::new(SIDE.0, SIDE.1, 1)
}

// A learner's wrong calls, each followed by the check its template makes after that step.
// SAFETY (every body): the calls are made on the exercise's context, current on this thread.

fn clamping_input(ex: &Exercise) -> anyhow::Result<Vec<f32>> {
    let t = unsafe { texture(ex, glow::R8, true)? };
    ex.texture_holds(1, t, grid(), &[0.5; 8])?;
    Ok(Vec::new())
}

fn mipmapped_filter(ex: &Exercise) -> anyhow::Result<Vec<f32>> {
    let t = unsafe { texture(ex, glow::R32F, false)? };
    ex.texture_holds(1, t, grid(), &[0.5; 8])?;
    Ok(Vec::new())
}

fn drawing_into_what_it_reads(ex: &Exercise) -> anyhow::Result<Vec<f32>> {
    unsafe {
        let gl = ex.gl();
        let t = texture(ex, glow::R32F, true)?;
        let fb = gl.create_framebuffer().map_err(anyhow::Error::msg)?;
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fb));
        gl.framebuffer_texture_2d(
            glow::FRAMEBUFFER,
            glow::COLOR_ATTACHMENT0,
            glow::TEXTURE_2D,
            Some(t),
            0,
        );
        let program = given::program(gl, hunt::VERTEX, hunt::FRAGMENT)?;
        given::vertex_array(gl)?;
        gl.use_program(Some(program));
        gl.viewport(0, 0, SIDE.0 as i32, SIDE.1 as i32);
        gl.active_texture(glow::TEXTURE0);
        gl.bind_texture(glow::TEXTURE_2D, Some(t));
        gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4);
    }
    ex.drew(6)?;
    Ok(Vec::new())
}

fn uniform_before_use(ex: &Exercise) -> anyhow::Result<Vec<f32>> {
    unsafe {
        let gl = ex.gl();
        let program = given::program(gl, hunt::VERTEX, hunt::FRAGMENT)?;
        let size = gl.get_uniform_location(program, "u_size");
        gl.uniform_2_i32(size.as_ref(), 4, 4);
        gl.use_program(Some(program));
        ex.in_use(4, program)?;
    }
    Ok(Vec::new())
}

fn no_viewport(ex: &Exercise) -> anyhow::Result<Vec<f32>> {
    let t = unsafe { texture(ex, glow::R32F, true)? };
    ex.viewport_covers(5, t)?;
    Ok(Vec::new())
}

#[test]
fn a_wrong_call_stops_at_its_step_naming_what_is_wrong() {
    let card = &host::saxpy::CARD;
    let cases: [(Body, u32, &[&str]); 5] = [
        (clamping_input, 1, &["GL_R8", "clamps", "GL_R32F"]),
        (
            mipmapped_filter,
            1,
            &[
                "GL_NEAREST_MIPMAP_LINEAR",
                "incomplete",
                "GL_TEXTURE_MIN_FILTER",
            ],
        ),
        (
            drawing_into_what_it_reads,
            6,
            &["u_current", "feedback loop", "GL_COLOR_ATTACHMENT0"],
        ),
        (
            uniform_before_use,
            4,
            &["GL_INVALID_OPERATION", "no program in use"],
        ),
        (
            no_viewport,
            5,
            &["the viewport is 0, 0, 0 x 0", "4 x 2", "glViewport"],
        ),
    ];
    for (body, gap, words) in cases {
        let run = attempt(card, body).unwrap();
        let Outcome::Stopped(Stop::Step { gap: at, problem }) = &run.outcome else {
            panic!("gap {gap}: {:?}", run.outcome);
        };
        assert_eq!(*at, gap, "{problem}");
        for word in words {
            assert!(problem.contains(word), "{word:?} not in: {problem}");
        }
        let said = text(card, &run);
        assert!(said.contains(&format!("gap {gap} of 7")), "{said}");
        assert!(said.contains(&format!("--hint {gap}.2")), "{said}");
    }
}

/// A program that runs to its end with a y one texel off: x's ramp read at the next texel.
fn one_texel_off(_: &Exercise) -> anyhow::Result<Vec<f32>> {
    let (x, y) = host::saxpy::inputs();
    let shifted = (0..x.len()).map(|k| x[(k + 1) % x.len()]);
    Ok(shifted
        .zip(&y)
        .map(|(x, y)| host::saxpy::A * x + y)
        .collect())
}

#[test]
fn a_result_that_is_not_the_cpus_fails_naming_its_texels() {
    let card = &host::saxpy::CARD;
    let run = attempt(card, one_texel_off).unwrap();
    assert!(matches!(run.outcome, Outcome::Ran));
    assert!(!run.passed());
    let said = text(card, &run);
    // Every texel is off by a x's step (2.5 / 8), so the first ones are named, with both values.
    assert!(said.contains("FAIL saxpy = the CPU loop"), "{said}");
    assert!(said.contains("192 of 192 values are off"), "{said}");
    assert!(
        said.contains("texel (0, 0) channel 0: the GPU wrote -0.6875, the CPU expects -1"),
        "{said}"
    );
    let short = attempt(card, |_| Ok(vec![0.0; 3])).unwrap();
    assert!(text(card, &short).contains("another count of values"));
}

#[test]
fn the_trace_beside_the_solutions_marks_the_first_difference() {
    let card = &host::saxpy::CARD;
    let wrong = attempt(card, clamping_input).unwrap();
    let right = attempt(card, mipmapped_filter).unwrap();
    let listing = beside::lines(&wrong.calls, &right.calls, &card.solution(), true).join("\n");
    // The same calls up to the format; there the filter call and the format differ.
    assert!(listing.contains(">>"), "{listing}");
    assert!(
        listing.contains("the first difference, row 3, in full"),
        "{listing}"
    );
    assert!(listing.contains("yours:    glTexParameteri"), "{listing}");
    assert!(
        listing.contains("GL_R8") && listing.contains("GL_R32F"),
        "{listing}"
    );
    let solution = attempt(card, saxpy_solution::exercise).unwrap();
    let same = beside::lines(&solution.calls, &solution.calls, "s", false);
    assert!(same[0].contains("call for call"), "{same:?}");
}

#[test]
fn the_hunt_finds_its_four_planted_faults_and_none_in_its_solution() {
    let card = &hunt::CARD;
    let planted = attempt(card, debug_hunt::exercise).unwrap();
    let found = hunt::verdicts(card, &planted);
    assert_eq!(found.len(), 4);
    for (fault, evidence) in &found {
        assert!(evidence.is_some(), "fault {} was not found", fault.number);
    }
    let evidence: Vec<String> = found.into_iter().filter_map(|(_, e)| e).collect();
    assert!(evidence[0].contains("only queued"), "{}", evidence[0]);
    assert!(evidence[1].contains("feedback loop"), "{}", evidence[1]);
    assert!(evidence[2].contains("GL_RGBA8"), "{}", evidence[2]);
    assert!(evidence[3].contains("glUniform2i"), "{}", evidence[3]);
    assert_eq!(planted.errors_left, ["GL_INVALID_OPERATION"]);
    let fixed = attempt(card, debug_hunt_solution::exercise).unwrap();
    assert!(hunt::verdicts(card, &fixed)
        .iter()
        .all(|(_, evidence)| evidence.is_none()));
    assert!(fixed.passed(), "{}", text(card, &fixed));
    assert!(fixed.errors_left.is_empty());
    for fault in 1..=4 {
        let line = host::hint_lines(card, &format!("{fault}.3"))
            .unwrap()
            .join("\n");
        assert!(line.contains("debug-hunt-solution.rs"), "{line}");
    }
}

#[test]
fn learn_list_json_gives_each_host_exercise_its_files_and_commands() {
    let lessons = common::json_of(&["learn", "--list", "--json"]);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut with = Vec::new();
    for lesson in lessons.as_array().unwrap() {
        let id = lesson["id"].as_str().unwrap();
        let host = &lesson["host_exercise"];
        if host.is_null() {
            continue;
        }
        with.push(id);
        for file in ["template", "solution"] {
            let path = host[file].as_str().unwrap();
            assert!(root.join(path).is_file(), "{id}: {file} {path}");
        }
        let example = Path::new(host["template"].as_str().unwrap())
            .file_stem()
            .unwrap()
            .to_str()
            .unwrap()
            .to_string();
        assert_eq!(
            host["run"].as_str().unwrap(),
            format!("cargo run --release --example {example}")
        );
        assert_eq!(
            host["run_solution"].as_str().unwrap(),
            format!("cargo run --release --example {example}-solution")
        );
    }
    assert_eq!(
        with,
        [
            "quad-is-loop",
            "ping-pong",
            "reduction",
            "readback-and-upload",
            "debugging"
        ]
    );
}
