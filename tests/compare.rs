//! `classic-gpgpu compare`: the kept results of several machines side by side, the refusals
//! (mixed sizes, mixed versions of the claims, a file that is not a results.json), the
//! folder it writes, and the README's table generated from the kept results.

use classic_gpgpu::compare::{self, headline, markdown, run};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The kept results, sorted by name (the order `assets/results/*.json` gives in a shell).
fn kept() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/results");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("assets/results/ holds the kept results")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    files
}

/// A fresh scratch folder for one test.
/// The kept results in groups that can share a page: the same sizes and claims version
/// (softpipe's kept run is a quick one beside full llvmpipe and zink runs).
fn kept_groups() -> Vec<Vec<PathBuf>> {
    let mut groups: Vec<(bool, String, Vec<PathBuf>)> = Vec::new();
    for file in kept() {
        let run = run::Run::read(&file).unwrap();
        match groups
            .iter_mut()
            .find(|(quick, version, _)| *quick == run.quick && *version == run.claims_version)
        {
            Some(group) => group.2.push(file),
            None => groups.push((run.quick, run.claims_version.clone(), vec![file])),
        }
    }
    groups.into_iter().map(|(_, _, files)| files).collect()
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "classic-gpgpu-compare-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn compare_cli(args: &[&Path], extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .arg("compare")
        .args(args)
        .args(extra)
        .output()
        .expect("the binary runs")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A copy of the first kept results.json in `dir`, changed by `edit`.
fn edited_copy(dir: &Path, name: &str, edit: impl FnOnce(&mut serde_json::Value)) -> PathBuf {
    let mut value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&kept()[0]).unwrap()).unwrap();
    edit(&mut value);
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_string(&value).unwrap()).unwrap();
    path
}

#[test]
fn there_are_kept_results_of_three_renderers_named_by_machine_and_commit() {
    let files = kept();
    assert!(files.len() >= 3, "{files:?}");
    for file in &files {
        let run = run::Run::read(file).unwrap();
        let name = file.file_name().unwrap().to_string_lossy();
        assert_eq!(name, run.kept_name(), "{}", file.display());
        assert!(!run.commit.is_empty() && !run.claims_version.is_empty());
    }
}

