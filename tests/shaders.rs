//! The shader files as a whole: every one compiles and starts with its header (the list comes
//! from `build.rs`, so a new file is covered without editing this test); `glsl list` and
//! `glsl export`; `--glsl-dir` (an edited shader changes a result, a broken one is an error
//! naming the file on disk and its line); and the viewer's live reload, driven headless.

mod common;

use classic_gpgpu::gl::shaders::{self, Stage};
use classic_gpgpu::gl::{Program, ShaderSource};
use classic_gpgpu::view::live::LiveDemo;
use classic_gpgpu::view::{Canvas, DemoSpec, ViewState};
use common::{classic_gpgpu, context, json_of};
use std::path::{Path, PathBuf};

/// Every file under glsl/ and cg_ports/ compiles on this context, with what its header says
/// comes before it; snippets (`*.glsl`) and preludes without a `main()` are compiled inside
/// every file that names them, and each snippet must be named by one. 4.3 stages are
/// compiled where the context has 4.3.
#[test]
fn every_shader_file_compiles() {
    let ctx = context();
    let mut failures = Vec::new();
    let mut compiled = 0;
    let mut skipped = Vec::new();
    for file in shaders::ALL {
        let Some(stage) = Stage::of(file.name) else {
            if !named_by_another(file.name) {
                failures.push(format!(
                    "{}: a snippet that no file names in '{}'",
                    file.name,
                    shaders::COMPILED_AFTER
                ));
            }
            continue;
        };
        // A prefix of other files' stages (a prelude without main()) is compiled inside them.
        if named_by_another(file.name) && !file.source.contains("void main") {
            continue;
        }
        let parts = match shaders::stage_parts(*file) {
            Ok(parts) => parts,
            Err(e) => {
                failures.push(e);
                continue;
            }
        };
        let sources: Vec<ShaderSource> = parts
            .iter()
            .map(|(name, source)| ShaderSource { name, source })
            .collect();
        if required_version(&sources) > ctx.info().gl_version {
            skipped.push(file.name);
            continue;
        }
        match Program::check_compiles(&ctx, stage, &sources) {
            Ok(()) => compiled += 1,
            Err(e) => failures.push(format!("{}: {e}", file.name)),
        }
    }
    eprintln!(
        "{compiled} shader files compiled; {} skipped (stages newer than OpenGL {}): {skipped:?}",
        skipped.len(),
        ctx.info().version
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(compiled >= 60, "only {compiled} compiled");
}

/// Whether another file's header names `name` in its `// Compiled after:` line.
fn named_by_another(name: &str) -> bool {
    shaders::ALL.iter().any(|other| {
        shaders::compiled_after(other.source)
            .iter()
            .any(|n| n == name)
    })
}

/// The OpenGL version a stage needs, from its `#version` lines (4.2 for atomic counters, 4.3 for
/// compute shaders and storage buffers); stages the context cannot run are skipped and listed.
fn required_version(parts: &[ShaderSource]) -> (i32, i32) {
    parts
        .iter()
        .flat_map(|p| p.source.lines())
        .filter_map(|l| l.trim().strip_prefix("#version"))
        .filter_map(|v| v.split_whitespace().next()?.parse::<i32>().ok())
        .map(|v| (v / 100, v / 10 % 10))
        .max()
        .unwrap_or((3, 3))
}

/// The header rule of glsl/README.md: the comment a file starts with names the paper or
/// lecture it implements ("Paper N", "Lecture N"), or, for the shared pieces, says it is a
/// "building block" or part of the "viewer". The lessons (glsl/learn/) follow their own
/// header rule.
#[test]
fn every_shader_file_starts_with_its_header() {
    let missing: Vec<&str> = shaders::ALL
        .iter()
        .filter(|s| !s.name.starts_with("glsl/learn/"))
        .filter(|s| !names_its_source(s.source))
        .map(|s| s.name)
        .collect();
    assert!(
        missing.is_empty(),
        "these files do not start with a header naming 'Paper N', 'Lecture N', 'building \
         block' or 'viewer' (glsl/README.md):\n{}",
        missing.join("\n")
    );
}

fn names_its_source(source: &str) -> bool {
    let header: String = shaders::header_lines(source)
        .collect::<Vec<_>>()
        .join(" ")
        .to_lowercase();
    let numbered = |word: &str| {
        header.match_indices(word).any(|(i, _)| {
            header[i + word.len()..]
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_digit())
        })
    };
    !header.is_empty()
        && (numbered("paper ")
            || numbered("lecture ")
            || header.contains("building block")
            || header.contains("viewer"))
}

#[test]
fn the_header_rule_refuses_a_file_without_one() {
    assert!(names_its_source(
        "// Paper 4, section 3.2: peel.\nvoid main() {}\n"
    ));
    assert!(names_its_source(
        "#version 330 core\n// A building block: reduction.\n"
    ));
    assert!(!names_its_source("#version 330 core\nvoid main() {}\n"));
    assert!(!names_its_source("// Papers and more.\n"));
    // Only the comment the file starts with counts.
    assert!(!names_its_source("// Sums.\nvoid main() {}\n// Paper 1\n"));
}

