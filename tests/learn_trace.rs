//! Code on every lesson page and the GL call trace (issue 39, item 1): the regions the guide
//! names exist and are not empty, the guide's code blocks are the files' own lines, the trace
//! of lesson 1's saxpy pass holds the framebuffer bind, the viewport, the program and the draw
//! in order with their counts, tracing off records nothing, and `--trace` prints or writes the
//! calls of a run.

use classic_gpgpu::gl::trace::{self, TracedCall};
use classic_gpgpu::learn::guide::{self, code};
use classic_gpgpu::learn::{self, LessonOptions};
use common::{assert_ok, assert_refused, classic_gpgpu};

mod common;

fn lesson_one(ctx: &classic_gpgpu::gl::Context) {
    let run = learn::find("quad-is-loop")
        .unwrap()
        .run(ctx, &LessonOptions::default())
        .unwrap();
    assert!(run.passed, "lesson 1 failed: {:?}", run.checks);
}

/// The index in `calls` of the first call to `function` whose arguments start with `args`.
fn position(calls: &[&TracedCall], function: &str, args: &str) -> usize {
    calls
        .iter()
        .position(|c| c.function == function && c.args.starts_with(args))
        .unwrap_or_else(|| {
            let all: Vec<String> = calls.iter().map(|c| c.to_string()).collect();
            panic!("no {function}({args}...) in:\n{}", all.join("\n"))
        })
}

#[test]
fn lesson_one_saxpy_pass_binds_sets_the_viewport_uses_the_program_and_draws() {
    let ctx = common::context();
    assert!(!ctx.tracing());
    ctx.trace_start();
    lesson_one(&ctx);
    let calls = ctx.trace_stop();
    assert!(!ctx.tracing());
    let pass = trace::first_pass(&calls, "saxpy");
    // The target is 16 x 12: the viewport is the array's size, the draw one strip of 4.
    let bind = position(&pass, "glBindFramebuffer", "GL_FRAMEBUFFER, ");
    let viewport = position(&pass, "glViewport", "0, 0, 16, 12");
    let draw = position(&pass, "glDrawArraysInstanced", "GL_TRIANGLE_STRIP, 0, 4, 1");
    assert!(
        bind < viewport && viewport < draw,
        "{bind} {viewport} {draw}"
    );
    assert_ne!(
        pass[bind].args, "GL_FRAMEBUFFER, 0",
        "the default framebuffer was bound"
    );
    // The program current at the draw is a real one.
    let used = pass[..draw]
        .iter()
        .rev()
        .find(|c| c.function == "glUseProgram")
        .expect("a glUseProgram before the draw");
    assert_ne!(used.args, "0");
    // The uniform by name and value, the two inputs on units 0 and 1.
    position(&pass, "glUniform1f", "u_a @ ");
    assert!(pass
        .iter()
        .any(|c| c.function == "glUniform1f" && c.args.ends_with(", 2.5")));
    let unit0 = position(&pass, "glActiveTexture", "GL_TEXTURE0 + 0");
    let unit1 = position(&pass, "glActiveTexture", "GL_TEXTURE0 + 1");
    assert!(unit0 < unit1 && unit1 < draw);
    position(&pass, "glBindTexture", "GL_TEXTURE_2D, ");
    // Outside the pass: the uploads, with the texture format by name.
    assert!(calls
        .iter()
        .any(|c| c.pass.is_none() && c.function == "glTexImage2D" && c.args.contains("GL_R32F")));
    // The lesson page shows the same calls.
    let page = guide::trace_section(learn::find("quad-is-loop").unwrap().info(), &calls);
    assert!(
        page.contains("glBindFramebuffer(GL_FRAMEBUFFER, "),
        "{page}"
    );
    assert!(page.contains("glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, 1)"));
}

#[test]
fn tracing_off_records_nothing() {
    let ctx = common::context();
    lesson_one(&ctx);
    assert!(
        ctx.trace_stop().is_empty(),
        "calls recorded with tracing off"
    );
    ctx.trace_start();
    let none = ctx.trace_stop();
    assert!(none.is_empty(), "{none:?}");
}

#[test]
fn every_region_the_guide_names_is_cut() {
    for lesson in learn::all() {
        let info = lesson.info();
        let (shaders, host) = code::blocks(info).unwrap_or_else(|e| panic!("{}: {e}", info.id));
        assert_eq!(shaders.len(), info.shaders.len());
        assert!(!host.is_empty(), "lesson {} shows no host code", info.id);
        for block in shaders.iter().chain(&host) {
            assert!(!block.text.trim().is_empty(), "{}", block.file);
        }
    }
    for lesson in code::LESSONS {
        assert!(learn::find(lesson.lesson).is_ok(), "{}", lesson.lesson);
        for shown in lesson.host {
            code::region(shown).unwrap_or_else(|e| panic!("{e}"));
        }
    }
}

