//! The offline guide: an HTML page per lesson, made by running every lesson of [`crate::learn::all`]
//! on the context given (its pictures are the lessons' own buffers and its numbers their
//! checks, so it cannot drift from the code), then the reading order from the lessons into
//! the papers with what to run and read for each, and a glossary of the papers' terms that
//! every page links to where it uses them. No scripts, no external files.

pub mod code;
pub mod ladder_page;

use crate::gl::trace::{self, TracedCall};
use crate::gl::Context;
use crate::learn::{LessonOptions, LessonRun};
use crate::page::html::{escape, STYLE};
use std::path::{Path, PathBuf};

/// What was written: every page, and each lesson's verdict.
#[derive(Debug)]
pub struct GuideWritten {
    pub pages: Vec<PathBuf>,
    /// (lesson id, passed; false also when the lesson could not run).
    pub lessons: Vec<(String, bool)>,
}

/// Run every lesson on `ctx` and write the guide into `dir` (made if missing), by the rule of
/// every folder writer ([`crate::page::folder::Staged`]): a folder holding files the guide
/// did not write is refused unless `force`, and a rewrite removes the old guide's files that
/// the new one does not have.
pub fn write_guide(ctx: &Context, dir: &Path, force: bool) -> anyhow::Result<GuideWritten> {
    let folder = crate::page::folder::Staged::begin("--guide", "learn --guide", dir, force)?;
    let staging = folder.path();
    let lessons = crate::learn::all();
    let mut runs = Vec::new();
    let mut traces = Vec::new();
    // Each lesson's GL calls are recorded for its page, unless a trace of the whole command
    // (`--trace`) is already recording them.
    let record = !ctx.tracing();
    for lesson in &lessons {
        let info = lesson.info();
        let opts = LessonOptions {
            png_dir: Some(staging.join("pictures").join(info.id)),
            exercise: None,
        };
        if record {
            ctx.trace_start();
        }
        runs.push(lesson.run(ctx, &opts).map_err(|e| format!("{e:#}")));
        traces.push(if record { ctx.trace_stop() } else { Vec::new() });
    }
    let mut pages = Vec::new();
    let mut write = |name: &str, html: String| -> anyhow::Result<()> {
        crate::files::write_bytes(&staging.join(name), html.as_bytes())?;
        pages.push(dir.join(name));
        Ok(())
    };
    write("index.html", index_page(ctx, &lessons, &runs))?;
    for (k, lesson) in lessons.iter().enumerate() {
        let neighbours = (
            k.checked_sub(1).map(|p| lessons[p].info()),
            lessons.get(k + 1).map(|n| n.info()),
        );
        // The reduction ladder's table and plot, on its lesson's page (empty elsewhere).
        let ladder = ladder_page::section(ctx, lesson.info().id, staging);
        write(
            &lesson_file(lesson.info().id),
            lesson_page(lesson.info(), &runs[k], &traces[k], neighbours, &ladder),
        )?;
    }
    write("reading.html", reading_page())?;
    write("glossary.html", glossary_page())?;
    for name in super::walks::write_pages(ctx, staging)? {
        pages.push(dir.join(name));
    }
    let verdicts = lessons
        .iter()
        .zip(&runs)
        .map(|(l, r)| (l.info().id.to_string(), matches!(r, Ok(run) if run.passed)))
        .collect();
    folder.finish()?;
    Ok(GuideWritten {
        pages,
        lessons: verdicts,
    })
}

fn lesson_file(id: &str) -> String {
    format!("lesson-{id}.html")
}

fn page(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{}</title><style>{STYLE}\
         {GUIDE_STYLE}</style></head><body>\n<nav><a href=\"index.html\">Lessons</a> \
         <a href=\"reading.html\">Reading order</a> <a href=\"glossary.html\">Glossary</a></nav>\n\
         {body}</body></html>\n",
        escape(title)
    )
}

