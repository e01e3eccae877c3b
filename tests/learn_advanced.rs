//! The lessons of the second half (counting and masks, depth peeling, readback and upload,
//! render to vertex buffer, compute reduction): each passes against its CPU reference, each
//! exercise's solution passes, each unfilled template fails, and the guide built from the
//! runs has no dead link or picture.

mod common;

use classic_gpgpu::learn::{self, LessonOptions};
use std::path::{Path, PathBuf};

const LESSONS: [&str; 5] = [
    "count-and-mask",
    "depth-peeling",
    "readback-and-upload",
    "render-to-vertex-buffer",
    "compute-reduction",
];

fn print_run(run: &learn::LessonRun) {
    println!("{} on {}: passed {}", run.id, run.renderer, run.passed);
    for c in &run.checks {
        println!(
            "  {} {}: {} (tolerance {})",
            if c.passed { "ok  " } else { "FAIL" },
            c.what,
            c.max_error,
            c.tolerance
        );
    }
    println!("  compute: {:?}", run.compute);
}

#[test]
fn every_lesson_passes_against_the_cpu() {
    let ctx = common::context();
    let pictures = common::temp_dir("learn-advanced", "pictures");
    for id in LESSONS {
        let lesson = learn::find(id).unwrap();
        let opts = LessonOptions {
            png_dir: Some(pictures.join(id)),
            exercise: None,
        };
        let run = lesson.run(&ctx, &opts).unwrap();
        print_run(&run);
        assert!(run.passed, "{id} failed: {:?}", run.checks);
        assert!(!run.checks.is_empty());
        assert!(run.max_error.is_finite());
        for pass in &run.passes {
            if let Some(p) = &pass.picture {
                assert!(pictures.join(id).join(p).is_file(), "{id}: {p} missing");
            }
        }
        for shader in &run.shaders {
            assert!(Path::new(env!("CARGO_MANIFEST_DIR")).join(shader).is_file());
        }
        // The compute counterpart ran exactly where the context has compute shaders.
        let compute = run.compute.as_deref().unwrap_or("");
        assert_eq!(
            compute.starts_with("ran"),
            ctx.has_compute(),
            "{id}: {compute}"
        );
        if !ctx.has_compute() {
            assert!(compute.contains("4.3"), "{id}: {compute}");
            assert!(run.checks.iter().all(|c| !c.what.starts_with("compute")));
        }
    }
}

/// Every exercise of these lessons: the shipped solution passes, the template (given through
/// a glsl folder, as a learner would) fails its check and gives the hint.
#[test]
fn solutions_pass_and_templates_fail() {
    let ctx = common::context();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for id in LESSONS {
        let lesson = learn::find(id).unwrap();
        for exercise in lesson.info().exercises {
            let opts = LessonOptions {
                png_dir: None,
                exercise: Some(exercise.number),
            };
            let template = exercise
                .shader
                .replacen("glsl/learn/", "glsl/learn/exercises/", 1);
            let template_text = std::fs::read_to_string(root.join(&template)).unwrap();
            assert!(template_text.contains("// EXERCISE:"), "{template}");
            if !ctx.has_compute() && exercise.shader.ends_with(".comp") {
                ctx.set_glsl_dir(None);
                let err = lesson.run(&ctx, &opts).expect_err("an error without 4.3");
                assert!(err.to_string().contains("4.3"), "{err}");
                println!("{id} exercise {}: needs 4.3 here", exercise.number);
                continue;
            }
            ctx.set_glsl_dir(None);
            let solved = lesson.run(&ctx, &opts).unwrap();
            assert!(solved.passed, "{id} solution {}", exercise.number);
            assert!(solved.hint.is_none());

            let dir = common::temp_dir("learn-advanced", &format!("{id}-{}", exercise.number));
            let learner = dir.join(exercise.shader);
            std::fs::create_dir_all(learner.parent().unwrap()).unwrap();
            std::fs::write(&learner, &template_text).unwrap();
            ctx.set_glsl_dir(Some(dir.clone()));
            let unfilled = lesson.run(&ctx, &opts);
            ctx.set_glsl_dir(None);
            let unfilled = unfilled.unwrap();
            print_run(&unfilled);
            assert!(
                !unfilled.passed,
                "{id}: the unfilled template {template} passed"
            );
            assert_eq!(unfilled.hint.as_deref(), Some(exercise.hints[0]));
        }
    }
}