#[test]
fn a_missing_region_is_named_in_the_error() {
    let missing = code::Shown {
        file: "src/learn/quad_is_loop.rs",
        region: "no-such-pass",
        caption: "",
    };
    let e = code::region(&missing).unwrap_err();
    assert!(
        e.contains("src/learn/quad_is_loop.rs") && e.contains("no-such-pass"),
        "{e}"
    );
}

fn unescape(html: &str) -> String {
    html.replace("<mark>", "")
        .replace("</mark>", "")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&amp;", "&")
}

/// Every `<pre class="code" data-file=F data-line=N>` block of `html`: (F, N, its text).
fn blocks_of(html: &str) -> Vec<(String, usize, String)> {
    let open = "<pre class=\"code\" data-file=\"";
    let mut out = Vec::new();
    let mut rest = html;
    while let Some(at) = rest.find(open) {
        rest = &rest[at + open.len()..];
        let file_end = rest.find('"').unwrap();
        let file = unescape(&rest[..file_end]);
        let line_at = rest.find("data-line=\"").unwrap() + "data-line=\"".len();
        let line_end = line_at + rest[line_at..].find('"').unwrap();
        let line: usize = rest[line_at..line_end].parse().unwrap();
        let code_at = rest.find("<code>").unwrap() + "<code>".len();
        let code_end = rest.find("</code></pre>").unwrap();
        out.push((file, line, unescape(&rest[code_at..code_end])));
        rest = &rest[code_end..];
    }
    out
}

/// The block is the file's lines from `first`, each with the same indent removed.
fn assert_same_lines(file: &str, first: usize, block: &str) {
    let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{file}: {e}"));
    let lines: Vec<&str> = text.lines().collect();
    let mut indent: Option<String> = None;
    for (k, shown) in block.lines().enumerate() {
        let actual = lines
            .get(first - 1 + k)
            .unwrap_or_else(|| panic!("{file}: the block runs past the end"));
        if shown.is_empty() {
            assert!(actual.trim().is_empty(), "{file}:{}: {actual}", first + k);
            continue;
        }
        let prefix = actual
            .strip_suffix(shown)
            .unwrap_or_else(|| panic!("{file}:{}: page has {shown:?}, file {actual:?}", first + k));
        assert!(prefix.trim().is_empty(), "{file}:{}", first + k);
        let indent = indent.get_or_insert_with(|| prefix.to_string());
        assert_eq!(indent, prefix, "{file}:{}: indent", first + k);
    }
}

#[test]
fn the_guides_code_blocks_are_the_files_lines() {
    let mut count = 0;
    for lesson in learn::all() {
        let info = lesson.info();
        let mut html = code::code_section(info).unwrap();
        for e in info.exercises {
            html.push_str(&code::exercise_code(e.shader).unwrap());
        }
        let blocks = blocks_of(&html);
        let expected = info.shaders.len() + code::host_of(info.id).len() + 2 * info.exercises.len();
        assert_eq!(blocks.len(), expected, "lesson {}", info.id);
        for (file, first, text) in &blocks {
            assert_same_lines(file, *first, text);
            count += 1;
        }
    }
    assert!(count > 40, "{count} blocks");
}

#[test]
fn an_exercise_page_marks_the_gap_and_hides_the_solution() {
    let html = code::exercise_code("glsl/learn/saxpy.frag").unwrap();
    let (template, solution) = html.split_once("<details>").unwrap();
    assert!(template.contains("<mark>    o_y = y;</mark>"), "{template}");
    assert!(
        solution.contains("<mark>    o_y = u_a * x + y;</mark>"),
        "{solution}"
    );
    assert!(template.contains("glsl/learn/exercises/saxpy.frag"));
}

#[test]
fn learn_trace_prints_the_calls_by_pass_and_writes_a_new_file() {
    let out = classic_gpgpu(&["learn", "quad-is-loop", "--trace"]);
    assert_ok(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("pass 'saxpy':"), "{text}");
    assert!(text.contains("glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, 1)"));
    let dir = common::temp_dir("learn_trace", "file");
    let file = dir.join("trace.txt");
    let trace = format!("--trace={}", file.display());
    let written = classic_gpgpu(&["learn", "quad-is-loop", &trace]);
    assert_ok(&written);
    let saved = std::fs::read_to_string(&file).unwrap();
    assert!(saved.contains("pass 'gather':") && saved.contains("glViewport(0, 0, 16, 12)"));
    // A trace never replaces a file.
    let again = classic_gpgpu(&["learn", "quad-is-loop", &trace]);
    assert_refused(&again, &["--trace", "trace.txt", "exists"]);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), saved);
}