const GUIDE_STYLE: &str = "nav a{margin-right:1.5em}.flow{display:flex;flex-wrap:wrap;\
align-items:center;gap:.4em;margin:.6em 0}.box{border:1px solid #99a;border-radius:4px;\
padding:.4em .6em;background:#f4f6fb;max-width:16em;font-size:90%}.box img{width:96px;\
image-rendering:pixelated;display:block;margin-top:.3em}.arrow{font-size:140%;color:#667}\
.pass{color:#070}td,th{text-align:left}.fail{color:#b00}code{background:#f2f2f2;padding:0 .2em}\
pre.code{background:#f7f7f2;border:1px solid #ccc;padding:.5em;overflow-x:auto;margin-top:0}\
pre.code code{background:none;padding:0}.where{font-size:85%;color:#555;margin-top:.8em}\
mark{background:#ffe08a}details{margin:.5em 0}\
.full{overflow-x:auto}.full img{max-width:none;image-rendering:pixelated}";

fn verdict(run: &Result<LessonRun, String>) -> String {
    match run {
        Ok(r) if r.passed => "<span class=\"pass\">passed</span>".into(),
        Ok(_) => "<span class=\"fail\">FAILED</span>".into(),
        Err(_) => "<span class=\"fail\">did not run</span>".into(),
    }
}