/// Every `href` and `src` of the guide's pages: (page, target).
fn guide_links(dir: &Path) -> Vec<(PathBuf, String)> {
    let mut links = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let page = entry.unwrap().path();
        if page.extension().is_none_or(|e| e != "html") {
            continue;
        }
        let html = std::fs::read_to_string(&page).unwrap();
        let dom = tl::parse(&html, tl::ParserOptions::default()).unwrap();
        for node in dom.nodes() {
            let Some(tag) = node.as_tag() else { continue };
            for attribute in ["href", "src"] {
                if let Some(Some(value)) = tag.attributes().get(attribute) {
                    links.push((page.clone(), value.as_utf8_str().to_string()));
                }
            }
        }
    }
    links
}

/// The ids a page declares (`id="..."`), for `page.html#id` links.
fn page_ids(page: &Path) -> Vec<String> {
    let html = std::fs::read_to_string(page).unwrap();
    let dom = tl::parse(&html, tl::ParserOptions::default()).unwrap();
    dom.nodes()
        .iter()
        .filter_map(|n| n.as_tag())
        .filter_map(|t| t.attributes().id().map(|id| id.as_utf8_str().to_string()))
        .collect()
}

#[test]
fn the_guide_builds_and_every_link_and_picture_resolves() {
    let ctx = common::context();
    let dir = common::temp_dir("learn-advanced", "guide").join("guide");
    let written = classic_gpgpu::learn::guide::write_guide(&ctx, &dir, false).unwrap();
    assert!(written.lessons.len() >= LESSONS.len());
    for id in LESSONS {
        assert!(written.lessons.iter().any(|(l, ok)| l == id && *ok), "{id}");
        assert!(dir.join(format!("lesson-{id}.html")).is_file());
    }
    let links = guide_links(&dir);
    let pictures = links.iter().filter(|(_, l)| l.ends_with(".png")).count();
    assert!(pictures >= 10, "only {pictures} pictures");
    for (page, link) in &links {
        assert!(
            !link.contains("://"),
            "{}: external link {link}",
            page.display()
        );
        let (file, fragment) = link.split_once('#').unwrap_or((link, ""));
        let target = if file.is_empty() {
            page.clone()
        } else {
            dir.join(file)
        };
        assert!(target.is_file(), "{}: dead link {link}", page.display());
        if !fragment.is_empty() {
            assert!(
                page_ids(&target).iter().any(|id| id == fragment),
                "{}: no #{fragment} in {}",
                page.display(),
                target.display()
            );
        }
    }
    // The index says once how the pictures map values to colours.
    let index = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert!(index.contains("zero is always the same dark grey"));
    // The glossary is linked from the lesson pages that use its terms.
    let peeling = std::fs::read_to_string(dir.join("lesson-depth-peeling.html")).unwrap();
    assert!(peeling.contains("glossary.html#peel"));
    // Each host exercise is on its lesson's page: the file to edit, which exists, and the
    // commands that run it and its solution; a lesson without one has no such section.
    for card in classic_gpgpu::learn::host::all() {
        let page =
            std::fs::read_to_string(dir.join(format!("lesson-{}.html", card.lesson))).unwrap();
        for text in [
            card.template(),
            card.run_command(),
            card.run_solution_command(),
        ] {
            assert!(page.contains(&text), "lesson-{}: no {text}", card.lesson);
        }
        let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        assert!(repo.join(card.template()).is_file(), "{}", card.template());
        assert!(repo.join(card.solution()).is_file(), "{}", card.solution());
    }
    let blending = std::fs::read_to_string(dir.join("lesson-scatter-and-blend.html")).unwrap();
    assert!(!blending.contains("Host exercise"));

    // Written again into its own folder: fine. A folder of someone else's: refused, unless
    // forced, and nothing in it lost.
    classic_gpgpu::learn::guide::write_guide(&ctx, &dir, false).unwrap();
    let theirs = common::temp_dir("learn-advanced", "guide-theirs");
    std::fs::write(theirs.join("notes.txt"), "mine").unwrap();
    let err = classic_gpgpu::learn::guide::write_guide(&ctx, &theirs, false).unwrap_err();
    assert!(err.to_string().contains("--force"), "{err}");
    assert_eq!(
        std::fs::read_to_string(theirs.join("notes.txt")).unwrap(),
        "mine"
    );
    classic_gpgpu::learn::guide::write_guide(&ctx, &theirs, true).unwrap();
    assert_eq!(
        std::fs::read_to_string(theirs.join("notes.txt")).unwrap(),
        "mine"
    );
}