#[test]
fn glsl_list_names_every_file() {
    let list = json_of(&["glsl", "list", "--json"]);
    let files = list.as_array().expect("an array");
    assert_eq!(files.len(), shaders::ALL.len());
    let paths: Vec<&str> = files.iter().map(|f| f["path"].as_str().unwrap()).collect();
    for s in shaders::ALL {
        assert!(paths.contains(&s.name), "{} missing", s.name);
    }
    let peel_main = files
        .iter()
        .find(|f| f["path"] == "glsl/mass/peel_main.frag")
        .unwrap();
    assert_eq!(peel_main["stage"], "fragment");
    assert!(peel_main["compiled_after"]
        .as_array()
        .unwrap()
        .iter()
        .any(|p| p == "glsl/gl/peel.glsl"));
    let text = classic_gpgpu(&["glsl", "list"]);
    assert!(text.status.success());
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains(&format!("{} shader files", shaders::ALL.len())),
        "{text}"
    );
}

/// Every file written at its own path with its own text; an existing file is kept (and the
/// command fails, naming it) unless --force.
#[test]
fn glsl_export_writes_every_file_and_keeps_existing_ones() {
    let dir = common::temp_dir("shaders", "export");
    let out = classic_gpgpu(&["glsl", "export", dir.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        said.contains(&format!(
            "wrote {} shader files under {}",
            shaders::ALL.len(),
            dir.display()
        )),
        "{said}"
    );
    for s in shaders::ALL {
        let text = std::fs::read_to_string(dir.join(s.name)).unwrap();
        assert_eq!(text, s.source, "{}", s.name);
    }

    let edited = dir.join("glsl/gl/reduce.frag");
    std::fs::write(&edited, "// mine\n").unwrap();
    let again = classic_gpgpu(&["glsl", "export", dir.to_str().unwrap()]);
    assert!(!again.status.success());
    let err = String::from_utf8_lossy(&again.stderr);
    assert!(
        err.contains("exist already") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&edited).unwrap(), "// mine\n");

    let forced = classic_gpgpu(&["glsl", "export", dir.to_str().unwrap(), "--force"]);
    assert!(forced.status.success());
    assert_eq!(
        std::fs::read_to_string(&edited).unwrap(),
        shaders::find("glsl/gl/reduce.frag").unwrap().source
    );
    std::fs::remove_dir_all(dir).ok();
}