fn index_page(
    ctx: &Context,
    lessons: &[&'static dyn crate::learn::Lesson],
    runs: &[Result<LessonRun, String>],
) -> String {
    let mut body = String::from(
        "<h1>Learn classic GPGPU</h1>\n<p>Lessons from \"a texture is an array\" to the \
         building blocks the papers are made of. Each is a small GPGPU program checked against \
         the CPU; every picture and number below comes from running it for this guide.</p>\n",
    );
    body.push_str(&format!(
        "<p>Renderer: <b>{}</b>.</p>\n<table><tr><th>lesson</th><th>title</th><th>checks</th>\
         <th>largest error</th><th>compute</th></tr>\n",
        escape(&ctx.info().renderer_line())
    ));
    for (lesson, run) in lessons.iter().zip(runs) {
        let info = lesson.info();
        let (error, compute) = match run {
            Ok(r) => (
                format!("{:.3e}", r.max_error),
                r.compute.clone().unwrap_or_default(),
            ),
            Err(_) => (String::new(), String::new()),
        };
        body.push_str(&format!(
            "<tr><td>{}</td><td><a href=\"{}\">{}</a></td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            info.number,
            lesson_file(info.id),
            escape(info.title),
            verdict(run),
            error,
            escape(&compute)
        ));
    }
    body.push_str(&format!(
        "</table>\n<p>{}</p>\n",
        escape(crate::gl::picture::MAPPING_IN_WORDS)
    ));
    body.push_str(
        "<p>Then: the <a href=\"reading.html\">reading order</a> from the lessons into the \
         papers, and the <a href=\"glossary.html\">glossary</a>.</p>\n",
    );
    body.push_str(&walk_links());
    page("Learn classic GPGPU", &body)
}

fn lesson_page(
    info: &crate::learn::LessonInfo,
    run: &Result<LessonRun, String>,
    calls: &[TracedCall],
    (previous, next): (
        Option<&crate::learn::LessonInfo>,
        Option<&crate::learn::LessonInfo>,
    ),
    ladder: &str,
) -> String {
    let mut body = format!(
        "<h1>Lesson {}: {}</h1>\n<p>{}</p>\n",
        info.number,
        escape(info.title),
        escape(info.idea)
    );
    match run {
        Err(e) => body.push_str(&format!(
            "<p class=\"note\">This lesson did not run here: {}</p>\n",
            escape(e)
        )),
        Ok(run) => body.push_str(&run_sections(info, run)),
    }
    body.push_str(ladder);
    body.push_str(&trace_section(info, calls));
    match code::code_section(info) {
        Ok(section) => body.push_str(&section),
        Err(e) => body.push_str(&format!(
            "<p class=\"fail\">The code of this page could not be cut: {}</p>\n",
            escape(&e)
        )),
    }
    body.push_str("<h2>Where the papers use it</h2>\n<ul>\n");
    for step in info.paper_steps {
        body.push_str(&format!(
            "<li>{}: {} (<code>{}</code>)</li>\n",
            escape(step.paper),
            escape(step.step),
            escape(step.file)
        ));
    }
    body.push_str("</ul>\n<h2>The code to read</h2>\n<ul>\n");
    let file = format!("src/learn/{}.rs", info.id.replace('-', "_"));
    body.push_str(&format!(
        "<li><code>{}</code>: the passes and the CPU reference</li>\n",
        escape(&file)
    ));
    for shader in info.shaders {
        body.push_str(&format!("<li><code>{}</code></li>\n", escape(shader)));
    }
    body.push_str("</ul>\n");
    body.push_str(&exercises(info));
    body.push_str(&host_exercise(info));
    body.push_str(&terms_used(&format!("{} {}", info.idea, info.title)));
    body.push_str("<p>");
    if let Some(p) = previous {
        body.push_str(&format!(
            "<a href=\"{}\">&larr; lesson {}</a> ",
            lesson_file(p.id),
            p.number
        ));
    }
    match next {
        Some(n) => body.push_str(&format!(
            "<a href=\"{}\">lesson {} &rarr;</a>",
            lesson_file(n.id),
            n.number
        )),
        None => body.push_str("<a href=\"reading.html\">into the papers &rarr;</a>"),
    }
    body.push_str("</p>\n");
    page(&format!("Lesson {}: {}", info.number, info.title), &body)
}

/// The lesson whose page shows the calls behind one pass in full, and that pass.
pub const CALLS_SHOWN: (&str, &str) = ("quad-is-loop", "saxpy");

/// The GL calls of one pass of the lesson, as recorded while the guide ran: in full on the
/// lesson of [`CALLS_SHOWN`], behind a `<details>` (its first pass) on the others.
pub fn trace_section(info: &crate::learn::LessonInfo, calls: &[TracedCall]) -> String {
    let groups = trace::grouped(calls);
    let (pass, list) = if info.id == CALLS_SHOWN.0 {
        (CALLS_SHOWN.1, trace::first_pass(calls, CALLS_SHOWN.1))
    } else {
        match groups.iter().find(|(pass, _)| pass.is_some()) {
            Some((Some(name), list)) => (&**name, list.clone()),
            _ => return String::new(),
        }
    };
    if list.is_empty() {
        return String::new();
    }
    let text: Vec<String> = list.iter().map(|c| escape(&c.to_string())).collect();
    let block = format!(
        "<pre class=\"code trace\"><code>{}</code></pre>\n",
        text.join("\n")
    );
    let summary = format!(
        "the {} GL calls of pass '{}', recorded while this guide ran ({} calls in the whole \
         lesson; <code>classic-gpgpu learn {} --trace</code> prints them all)",
        list.len(),
        escape(pass),
        calls.len(),
        info.id
    );
    if info.id == CALLS_SHOWN.0 {
        format!(
            "<h2>What one pass is made of</h2>\n<p>The call <code>fb.pass(&amp;program, \
             \"{}\")?...draw_full()</code> hides the calls that make a quad a loop. Here are \
             {summary}. Read them in order: the program made current and each uniform set by \
             name (a sampler uniform holds a texture unit's number; <code>u_rect</code> is the \
             rectangle to cover), then the framebuffer bound as the target, the viewport set to \
             the array's size, each input texture bound to its unit, the fixed-function state \
             reset (no depth or stencil test, no blending), and one draw of four vertices: a \
             triangle strip covering the target, so the fragment shader runs once per \
             element. Objects are shown by their ids, enums \
             by their GL names.</p>\n{block}",
            escape(pass)
        )
    } else {
        format!("<details><summary>The GL calls: {summary}</summary>\n{block}</details>\n")
    }
}

/// The passes as a diagram, the checks, the notes and the compute counterpart of a run.
fn run_sections(info: &crate::learn::LessonInfo, run: &LessonRun) -> String {
    let mut out = format!(
        "<p>Run for this guide on {}: {}.</p>\n<h2>The passes</h2>\n",
        escape(&run.renderer),
        verdict(&Ok(run.clone()))
    );
    for pass in &run.passes {
        out.push_str("<div class=\"flow\">");
        out.push_str(&format!(
            "<div class=\"box\"><b>{}</b><br>{}</div>",
            escape(&pass.name),
            escape(&pass.what)
        ));
        if !pass.shader.is_empty() {
            out.push_str(&format!(
                "<span class=\"arrow\">&rarr;</span><div class=\"box\"><code>{}</code></div>",
                escape(&pass.shader)
            ));
        }
        if let Some(picture) = &pass.picture {
            let src = format!("pictures/{}/{}", info.id, picture);
            out.push_str(&format!(
                "<span class=\"arrow\">&rarr;</span><div class=\"box\">buffer<a href=\"{0}\">\
                 <img src=\"{0}\" alt=\"{1}\"></a></div>",
                escape(&src),
                escape(&pass.name)
            ));
        }
        out.push_str("</div>\n");
    }
    out.push_str(&full_size_buffers(info, run));
    out.push_str(
        "<h2>The checks against the CPU</h2>\n<table><tr><th>check</th><th>error</th>\
         <th>tolerance</th><th>verdict</th></tr>\n",
    );
    for c in &run.checks {
        out.push_str(&format!(
            "<tr><td>{}</td><td>{:.3e}</td><td>{:.1e}</td><td>{}</td></tr>\n",
            escape(&c.what),
            c.max_error,
            c.tolerance,
            if c.passed {
                "<span class=\"pass\">ok</span>"
            } else {
                "<span class=\"fail\">failed</span>"
            }
        ));
    }
    out.push_str("</table>\n");
    if !run.notes.is_empty() {
        out.push_str("<h2>Measured, not checked</h2>\n<table>\n");
        for (name, value) in &run.notes {
            out.push_str(&format!(
                "<tr><td>{}</td><td>{}</td></tr>\n",
                escape(name),
                escape(value)
            ));
        }
        out.push_str("</table>\n");
    }
    if let Some(compute) = &run.compute {
        out.push_str(&format!(
            "<h2>The compute counterpart</h2>\n<p>{}</p>\n",
            escape(compute)
        ));
    }
    out
}

/// Every buffer of the passes at its own size, its key's numbers as drawn (16 pixels high:
/// the lessons draw their pictures at least [`crate::gl::picture::LEGIBLE_WIDTH`] wide), each
/// opening by itself.
fn full_size_buffers(info: &crate::learn::LessonInfo, run: &LessonRun) -> String {
    let mut out = String::new();
    for pass in &run.passes {
        if let Some(picture) = &pass.picture {
            let src = escape(&format!("pictures/{}/{}", info.id, picture));
            out.push_str(&format!(
                "<figure><figcaption>{}</figcaption><div class=\"full\"><a href=\"{src}\">\
                 <img src=\"{src}\" alt=\"{}\"></a></div></figure>\n",
                escape(&pass.name),
                escape(&pass.name)
            ));
        }
    }
    if out.is_empty() {
        return out;
    }
    format!("<h2>The buffers at full size</h2>\n{out}")
}

fn exercises(info: &crate::learn::LessonInfo) -> String {
    if info.exercises.is_empty() {
        return String::new();
    }
    let mut out = String::from("<h2>Exercises</h2>\n");
    for e in info.exercises {
        out.push_str(&format!(
            "<p><b>{}.</b> {} The file to edit: <code>{}</code>. Get the templates and run \
             yours:</p>\n<pre>classic-gpgpu glsl export DIR --exercises\n# edit DIR/{}, then\n\
             classic-gpgpu learn {} --exercise {} --glsl-dir DIR</pre>\n<p>Without \
             <code>--glsl-dir</code> the shipped solution runs, and says so. A failed check \
             names the first wrong texels with the GPU's value and the CPU's, writes the \
             difference GPU - CPU beside the <code>--png</code> pictures, and shows the first \
             hint; <code>--hint 2</code> and <code>--hint 3</code> come closer to the answer, \
             <code>--solution</code> prints the shipped shader.</p>\n",
            e.number,
            escape(e.task),
            escape(e.shader),
            escape(e.shader),
            info.id,
            e.number
        ));
        match code::exercise_code(e.shader) {
            Ok(code) => out.push_str(&code),
            Err(why) => out.push_str(&format!(
                "<p class=\"fail\">The template could not be shown: {}</p>\n",
                escape(&why)
            )),
        }
    }
    out
}

/// The lesson's host exercise, where it has one: the example the learner edits (every GL call
/// theirs), its gaps or planted faults, and the commands, run from the repository.
fn host_exercise(info: &crate::learn::LessonInfo) -> String {
    let Some(card) = crate::learn::host::for_lesson(info.id) else {
        return String::new();
    };
    let card = card.card();
    let hunt = !card.faults.is_empty();
    let (intro, unit, items, listed) = if hunt {
        (
            "Here you hunt faults in a program that makes its GL calls with glow: find each, \
             fix it, run again; the run says which faults are still there by what they do, \
             and <code>-- --trace</code> and <code>-- --inspect</code> show the calls and the \
             draws.",
            "fault",
            &card.faults,
            "The faults, by their symptoms",
        )
    } else {
        (
            "Here you write the GL calls yourself, with glow: textures, framebuffer, viewport, \
             program and uniforms, the draw and the readback. A gap left unfilled stops the run \
             naming its GL step; the lines after each gap check your step against GL's state; \
             the result is checked against the CPU texel by texel, and your calls are set \
             beside the solution's with the first difference marked.",
            "gap",
            &card.gaps,
            "The gaps, each one GL step",
        )
    };
    let mut out = format!(
        "<h2>Host exercise: {}</h2>\n<p>{intro} The file to edit: <code>{}</code>. Run from \
         the repository (the crate's build is reused: seconds):</p>\n<pre>{}\n{} -- --hint \
         1.1   # {unit} 1: the idea; 1.2 the call; 1.3 the solution's lines\n{}   # the \
         shipped solution, {}</pre>\n<p>{listed}:</p>\n<ol>\n",
        escape(card.title),
        escape(&card.template),
        escape(&card.run),
        escape(&card.run),
        escape(&card.run_solution),
        escape(&card.solution),
    );
    for item in items {
        out.push_str(&format!("<li>{}</li>\n", escape(item)));
    }
    out.push_str("</ol>\n");
    out
}

/// "Terms used here", each linked to its glossary entry: the glossary terms found in `text`.
fn terms_used(text: &str) -> String {
    let found: Vec<String> = GLOSSARY
        .iter()
        .filter(|t| t.cues.iter().any(|cue| contains_word(text, cue)))
        .map(|t| {
            format!(
                "<a href=\"glossary.html#{}\">{}</a>",
                t.anchor,
                escape(t.term)
            )
        })
        .collect();
    if found.is_empty() {
        return String::new();
    }
    format!("<p>Terms used here: {}.</p>\n", found.join(", "))
}

fn contains_word(text: &str, word: &str) -> bool {
    let lower = text.to_lowercase();
    let word = word.to_lowercase();
    lower.match_indices(&word).any(|(at, _)| {
        let before = lower[..at].chars().next_back();
        let after = lower[at + word.len()..].chars().next();
        !before.is_some_and(char::is_alphanumeric) && !after.is_some_and(char::is_alphanumeric)
    })
}

/// A step of the reading order: what it is, what to run, what to read.
/// What to read after the last lesson, as lines for the terminal: the first paper of the
/// reading order, what it does, a command that runs it and the files to read.
pub fn after_the_lessons() -> Vec<String> {
    let Some(paper) = READING.iter().find(|r| r.title.starts_with("Paper")) else {
        return Vec::new();
    };
    let mut lines = vec![format!("next, the papers: {}", paper.title)];
    lines.push(format!("  {}", paper.what));
    if let Some(run) = paper.run.first() {
        lines.push(format!("  run:  {run}"));
    }
    lines.push(format!("  read: {}", paper.read.join(", ")));
    lines.push(
        "  the whole reading order: classic-gpgpu learn --guide DIR, then DIR/reading.html"
            .to_string(),
    );
    lines
}

struct Reading {
    title: &'static str,
    what: &'static str,
    run: &'static [&'static str],
    read: &'static [&'static str],
}