/// Headless Chromium loads every page of the guide; a script in a checker page (written
/// beside, not into, the guide) looks at every picture (decoded, non-zero size) and fetches
/// every link. Skipped, saying why, where no Chromium is installed.
#[test]
fn the_guide_renders_in_headless_chromium() {
    let Some(chromium) = ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|c| {
            std::process::Command::new(c)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        })
    else {
        println!("skipped: no chromium, chromium-browser or google-chrome on PATH");
        return;
    };
    let ctx = common::context();
    let root = common::temp_dir("learn-advanced", "guide-chromium");
    let dir = root.join("guide");
    let written = classic_gpgpu::learn::guide::write_guide(&ctx, &dir, false).unwrap();
    let checker = root.join("check.html");
    std::fs::write(&checker, CHECKER).unwrap();
    for page in &written.pages {
        let url = format!(
            "file://{}?page={}",
            checker.display(),
            page.file_name().unwrap().to_string_lossy()
        );
        let out = std::process::Command::new(chromium)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--allow-file-access-from-files",
                "--virtual-time-budget=20000",
                "--dump-dom",
                &url,
            ])
            .output()
            .unwrap();
        let dom = String::from_utf8_lossy(&out.stdout);
        let verdict = dom
            .split("RESULT[")
            .nth(1)
            .and_then(|r| r.split(']').next())
            .unwrap_or("no result");
        println!("{}: {verdict}", page.display());
        assert!(
            verdict.starts_with("ok"),
            "{}: {verdict}\n{}",
            page.display(),
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// Loads `guide/<page>` in a frame, then checks its pictures and links.
const CHECKER: &str = r##"<!DOCTYPE html><html><body><iframe id="f" width="1280" height="900"></iframe>
<pre id="out"></pre><script>
const page = new URLSearchParams(location.search).get("page");
const out = document.getElementById("out");
const frame = document.getElementById("f");
function exists(url) {
  return new Promise(done => {
    const x = new XMLHttpRequest();
    x.onload = () => done(x.responseText.length > 0);
    x.onerror = () => done(false);
    try { x.open("GET", url); x.send(); } catch (e) { done(false); }
  });
}
frame.onload = async () => {
  const doc = frame.contentDocument;
  if (!doc || !doc.body) { out.textContent = "RESULT[no document]"; return; }
  const broken = [];
  const images = [...doc.images];
  for (const img of images) {
    if (!img.complete || img.naturalWidth === 0) broken.push("picture " + img.getAttribute("src"));
  }
  const links = [...doc.querySelectorAll("a[href]")];
  for (const a of links) {
    const target = a.href.split("#")[0];
    if (!(await exists(target))) broken.push("link " + a.getAttribute("href"));
  }
  out.textContent = broken.length === 0
    ? "RESULT[ok: " + images.length + " pictures, " + links.length + " links]"
    : "RESULT[broken: " + broken.join(", ") + "]";
};
frame.src = "guide/" + page;
</script></body></html>
"##;