/// With --exercises: nothing under glsl/learn/exercises/, and each lesson file is its template
/// where it has one, its solution where not.
#[test]
fn glsl_export_of_the_exercises_puts_templates_in_place_of_solutions() {
    let dir = common::temp_dir("shaders", "export-exercises");
    let summary = json_of(&[
        "glsl",
        "export",
        dir.to_str().unwrap(),
        "--exercises",
        "--json",
    ]);
    assert!(!dir.join(shaders::EXERCISES).exists());
    let templates = shaders::ALL
        .iter()
        .filter(|s| s.name.starts_with(shaders::EXERCISES))
        .count();
    assert_eq!(
        summary["written"].as_u64().unwrap() as usize,
        shaders::ALL.len() - templates
    );
    for s in shaders::ALL {
        let (path, want) = match s.name.strip_prefix(shaders::EXERCISES) {
            Some(rest) => (format!("glsl/learn/{rest}"), s.source),
            None => {
                let template = s
                    .name
                    .strip_prefix("glsl/learn/")
                    .and_then(|rest| shaders::find(&format!("{}{rest}", shaders::EXERCISES)));
                (s.name.to_string(), template.map_or(s.source, |t| t.source))
            }
        };
        assert_eq!(
            std::fs::read_to_string(dir.join(&path)).unwrap(),
            want,
            "{path}"
        );
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_missing_glsl_dir_is_an_error() {
    let out = classic_gpgpu(&["--glsl-dir", "/no/such/folder", "info"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--glsl-dir /no/such/folder: no such folder"),
        "{err}"
    );
}

/// The section 3.1 listing with its first output doubled: every integral doubles, so the
/// volume `mass` reports does (the same pixels are summed).
const DOUBLED: (&str, &str) = ("FragData[0] = c * p;", "FragData[0] = 2.0 * c * p;");
/// A syntax error on line 19 of the listing (after the last statement of main()'s first line).
const BROKEN: (&str, &str) = ("FragData[0] = c * p;", "FragData[0] = c * p +;");
const LISTING: &str = "cg_ports/mass_integrands.frag";

fn write_listing(dir: &Path, (from, to): (&str, &str)) -> PathBuf {
    let original = shaders::find(LISTING).unwrap().source;
    assert!(original.contains(from));
    let path = dir.join(LISTING);
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(&path, original.replace(from, to)).unwrap();
    path
}

fn line_of(path: &Path, text: &str) -> usize {
    let source = std::fs::read_to_string(path).unwrap();
    source.lines().position(|l| l.contains(text)).unwrap() + 1
}

#[test]
fn glsl_dir_shaders_change_the_result_and_errors_name_the_file_on_disk() {
    let dir = common::temp_dir("shaders", "glsl-dir");
    let args = ["mass", "cube", "--resolution", "16", "--json"];
    let plain = json_of(&args);
    let volume = plain["volume"].as_f64().unwrap();
    assert!((volume - plain["analytic"]["volume"].as_f64().unwrap()).abs() < 0.01 * volume);

    // A folder without the file: the compiled-in copy, the same result.
    let with = |args: &[&str]| {
        let mut all = vec!["--glsl-dir", dir.to_str().unwrap()];
        all.extend_from_slice(args);
        all.iter().map(|s| s.to_string()).collect::<Vec<_>>()
    };
    let same = json_of(&with(&args).iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(same["volume"], plain["volume"]);

    write_listing(&dir, DOUBLED);
    let doubled = json_of(&with(&args).iter().map(String::as_str).collect::<Vec<_>>());
    let got = doubled["volume"].as_f64().unwrap();
    // The same pixels summed with every term doubled: exactly twice in fp32 (a power of two).
    assert_eq!(got, 2.0 * volume, "doubled listing: {got} vs {volume}");

    let path = write_listing(&dir, BROKEN);
    let line = line_of(&path, "c * p +;");
    let out = classic_gpgpu(&with(&args).iter().map(String::as_str).collect::<Vec<_>>());
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(&format!("{}:{line}", path.display())),
        "the error must name {}:{line}:\n{err}",
        path.display()
    );
    assert!(
        err.contains("c * p +;"),
        "the excerpt shows the line:\n{err}"
    );
    std::fs::remove_dir_all(dir).ok();
}

/// The viewer's reload as the window drives it, headless: a good edit is picked up (a new
/// frame), a broken one keeps the last good demo running with the error in the overlay, and
/// mending it reloads again. Files are given distinct modification times so that the polling
/// is deterministic.
#[test]
fn the_viewer_reloads_edited_shaders_and_keeps_the_last_good_demo() {
    let ctx = context();
    let dir = common::temp_dir("shaders", "live");
    ctx.set_glsl_dir(Some(dir.clone()));
    let spec = DemoSpec::Mass {
        model: "cube".into(),
        resolution: 16,
    };
    let size = (320, 240);
    let canvas = Canvas::new(&ctx, size.0, size.1).unwrap();
    let view = ViewState::default();
    let mut live = LiveDemo::new(&spec, &ctx, size, "").unwrap();
    assert!(live.watching());
    for _ in 0..2 {
        live.step().unwrap();
    }
    let frame = |live: &mut LiveDemo| {
        live.draw(&canvas, &view).unwrap();
        canvas.pixels().unwrap()
    };
    let original = frame(&mut live);
    let original_text = live.demo().overlay();
    assert_eq!(live.poll(&ctx), None, "nothing changed yet");

    let mut clock = std::time::SystemTime::now();
    let mut touch = |path: &Path| {
        clock += std::time::Duration::from_secs(2);
        let file = std::fs::File::options().write(true).open(path).unwrap();
        file.set_modified(clock).unwrap();
    };

    // Good: the volume doubles, the frame changes, the step count is kept.
    let path = write_listing(&dir, DOUBLED);
    touch(&path);
    assert_eq!(live.poll(&ctx), Some(true));
    assert_eq!(live.steps(), 2);
    assert!(live.error().is_none());
    let doubled = frame(&mut live);
    let doubled_text = live.demo().overlay();
    assert_ne!(doubled_text, original_text);
    assert_ne!(doubled, original);

    // Broken: the error (file on disk and line) is shown, the doubled demo keeps running.
    let broken = write_listing(&dir, BROKEN);
    touch(&broken);
    let line = line_of(&broken, "c * p +;");
    assert_eq!(live.poll(&ctx), Some(false));
    let error = live
        .error()
        .expect("the error is kept for the overlay")
        .to_string();
    assert!(
        error.starts_with(&format!("{}:{line}: ", broken.display())),
        "{error}"
    );
    assert!(error.len() > format!("{}:{line}: ", broken.display()).len());
    assert_eq!(live.demo().overlay(), doubled_text, "the last good demo");
    let with_error = frame(&mut live);
    assert_ne!(with_error, doubled, "the error is drawn");
    // The text box is the bottom rows of the frame; the rows above it are the doubled frame's.
    let row = size.0 as usize * 4;
    let top = (size.1 as usize - 20) * row;
    assert_eq!(with_error[top..], doubled[top..]);
    live.step().unwrap();

    // Mended: back to the listing as shipped, the original result at the same step count.
    let mended = write_listing(&dir, ("", ""));
    touch(&mended);
    assert_eq!(live.poll(&ctx), Some(true));
    assert!(live.error().is_none());
    assert_eq!(live.steps(), 3);
    let mut reference = LiveDemo::new(&spec, &ctx, size, "").unwrap();
    for _ in 0..3 {
        reference.step().unwrap();
    }
    assert_eq!(frame(&mut live), frame(&mut reference));
    std::fs::remove_dir_all(dir).ok();
}