const READING: &[Reading] = &[
    Reading {
        title: "The lessons",
        what: "In order, from lesson 0. Each ends by naming the paper step that uses its idea.",
        run: &[
            "classic-gpgpu learn --list",
            "classic-gpgpu learn 0 --png lesson0/",
        ],
        read: &["src/learn/", "glsl/learn/"],
    },
    Reading {
        title: "Lecture 3's texture tricks",
        what: "The image pyramid (a max quadtree built by passes), a function stored in a \
               texture, random numbers generated into one, an if removed by the depth buffer, \
               a histogram by blending: the lessons' building blocks used once each.",
        run: &[
            "classic-gpgpu lecture3 pyramid",
            "classic-gpgpu lecture3 function",
            "classic-gpgpu lecture3 random",
            "classic-gpgpu lecture3 depth-mask",
            "classic-gpgpu lecture3 histogram",
        ],
        read: &[
            "src/lecture3/pyramid.rs",
            "src/lecture3/function_texture.rs",
            "src/lecture3/random_texture.rs",
            "src/lecture3/depth_mask.rs",
            "src/lecture3/blend_histogram.rs",
        ],
    },
    Reading {
        title: "Paper 3: a neural network as render passes",
        what: "The simplest paper: a matrix product is a quad whose pixels take inner \
               products, the sigmoid a second pass (or a function texture).",
        run: &[
            "classic-gpgpu mlp detect assets/mlp/text.png --out mask.png",
            "classic-gpgpu mlp-bench",
        ],
        read: &[
            "src/mlp/matmul.rs",
            "src/mlp/activation.rs",
            "src/mlp/network.rs",
        ],
    },
    Reading {
        title: "Paper 4: mass properties by depth peeling",
        what: "Depth peeling (lesson 7) finds every layer of a body, MRT writes three \
               integrands per layer, a reduction (lessons 3 and 10) sums them.",
        run: &[
            "classic-gpgpu mass knot --json",
            "classic-gpgpu buoyancy --steps 300 --png-every 50 frames/",
        ],
        read: &[
            "src/mass/peel.rs",
            "src/mass/integrands.rs",
            "src/mass/reduce.rs",
            "src/mass/peel_end.rs",
        ],
    },
    Reading {
        title: "Paper 2: a crowd skinned in a pixel shader",
        what: "Pass 1 skins one vertex per texel, render-to-vertex-buffer (lesson 9) makes it \
               the VBO of pass 2; LOD and culling keep the crowd large.",
        run: &[
            "classic-gpgpu crowd --characters 1024 --png crowd.png",
            "classic-gpgpu crowd-bench",
        ],
        read: &[
            "src/crowd/pass1_skinning.rs",
            "src/crowd/render_to_vbo.rs",
            "src/crowd/pass2_draw.rs",
            "src/crowd/lod.rs",
        ],
    },
    Reading {
        title: "Paper 1: collision detection with streaming AABBs",
        what: "Everything at once: AABB streams in textures, the overlap test as a quad with a \
               stencil mask of the virtual pairs, an occlusion query counting the CAPs \
               (lesson 6), the hierarchical readback of P0 through P1-P3 (lesson 8), then the \
               exact triangle tests.",
        run: &[
            "classic-gpgpu collide-scene interlocking-tori --frames 20",
            "classic-gpgpu collide-bench",
        ],
        read: &[
            "src/collide/stream_setup.rs",
            "src/collide/streaming_test.rs",
            "src/collide/reduction.rs",
            "src/collide/reduction_gpu.rs",
            "src/collide/tri_test.rs",
        ],
    },
    Reading {
        title: "Lecture 3's displacement and light hierarchy",
        what: "Pyramidal displacement mapping traces each pixel through the max pyramid; the \
               indirect light is gathered by a quadtree search of a light hierarchy.",
        run: &[
            "classic-gpgpu lecture3 displace --height assets/lecture3/height.png --png pdm.png",
            "classic-gpgpu lecture3 light --png light.png",
        ],
        read: &[
            "src/lecture3/displacement/",
            "src/lecture3/light_hierarchy/",
        ],
    },
    Reading {
        title: "Then and now",
        what: "Each paper's kernels in their 2007 formulation beside the compute-shader one \
               (OpenGL 4.3), measured in one run; lesson 10 is the small version of this.",
        run: &[
            "classic-gpgpu collide-scene merging-tori --formulation compute --json",
            "classic-gpgpu reproduce --quick --out report",
        ],
        read: &[
            "src/report/then_and_now.rs",
            "src/collide/compute_overlap.rs",
            "src/gl/reduce_shared.rs",
        ],
    },
];