#[test]
fn mixed_sizes_are_refused_with_the_files_named() {
    let dir = scratch("sizes");
    // The same run, said to be at the other sizes.
    let full = edited_copy(&dir, "other-size.json", |v| {
        v["quick"] = serde_json::json!(v["quick"] != true)
    });
    let quick = kept()[0].clone();
    let out = dir.join("page");
    let run = compare_cli(&[&quick, &full], &["--out", out.to_str().unwrap()]);
    assert!(!run.status.success());
    let e = stderr(&run);
    assert!(e.contains("different sizes"), "{e}");
    assert!(
        e.contains("other-size.json") && e.contains(&*quick.to_string_lossy()),
        "{e}"
    );
    assert!(!e.contains("panicked"), "{e}");
    assert!(
        !out.exists(),
        "a refused comparison wrote {}",
        out.display()
    );
    // The library says the same.
    let runs = [
        run::Run::read(&quick).unwrap(),
        run::Run::read(&full).unwrap(),
    ];
    assert!(compare::comparable(&runs).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn mixed_versions_of_the_claims_are_refused() {
    let dir = scratch("versions");
    let other = edited_copy(&dir, "other.json", |v| {
        v["claims_version"] = serde_json::json!("0123456789abcdef")
    });
    let page = dir.join("page");
    let run = compare_cli(&[&kept()[0], &other], &["--out", page.to_str().unwrap()]);
    assert!(!run.status.success());
    let e = stderr(&run);
    assert!(e.contains("different versions of the claims"), "{e}");
    assert!(e.contains("0123456789abcdef"), "{e}");
    assert!(!page.exists(), "a refused comparison wrote a page");
    // The README's text puts each version in a table of its own, under its heading.
    let run = compare_cli(&[&kept()[0], &other], &["--markdown"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = String::from_utf8_lossy(&run.stdout);
    assert_eq!(text.matches("| paper | claim |").count(), 2, "{text}");
    assert!(text.contains("(claims version 0123456789abcdef)"), "{text}");

    // A results.json from before the version was recorded is refused too.
    let old = edited_copy(&dir, "old.json", |v| {
        v.as_object_mut().unwrap().remove("claims_version");
    });
    let run = compare_cli(&[&old], &["--markdown"]);
    assert!(!run.status.success());
    assert!(
        stderr(&run).contains("does not record which version"),
        "{}",
        stderr(&run)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_file_that_is_not_results_json_is_named() {
    let dir = scratch("bad");
    let bad = dir.join("notes.json");
    std::fs::write(&bad, "{\"mine\": 1}").unwrap();
    let run = compare_cli(&[&bad], &["--out", dir.join("page").to_str().unwrap()]);
    assert!(!run.status.success());
    let e = stderr(&run);
    assert!(
        e.contains("notes.json") && e.contains("not a results.json"),
        "{e}"
    );
    let missing = dir.join("missing.json");
    let run = compare_cli(&[&missing], &["--markdown"]);
    assert!(!run.status.success());
    assert!(stderr(&run).contains("missing.json"), "{}", stderr(&run));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_page_shows_every_claim_of_every_machine() {
    let dir = scratch("page");
    let out = dir.join("page");
    // The largest group of kept runs that can share a page.
    let files = kept_groups().into_iter().max_by_key(Vec::len).unwrap();
    assert!(files.len() >= 2, "{files:?}");
    let args: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    let run = compare_cli(&args, &["--out", out.to_str().unwrap()]);
    assert!(run.status.success(), "{}", stderr(&run));

    let comparison: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("comparison.json")).unwrap())
            .unwrap();
    let machines = comparison["machines"].as_array().unwrap();
    assert_eq!(machines.len(), files.len());
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    for (m, file) in machines.iter().zip(&files) {
        // Each machine's renderer, GL version, CPU, date, commit and command line.
        for key in ["renderer", "gl_version", "cpu", "date", "commit"] {
            let v = m[key].as_str().unwrap();
            assert!(!v.is_empty(), "{key} of {}", file.display());
            assert!(html.contains(&escape(v)), "the page lacks {key} {v}");
        }
        assert!(html.contains(&escape(m["command_line"][1].as_str().unwrap())));
    }
    // Every claim of every input is a row, with a cell per machine.
    let rows = comparison["claims"].as_array().unwrap();
    for file in &files {
        let results: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
        for section in results["sections"].as_array().unwrap() {
            for claim in section["claims"].as_array().unwrap() {
                let text = claim["claim"].as_str().unwrap();
                let row = rows
                    .iter()
                    .find(|r| r["section"] == section["id"] && r["claim"] == text)
                    .unwrap_or_else(|| panic!("no row for '{text}'"));
                assert_eq!(row["cells"].as_array().unwrap().len(), files.len());
                assert!(html.contains(&escape(claim["measured"].as_str().unwrap())));
            }
        }
    }
    // The figures the page shows are there, with the legend below the axes.
    for figure in ["headline_ratios.png", "then_and_now.png"] {
        if html.contains(figure) {
            let image = image::open(out.join(figure)).unwrap();
            assert!(image.width() >= 900 && image.height() > 520, "{figure}");
        }
    }
    assert!(html.contains("headline_ratios.png"), "no headline plot");

    // Run again into its own folder: allowed, and nothing else is left there.
    let again = compare_cli(&args, &["--out", out.to_str().unwrap()]);
    assert!(again.status.success(), "{}", stderr(&again));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The page's escaping of a text (as html.rs does it).
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[test]
fn the_out_folder_is_only_ever_the_pages_own() {
    let dir = scratch("folder");
    let input = kept()[0].clone();
    // A folder of someone else's: refused without --force.
    let foreign = dir.join("mine");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "mine").unwrap();
    let run = compare_cli(&[&input], &["--out", foreign.to_str().unwrap()]);
    assert!(!run.status.success());
    assert!(stderr(&run).contains("--force"), "{}", stderr(&run));
    assert!(!foreign.join("index.html").exists());
    // With --force the page is added; the user's file stays.
    let run = compare_cli(&[&input], &["--out", foreign.to_str().unwrap(), "--force"]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(foreign.join("index.html").is_file());
    assert_eq!(
        std::fs::read_to_string(foreign.join("notes.txt")).unwrap(),
        "mine"
    );
    // A user's index.html is never replaced, not even with --force.
    let theirs = dir.join("theirs");
    std::fs::create_dir_all(&theirs).unwrap();
    std::fs::write(theirs.join("index.html"), "theirs").unwrap();
    let run = compare_cli(&[&input], &["--out", theirs.to_str().unwrap(), "--force"]);
    assert!(!run.status.success());
    assert_eq!(
        std::fs::read_to_string(theirs.join("index.html")).unwrap(),
        "theirs"
    );
    // A report of `reproduce` is never written into: its page would be lost.
    let report = dir.join("report");
    std::fs::create_dir_all(&report).unwrap();
    let mut owned = classic_gpgpu::page::folder::Owned::default();
    owned.add("-", "index.html");
    owned.add("-", "results.json");
    std::fs::write(report.join("index.html"), "the report").unwrap();
    owned.write(&report).unwrap();
    let run = compare_cli(&[&input], &["--out", report.to_str().unwrap(), "--force"]);
    assert!(!run.status.success());
    assert!(stderr(&run).contains("reproduce"), "{}", stderr(&run));
    assert_eq!(
        std::fs::read_to_string(report.join("index.html")).unwrap(),
        "the report"
    );
    // A file as --out.
    let file = dir.join("file");
    std::fs::write(&file, "x").unwrap();
    let run = compare_cli(&[&input], &["--out", file.to_str().unwrap()]);
    assert!(!run.status.success());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn every_headline_figure_is_read_from_every_kept_run() {
    for group in kept_groups() {
        headline_figures_are_read(&group);
    }
}

fn headline_figures_are_read(files: &[PathBuf]) {
    let runs = compare::read(files).unwrap();
    let comparison = compare::compare(runs).unwrap();
    // Every headline, unless every machine left its section out (`--only`).
    let partial = comparison
        .machines
        .iter()
        .all(|m| m.command_line.iter().any(|a| a == "--only"));
    if partial {
        assert!(!comparison.headlines.is_empty());
        assert!(comparison.headlines.len() <= headline::headlines().len());
    } else {
        assert_eq!(comparison.headlines.len(), headline::headlines().len());
    }
    for row in &comparison.headlines {
        for (cell, machine) in row.cells.iter().zip(&comparison.machines) {
            // A kept run may leave sections out (`--only`): then the section says so.
            if cell.verdict == "not run" {
                assert!(
                    machine.command_line.iter().any(|a| a == "--only"),
                    "{} not run on {}, which ran every section",
                    row.label,
                    machine.label
                );
                continue;
            }
            let figure = cell
                .figure
                .as_ref()
                .unwrap_or_else(|| panic!("no figure for '{}' on {}", row.label, machine.label));
            assert!(!figure.text.is_empty());
            if !row.ratio.is_empty() {
                // 0 where the claim printed "0.00" (a log axis leaves that point out).
                let ratio = figure.ratio.expect("a ratio to plot");
                assert!(ratio.is_finite() && ratio >= 0.0, "{} {ratio}", row.label);
            }
        }
    }
    // The then-and-now figure of a machine with compute shaders is the frame's ratio.
    for row in &comparison.then_and_now {
        for cell in &row.cells {
            assert!(
                cell.ratio.is_some_and(|r| r.is_finite() && r > 0.0) || !cell.note.is_empty(),
                "{} {}: neither a ratio nor why not",
                row.machine,
                cell.section
            );
        }
    }
}

#[test]
fn the_readme_table_is_the_one_compare_prints_from_the_kept_results() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let in_readme = markdown::between_markers(&readme).unwrap();
    let printed = markdown::grouped(&kept()).unwrap();
    assert!(
        in_readme == printed,
        "README.md's table between {} and {} differs from what `classic-gpgpu compare \
         --markdown assets/results/*.json` prints; put the printed text there. It prints:\n{printed}",
        markdown::BEGIN,
        markdown::END
    );
    // No figure of the table is typed: every column is a kept file.
    for file in kept() {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        assert!(
            printed.contains(&format!("assets/results/{name}")),
            "{name}"
        );
    }
}

#[test]
fn markdown_puts_runs_of_other_sizes_in_their_own_table() {
    let dir = scratch("grouped");
    let quick = kept()[0].clone();
    let was_quick = run::Run::read(&quick).unwrap().quick;
    let other = edited_copy(&dir, "other-size.json", |v| {
        v["quick"] = serde_json::json!(!was_quick)
    });
    let text = markdown::grouped(&[quick, other]).unwrap();
    // Two groups, each its own table under its own heading, the papers' sizes first.
    assert_eq!(text.matches("#### ").count(), 2, "{text}");
    assert_eq!(text.matches("| paper | claim |").count(), 2, "{text}");
    let full_at = text
        .find("#### Runs at the papers' sizes")
        .expect("a full group");
    let quick_at = text.find("#### `--quick` runs").expect("a quick group");
    assert!(full_at < quick_at, "{text}");
    // One group alone has no heading, as the README's single table.
    let alone = markdown::grouped(&kept()[..1]).unwrap();
    assert!(!alone.contains("#### "), "{alone}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn figures_are_read_from_the_claims_words() {
    assert_eq!(headline::leading_number("12.5 ms"), Some((12.5, " ms")));
    assert_eq!(headline::leading_number("46.18x on"), Some((46.18, "x on")));
    assert_eq!(headline::leading_number("6. The"), Some((6.0, ". The")));
    assert_eq!(headline::leading_number("x"), None);
    assert_eq!(
        headline::range_after(
            "SOLID / streaming 0.09-0.24x without download, 0.08-0.20x with it",
            "without download, "
        ),
        Some((0.08, 0.20))
    );
    assert_eq!(headline::number_after("= 0.06x on", "= "), Some(0.06));
    assert_eq!(
        headline::range_after("missed 7%", "missed "),
        Some((7.0, 7.0))
    );
}

#[test]
fn renderers_get_short_names_and_commits_short_hashes() {
    assert_eq!(
        run::short_name("llvmpipe (LLVM 15.0.6, 256 bits)"),
        "llvmpipe"
    );
    assert_eq!(
        run::short_name("zink Vulkan 1.3(llvmpipe (LLVM 15.0.6, 256 bits) (MESA_LLVMPIPE))"),
        "zink"
    );
    assert_eq!(
        run::short_name("NVIDIA H100 80GB HBM3/PCIe/SSE2"),
        "NVIDIA H100 80GB HBM3"
    );
    assert_eq!(run::short_name(""), "unknown renderer");
    assert_eq!(run::slug("NVIDIA H100 80GB HBM3"), "nvidia-h100-80gb-hbm3");
    assert_eq!(run::range(1.0, 1.001), "1.00");
    assert_eq!(run::range(0.5, 1.25), "0.50-1.25");
}