fn reading_page() -> String {
    let mut body = String::from(
        "<h1>Reading order: from the lessons into the papers</h1>\n<p>Each step: what it \
         adds, the commands to run (each checks itself against the CPU and says so), and the \
         files to read.</p>\n<ol>\n",
    );
    let mut all_text = String::new();
    for step in READING {
        all_text.push_str(step.what);
        all_text.push(' ');
        body.push_str(&format!(
            "<li><h2>{}</h2>\n<p>{}</p>\n<pre>",
            escape(step.title),
            escape(step.what)
        ));
        body.push_str(&escape(&step.run.join("\n")));
        body.push_str("</pre>\n<p>Read: ");
        let files: Vec<String> = step
            .read
            .iter()
            .map(|f| format!("<code>{}</code>", escape(f)))
            .collect();
        body.push_str(&files.join(", "));
        body.push_str("</p></li>\n");
    }
    body.push_str("</ol>\n");
    body.push_str(&walk_links());
    body.push_str(&terms_used(&all_text));
    page("Reading order", &body)
}

/// The papers and lectures walked pass by pass ([`super::walks`]), as a list of links.
fn walk_links() -> String {
    let mut out = String::from(
        "<h2>Each paper walked pass by pass</h2>\n<p>Every pass in the order it runs: its \
         section, its code, the buffer it wrote and the lesson it builds on.</p>\n<ul>\n",
    );
    for walk in super::walks::all() {
        out.push_str(&format!(
            "<li><a href=\"{}\">{}</a></li>\n",
            super::walks::page_file(walk.id),
            escape(walk.title)
        ));
    }
    out.push_str("</ul>\n");
    out
}

/// A glossary entry: the term, its anchor, the words that show a page uses it, and what it
/// means.
struct Term {
    term: &'static str,
    anchor: &'static str,
    cues: &'static [&'static str],
    meaning: &'static str,
}

const GLOSSARY: &[Term] = &[
    Term {
        term: "CAP",
        anchor: "cap",
        cues: &["CAP", "CAPs", "colliding pairs"],
        meaning: "Colliding AABB pair (paper 1): two leaf boxes, one from each model, whose \
                  boxes overlap; the pixel of the overlap pass that holds 1 in P0.",
    },
    Term {
        term: "PCTP",
        anchor: "pctp",
        cues: &["PCTP"],
        meaning: "Potentially colliding triangle pair (paper 1): the triangles under a CAP, \
                  which the exact triangle test then confirms or rejects.",
    },
    Term {
        term: "CTP",
        anchor: "ctp",
        cues: &["CTP", "exact triangle"],
        meaning: "Colliding triangle pair (paper 1): a PCTP whose triangles really intersect; \
                  the answer of the collision query.",
    },
    Term {
        term: "PAP",
        anchor: "pap",
        cues: &["PAP", "virtual pairs", "virtual nodes"],
        meaning: "A pair involving a virtual node (paper 1): a slot of the power-of-two stream \
                  that holds no real box. The stencil mask keeps the overlap test off these.",
    },
    Term {
        term: "eta",
        anchor: "eta",
        cues: &["eta"],
        meaning: "The share of P0's pixels that are set (paper 1, section 5.3.2): below 0.095% \
                  the hierarchical readback is cheaper, above it the reduced one.",
    },
    Term {
        term: "P0-P3",
        anchor: "p0-p3",
        cues: &["P0", "P1", "P1-P3", "hierarchical readback"],
        meaning: "Paper 1's readback levels: P0 is the overlap pass's target, one pixel per pair \
                  of boxes; each texel of P1, P2, P3 encodes which texels of a 4x4 block one \
                  level down are set, so the CPU reads P3 and descends only into set blocks.",
    },
    Term {
        term: "peel",
        anchor: "peel",
        cues: &["peel", "peels", "peeling", "layer", "layers"],
        meaning: "One pass of depth peeling: draw again, keeping only fragments behind the depth \
                  the previous pass kept; the depth test then keeps the next layer. Paper 4 \
                  finds a body's surface layers so.",
    },
    Term {
        term: "LOD",
        anchor: "lod",
        cues: &["LOD", "levels of detail"],
        meaning: "Level of detail (paper 2): the same character as meshes of fewer polygons, \
                  chosen by distance so a large crowd costs less.",
    },
    Term {
        term: "ping-pong",
        anchor: "ping-pong",
        cues: &["ping-pong", "reduction", "reduces"],
        meaning: "Two textures used in turn: each pass reads one and writes the other, since a \
                  pass cannot read the texture it writes. Reductions and iterated stencils are \
                  built this way.",
    },
    Term {
        term: "fan-in",
        anchor: "fan-in",
        cues: &["fan-in", "2x2", "256-fold"],
        meaning: "How many inputs one output of a reduction pass combines: 2x2 in the classic \
                  pass, wider blocks for fewer passes, a whole work group in shared memory.",
    },
    Term {
        term: "MRT",
        anchor: "mrt",
        cues: &["MRT", "render targets", "three integrands"],
        meaning: "Multiple render targets: one fragment shader writing several colour \
                  attachments in one pass (paper 4's integrands, paper 2's positions and \
                  normals).",
    },
    Term {
        term: "PBO",
        anchor: "pbo",
        cues: &[
            "PBO",
            "pixel buffer",
            "pixel pack buffer",
            "pixel unpack buffer",
        ],
        meaning: "Pixel buffer object: a GL buffer that pixel transfers read from (unpack) or \
                  write into (pack), so an upload or readback is queued instead of making the \
                  CPU wait, and a readback can stay on the GPU as a vertex buffer.",
    },
    Term {
        term: "VBO",
        anchor: "vbo",
        cues: &["VBO", "vertex buffer"],
        meaning: "Vertex buffer object: the GL buffer a draw reads its vertex attributes from.",
    },
    Term {
        term: "occlusion query",
        anchor: "occlusion-query",
        cues: &["occlusion query", "query"],
        meaning: "Counts the samples that pass every test in a stretch of draw calls; one \
                  number read back instead of a buffer.",
    },
    Term {
        term: "stencil mask",
        anchor: "stencil-mask",
        cues: &["stencil"],
        meaning: "Values in the stencil buffer that a later pass tests, so it runs only on the \
                  pixels a first pass marked.",
    },
    Term {
        term: "transform feedback",
        anchor: "transform-feedback",
        cues: &["transform feedback"],
        meaning: "Captures the vertex shader's outputs into a buffer (OpenGL 3.0), the later \
                  way to compute vertices on the GPU.",
    },
    Term {
        term: "shared memory",
        anchor: "shared-memory",
        cues: &["shared memory", "work group", "compute shader"],
        meaning: "On-chip memory a compute work group shares, with barriers between steps: \
                  what CUDA calls shared memory, and what the fragment pipeline never had.",
    },
];

fn glossary_page() -> String {
    let mut body = String::from(
        "<h1>Glossary</h1>\n<p>The papers' terms, as this project uses them.</p>\n<dl>\n",
    );
    for t in GLOSSARY {
        body.push_str(&format!(
            "<dt id=\"{}\"><b>{}</b></dt><dd>{}</dd>\n",
            t.anchor,
            escape(t.term),
            escape(t.meaning)
        ));
    }
    body.push_str("</dl>\n");
    page("Glossary", &body)
}
