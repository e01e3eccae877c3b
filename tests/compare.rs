//! `classic-gpgpu compare`: the kept results of several machines and builds side by side (runs
//! of other sizes in a group of their own, a claim whose version differs shown per version,
//! runs from before per-claim versions as their own version: nothing refused), the bounds on
//! what a results.json may hold, the folder it writes, the README's table generated from the
//! kept results with every text escaped, and the regression gate (`--baseline`).

use classic_gpgpu::compare::{self, headline, markdown, run};
use classic_gpgpu::report::{claim_defs, versions};
use serde_json::{json, Value};
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

/// The first kept run at the papers' sizes that ran every section.
fn full_kept() -> PathBuf {
    kept()
        .into_iter()
        .find(|f| {
            let run = run::Run::read(f).unwrap();
            !run.quick && run.sections.len() >= 7
        })
        .expect("a kept run of every section at the papers' sizes")
}

/// A fresh scratch folder for one test.
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

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn write_json(dir: &Path, name: &str, value: &Value) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_string(value).unwrap()).unwrap();
    path
}

/// A kept run as this build would record it: a claim without an id gets one (a headline's
/// where its words say which, else one made up from its section and place), and every claim
/// without a version this build's version of it (or a made-up one).
fn as_this_build(mut value: Value) -> Value {
    let quick = value["quick"] == true;
    for section in value["sections"].as_array_mut().unwrap() {
        let id = section["id"].as_str().unwrap().to_string();
        for (i, claim) in section["claims"]
            .as_array_mut()
            .unwrap()
            .iter_mut()
            .enumerate()
        {
            if claim["id"].as_str().unwrap_or("").is_empty() {
                let words = claim["claim"].as_str().unwrap().to_string();
                let known = headline::headlines()
                    .into_iter()
                    .find(|h| h.section == id && words.contains(h.claim))
                    .map(|h| h.id.to_string());
                claim["id"] = json!(known.unwrap_or(format!("{id}.claim-{i}")));
            }
            if claim["version"].as_str().unwrap_or("").is_empty() {
                let version = compare::current_version(claim["id"].as_str().unwrap(), quick);
                claim["version"] = json!(version.unwrap_or("0123456789abcdef".into()));
            }
        }
    }
    value
}

/// A copy of the full kept run as this build would record it, changed by `edit`.
fn this_build_copy(dir: &Path, name: &str, edit: impl FnOnce(&mut Value)) -> PathBuf {
    let mut value = as_this_build(read_json(&full_kept()));
    edit(&mut value);
    write_json(dir, name, &value)
}

/// The claim `id` of a results.json value.
fn claim_mut<'a>(value: &'a mut Value, id: &str) -> &'a mut Value {
    value["sections"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .flat_map(|s| s["claims"].as_array_mut().unwrap().iter_mut())
        .find(|c| c["id"] == id)
        .unwrap_or_else(|| panic!("no claim {id}"))
}

#[test]
fn there_are_kept_results_named_by_machine_and_commit() {
    let files = kept();
    assert!(files.len() >= 3, "{files:?}");
    for file in &files {
        let run = run::Run::read(file).unwrap();
        let name = file.file_name().unwrap().to_string_lossy();
        assert_eq!(name, run.kept_name(), "{}", file.display());
        assert!(!run.commit.is_empty());
    }
}

#[test]
fn the_readmes_command_compares_every_kept_run() {
    let dir = scratch("all-kept");
    let out = dir.join("page");
    let files = kept();
    let args: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    let run = compare_cli(&args, &["--out", out.to_str().unwrap()]);
    assert!(run.status.success(), "{}", stderr(&run));
    let comparison = read_json(&out.join("comparison.json"));
    let machines: usize = comparison["groups"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g["machines"].as_array().unwrap().len())
        .sum();
    assert_eq!(machines, files.len());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn runs_of_other_sizes_form_their_own_group_on_the_same_page() {
    let dir = scratch("sizes");
    let full = this_build_copy(&dir, "full.json", |_| {});
    let quick = this_build_copy(&dir, "quick.json", |v| v["quick"] = json!(true));
    let out = dir.join("page");
    // The quick run first: the papers' sizes still come first on the page.
    let run = compare_cli(&[&quick, &full], &["--out", out.to_str().unwrap()]);
    assert!(run.status.success(), "{}", stderr(&run));
    let comparison = read_json(&out.join("comparison.json"));
    let groups = comparison["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 2);
    assert_eq!(groups[0]["quick"], false);
    assert_eq!(groups[1]["quick"], true);
    assert!(groups[1]["reason"].as_str().unwrap().contains("--quick"));
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("Runs at the papers' sizes") && html.contains("--quick runs"));
    // Each group its own figures.
    assert!(out.join("headline_ratios.png").is_file());
    assert!(out.join("headline_ratios-quick.png").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_claim_whose_version_differs_is_shown_per_version_never_mixed() {
    let dir = scratch("versions");
    let id = "paper4.error-bound";
    let now = this_build_copy(&dir, "now.json", |_| {});
    let before = this_build_copy(&dir, "before.json", |v| {
        let commit = json!("1111111111111111111111111111111111111111");
        for section in v["sections"].as_array_mut().unwrap() {
            section["commit"] = commit.clone();
        }
        v["commit"] = commit;
        v["date"] = json!("2026-01-01 00:00:00 UTC");
        let claim = claim_mut(v, id);
        claim["version"] = json!("00000000000000aa");
        claim["measured"] = json!("judged the earlier way");
    });
    let comparison =
        compare::compare(compare::read(&[before.clone(), now.clone()]).unwrap()).unwrap();
    let group = &comparison.groups[0];
    let rows: Vec<_> = group.claims.iter().filter(|r| r.id == id).collect();
    assert_eq!(rows.len(), 2, "a row per version");
    // This build's definition first; each row's cells only of the runs that judged it.
    assert_eq!(rows[0].status, "this build's definition");
    assert!(rows[0].cells[1].ran && !rows[0].cells[0].ran);
    assert!(rows[0].cells[0].measured.contains("another version"));
    assert!(rows[1].cells[0].ran && !rows[1].cells[1].ran);
    assert_eq!(rows[1].cells[0].measured, "judged the earlier way");
    assert!(
        rows[1].status.contains("changed since 1111111"),
        "{}",
        rows[1].status
    );
    // Every cell keeps its commit and date.
    assert_eq!(rows[1].cells[0].commit, "1111111");
    assert!(rows[1].cells[0].date.starts_with("2026-01-01"));
    // Listed as changed, and the claims that did not change share their rows.
    assert_eq!(group.changed.len(), 1);
    assert_eq!(group.changed[0].id, id);
    assert!(group.changed[0].since.contains("changed since 1111111"));
    let shared = group.claims.iter().filter(|r| r.id != id);
    for row in shared {
        assert!(row.cells.iter().all(|c| c.ran), "{}", row.id);
    }
    // The README's table takes the claim from the run of this build's version only.
    let text = markdown::grouped(std::slice::from_ref(&before)).unwrap();
    let line = text.lines().find(|l| l.contains("error at 32x32")).unwrap();
    assert!(
        line.contains("re-run needed: the claim changed since 1111111"),
        "{line}"
    );
    let text = markdown::grouped(&[before, now]).unwrap();
    let line = text.lines().find(|l| l.contains("error at 32x32")).unwrap();
    assert!(!line.contains("re-run needed"), "{line}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_run_from_before_per_claim_versions_is_a_version_of_its_own() {
    let dir = scratch("old");
    let mut old = read_json(&full_kept());
    for section in old["sections"].as_array_mut().unwrap() {
        for claim in section["claims"].as_array_mut().unwrap() {
            let claim = claim.as_object_mut().unwrap();
            claim.remove("id");
            claim.remove("version");
        }
    }
    old["claims_version"] = json!("62524e1e5c1d841e");
    let old = write_json(&dir, "old.json", &old);
    let now = this_build_copy(&dir, "now.json", |_| {});
    let page = dir.join("page");
    let run = compare_cli(&[&old, &now], &["--out", page.to_str().unwrap()]);
    assert!(run.status.success(), "{}", stderr(&run));
    let comparison = compare::compare(compare::read(&[old.clone(), now.clone()]).unwrap()).unwrap();
    let group = &comparison.groups[0];
    // The old run's claims join the rows of the same claims by their words, a version apart.
    let rows: Vec<_> = group
        .claims
        .iter()
        .filter(|r| r.id == "paper1.beats-cullide")
        .collect();
    assert_eq!(rows.len(), 2);
    assert!(rows[1]
        .status
        .contains("version not recorded: run before per-claim versions"));
    assert!(rows[1].cells[0].ran && !rows[1].cells[1].ran);
    // In the README's table: re-run needed, never its old figure as current.
    let text = markdown::grouped(std::slice::from_ref(&old)).unwrap();
    assert!(
        text.contains("is a run before per-claim versions"),
        "{text}"
    );
    // The gate against it: every claim compared (matched by its words), none judged.
    let gate = compare_cli(&[&now], &["--baseline", old.to_str().unwrap()]);
    assert!(gate.status.success(), "{}", stdout(&gate));
    let n = claims_in(&old);
    assert_eq!(summary(&gate), (n, 0, n, 0), "{}", stdout(&gate));
    assert!(stdout(&gate).contains("run before per-claim versions"));
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
fn a_results_json_past_a_bound_is_refused_with_the_file_named() {
    let dir = scratch("bounds");
    let deep = this_build_copy(&dir, "deep.json", |v| {
        let mut nested = json!(1);
        for _ in 0..100 {
            nested = json!([nested]);
        }
        v["sections"][0]["results"]["deep"] = nested;
    });
    let long = this_build_copy(&dir, "long.json", |v| {
        v["cpu"] = json!("x".repeat(100_000));
    });
    let big = dir.join("big.json");
    std::fs::write(&big, " ".repeat((run::MAX_BYTES + 1) as usize)).unwrap();
    let page = dir.join("page");
    let page = page.to_str().unwrap();
    for (file, bound) in [(&deep, "nested"), (&long, "longer than"), (&big, "bytes")] {
        for extra in [&["--markdown"][..], &["--out", page][..]] {
            let run = compare_cli(&[file], extra);
            assert!(!run.status.success());
            let e = stderr(&run);
            assert!(
                e.contains(&*file.to_string_lossy()) && e.contains("refused") && e.contains(bound),
                "{e}"
            );
            assert!(!e.contains("panicked"), "{e}");
        }
    }
    assert!(!dir.join("page").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn texts_of_a_results_json_are_data_never_markup() {
    let dir = scratch("markup");
    let hostile = this_build_copy(&dir, "hostile.json", |v| {
        v["renderer"]["renderer"] = json!("<img src=x onerror=alert(2)>");
        v["cpu"] = json!("[click](javascript:alert(1)) ![x](http://example.com/x.png) | a cell");
        v["command_line"] = json!(["classic-gpgpu", "reproduce`<b>`"]);
        claim_mut(v, "paper4.error-bound")["paper"] = json!("<script>alert(3)</script>");
    });
    let run = compare_cli(&[&hostile], &["--markdown"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = stdout(&run);
    for raw in ["<img", "<script", "[click](", "![x](", "<b>"] {
        assert!(!text.contains(raw), "`{raw}` came out as markup:\n{text}");
    }
    assert!(
        text.contains("&lt;img src=x onerror=alert(2)&gt;"),
        "{text}"
    );
    assert!(text.contains("\\[click\\]"), "{text}");
    // The table keeps its shape: no cell added by a `|`.
    for line in text.lines().filter(|l| l.starts_with("| ")) {
        let cells = line.matches(" |").count();
        assert!(cells >= 4, "{line}");
    }
    // The page escapes the same texts.
    let page = dir.join("page");
    let run = compare_cli(&[&hostile], &["--out", page.to_str().unwrap()]);
    assert!(run.status.success(), "{}", stderr(&run));
    let html = std::fs::read_to_string(page.join("index.html")).unwrap();
    assert!(!html.contains("<img src=x") && !html.contains("<script>alert"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_page_shows_every_claim_of_every_machine() {
    let dir = scratch("page");
    let out = dir.join("page");
    let files = vec![
        this_build_copy(&dir, "a.json", |_| {}),
        this_build_copy(&dir, "b.json", |v| {
            v["renderer"]["renderer"] = json!("zink Vulkan 1.3(llvmpipe)");
        }),
    ];
    let args: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    let run = compare_cli(&args, &["--out", out.to_str().unwrap()]);
    assert!(run.status.success(), "{}", stderr(&run));

    let comparison = read_json(&out.join("comparison.json"));
    let group = &comparison["groups"][0];
    let machines = group["machines"].as_array().unwrap();
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
    let rows = group["claims"].as_array().unwrap();
    for file in &files {
        let results = read_json(file);
        for section in results["sections"].as_array().unwrap() {
            for claim in section["claims"].as_array().unwrap() {
                let row = rows
                    .iter()
                    .find(|r| r["id"] == claim["id"] && r["version"] == claim["version"])
                    .unwrap_or_else(|| panic!("no row for {}", claim["id"]));
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
    let comparison = compare::compare(compare::read(&kept()).unwrap()).unwrap();
    for group in &comparison.groups {
        // Every headline, unless every machine left its section out (`--only`).
        let partial = group
            .machines
            .iter()
            .all(|m| m.command_line.iter().any(|a| a == "--only"));
        if partial {
            assert!(!group.headlines.is_empty());
            assert!(group.headlines.len() <= headline::headlines().len());
        } else {
            assert_eq!(group.headlines.len(), headline::headlines().len());
        }
        for row in &group.headlines {
            for (cell, machine) in row.cells.iter().zip(&group.machines) {
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
                let figure = cell.figure.as_ref().unwrap_or_else(|| {
                    panic!("no figure for '{}' on {}", row.label, machine.label)
                });
                assert!(!figure.text.is_empty());
                if !row.ratio.is_empty() {
                    // 0 where the claim printed "0.00" (a log axis leaves that point out).
                    let ratio = figure.ratio.expect("a ratio to plot");
                    assert!(ratio.is_finite() && ratio >= 0.0, "{} {ratio}", row.label);
                }
            }
        }
        // The then-and-now figure of a machine with compute shaders is the frame's ratio.
        for row in &group.then_and_now {
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
    let full = this_build_copy(&dir, "full.json", |_| {});
    let quick = this_build_copy(&dir, "quick.json", |v| v["quick"] = json!(true));
    let text = markdown::grouped(&[quick, full.clone()]).unwrap();
    // Two groups, each its own table under its own heading, the papers' sizes first.
    assert_eq!(text.matches("#### ").count(), 2, "{text}");
    assert_eq!(text.matches("| paper | claim |").count(), 2, "{text}");
    let full_at = text
        .find("#### Runs at the papers' sizes")
        .expect("a full group");
    let quick_at = text.find("#### `--quick` runs").expect("a quick group");
    assert!(full_at < quick_at, "{text}");
    // One group alone has no heading, as the README's single table.
    let alone = markdown::grouped(&[full]).unwrap();
    assert!(!alone.contains("#### "), "{alone}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The gate's last line, parsed: (compared, regressed, changed definition, not judged).
fn summary(out: &Output) -> (usize, usize, usize, usize) {
    let text = stdout(out);
    let last = text.lines().last().unwrap_or_default().to_string();
    let numbers: Vec<usize> = last
        .split(|c: char| !c.is_ascii_digit())
        .filter(|w| !w.is_empty())
        .map(|w| w.parse().unwrap())
        .collect();
    assert!(
        last.starts_with("compared ")
            && last.contains(" claims: ")
            && last.ends_with(" not judged")
            && numbers.len() == 4,
        "last line: {last}\n{text}"
    );
    (numbers[0], numbers[1], numbers[2], numbers[3])
}

/// The number of claims of a results.json.
fn claims_in(path: &Path) -> usize {
    read_json(path)["sections"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["claims"].as_array().unwrap().len())
        .sum()
}

#[test]
fn the_gate_passes_a_run_against_itself() {
    let dir = scratch("gate-same");
    let run = this_build_copy(&dir, "run.json", |_| {});
    let out = compare_cli(&[&run], &["--baseline", run.to_str().unwrap()]);
    assert!(out.status.success(), "{}{}", stdout(&out), stderr(&out));
    assert_eq!(summary(&out), (claims_in(&run), 0, 0, 0));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_gate_fails_on_a_flipped_verdict_decided_by_counts() {
    let dir = scratch("gate-flip");
    let id = "paper3.same-classification";
    let baseline = this_build_copy(&dir, "baseline.json", |v| {
        assert_eq!(claim_mut(v, id)["decided_by"], "count");
    });
    let flipped = this_build_copy(&dir, "flipped.json", |v| {
        let claim = claim_mut(v, id);
        let holds = claim["holds"].as_bool().unwrap();
        claim["holds"] = json!(!holds);
    });
    let junit = dir.join("gate.xml");
    let out = compare_cli(
        &[&flipped],
        &[
            "--baseline",
            baseline.to_str().unwrap(),
            "--junit",
            junit.to_str().unwrap(),
        ],
    );
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}{}",
        stdout(&out),
        stderr(&out)
    );
    let text = stdout(&out);
    assert!(text.contains(&format!("REGRESSED: {id}")), "{text}");
    assert!(text.contains("verdict holds -> does not hold") || text.contains("-> holds"));
    assert_eq!(summary(&out), (claims_in(&flipped), 1, 0, 0));
    // The same as JUnit: one failure, named.
    let xml = std::fs::read_to_string(&junit).unwrap();
    assert!(xml.contains("failures=\"1\"") && xml.contains(&format!("name=\"{id}\"")));
    // An existing JUnit file is replaced only with --force.
    let again = compare_cli(
        &[&flipped],
        &[
            "--baseline",
            baseline.to_str().unwrap(),
            "--junit",
            junit.to_str().unwrap(),
        ],
    );
    assert_eq!(again.status.code(), Some(1));
    assert!(stderr(&again).contains("--force"), "{}", stderr(&again));
    let forced = compare_cli(
        &[&flipped],
        &[
            "--baseline",
            baseline.to_str().unwrap(),
            "--junit",
            junit.to_str().unwrap(),
            "--force",
        ],
    );
    assert_eq!(forced.status.code(), Some(1), "{}", stderr(&forced));
    assert_eq!(summary(&forced).1, 1);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn timings_are_judged_only_between_quiet_runs_and_definitions_that_changed_are_not_judged() {
    let dir = scratch("gate-timing");
    let id = "paper4.interactive-buoyancy";
    let timing = |fps: f64, load: f64| {
        json!([{
            "name": "frames per second", "kind": "timing", "value": fps,
            "unit": " frames/s", "higher_is_better": true, "band": 0.25,
            "load": {"one_minute": load, "cores": 2}
        }])
    };
    let baseline = this_build_copy(&dir, "baseline.json", |v| {
        claim_mut(v, id)["evidence"] = timing(20.0, 0.5);
    });
    // Half the rate on a loaded machine: not judged, not a failure.
    let loaded = this_build_copy(&dir, "loaded.json", |v| {
        claim_mut(v, id)["evidence"] = timing(10.0, 7.5);
    });
    let out = compare_cli(&[&loaded], &["--baseline", baseline.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stdout(&out));
    assert!(
        stdout(&out).contains(&format!("not judged: {id}")),
        "{}",
        stdout(&out)
    );
    assert_eq!(summary(&out).3, 1);
    // The same on a quiet machine: a regression (past the 25% band).
    let quiet = this_build_copy(&dir, "quiet.json", |v| {
        claim_mut(v, id)["evidence"] = timing(10.0, 0.5);
    });
    let out = compare_cli(&[&quiet], &["--baseline", baseline.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    assert_eq!(summary(&out).1, 1);
    // Another machine's run, quiet and as slow: its timings are not judged against these.
    let other = this_build_copy(&dir, "other.json", |v| {
        v["renderer"]["renderer"] = json!("softpipe");
        claim_mut(v, id)["evidence"] = timing(10.0, 0.5);
    });
    let out = compare_cli(&[&other], &["--baseline", baseline.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stdout(&out));
    assert!(
        stdout(&out).contains("timings of two machines"),
        "{}",
        stdout(&out)
    );
    assert_eq!(summary(&out).3, 1);
    // Two quiet --quick runs: their timings are too short to judge.
    let quick = |name, fps| {
        this_build_copy(&dir, name, |v| {
            v["quick"] = json!(true);
            claim_mut(v, id)["evidence"] = timing(fps, 0.5);
        })
    };
    let (quick_baseline, quick_slow) = (quick("qb.json", 20.0), quick("qs.json", 10.0));
    let out = compare_cli(
        &[&quick_slow],
        &["--baseline", quick_baseline.to_str().unwrap()],
    );
    assert!(out.status.success(), "{}", stdout(&out));
    assert!(
        stdout(&out).contains("timings at --quick sizes are too short to judge"),
        "{}",
        stdout(&out)
    );
    assert_eq!(summary(&out).3, 1);
    // A baseline that kept no figures of the claim (a run from before claims kept them): its
    // timing is not judged, however it moved.
    let bare = this_build_copy(&dir, "bare.json", |v| {
        claim_mut(v, id)["evidence"] = json!([]);
    });
    let out = compare_cli(&[&quiet], &["--baseline", bare.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stdout(&out));
    assert!(
        stdout(&out).contains("kept no figures of this claim: its timings are not judged"),
        "{}",
        stdout(&out)
    );
    assert_eq!(summary(&out).3, 1);
    // Within the band: no regression.
    let close = this_build_copy(&dir, "close.json", |v| {
        claim_mut(v, id)["evidence"] = timing(18.0, 0.5);
    });
    let out = compare_cli(&[&close], &["--baseline", baseline.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stdout(&out));
    // A claim whose definition changed since the baseline is listed, not judged.
    let redefined = this_build_copy(&dir, "redefined.json", |v| {
        let claim = claim_mut(v, "paper3.same-classification");
        claim["version"] = json!("00000000000000bb");
        claim["holds"] = json!(false);
    });
    let out = compare_cli(&[&redefined], &["--baseline", baseline.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stdout(&out));
    assert!(stdout(&out).contains("changed definition: paper3.same-classification"));
    assert_eq!(summary(&out).2, 1);
    // The gate takes one new run.
    let out = compare_cli(
        &[&close, &quiet],
        &["--baseline", baseline.to_str().unwrap()],
    );
    assert!(!out.status.success());
    assert!(stderr(&out).contains("--baseline"), "{}", stderr(&out));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_run_from_before_per_claim_versions_is_stamped_with_this_builds_where_asked() {
    let dir = scratch("stamp");
    let mut old = read_json(&full_kept());
    for claim in old["sections"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .flat_map(|s| s["claims"].as_array_mut().unwrap().iter_mut())
    {
        let claim = claim.as_object_mut().unwrap();
        claim.remove("id");
        claim.remove("version");
    }
    let old = write_json(&dir, "old.json", &old);
    // A run of this build: only claims it has (the kept run's may have made-up ids here).
    let like = this_build_copy(&dir, "like.json", |v| {
        for section in v["sections"].as_array_mut().unwrap() {
            section["claims"]
                .as_array_mut()
                .unwrap()
                .retain(|c| compare::current_version(c["id"].as_str().unwrap(), false).is_some());
        }
    });
    let out = dir.join("stamped.json");
    let stamp = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
            .args(["claims", "--stamp", old.to_str().unwrap()])
            .args([
                "--like",
                like.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ])
            .args(extra)
            .output()
            .unwrap()
    };
    let run = stamp(&["--except", "paper4.interactive-buoyancy"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let stamped = read_json(&out);
    assert!(stamped["stamped"]
        .as_str()
        .unwrap()
        .contains("paper4.interactive-buoyancy"));
    let claim = |id: &str| {
        stamped["sections"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|s| s["claims"].as_array().unwrap())
            .find(|c| c["id"] == id)
            .cloned()
    };
    // A claim of this build: its id and this build's version at the run's sizes.
    let cullide = claim("paper1.beats-cullide").expect("stamped");
    assert_eq!(
        cullide["version"],
        compare::current_version("paper1.beats-cullide", false).unwrap()
    );
    // A claim left out keeps no version: "re-run needed".
    assert!(claim("paper4.interactive-buoyancy").is_none());
    let text = markdown::grouped(std::slice::from_ref(&out)).unwrap();
    let line = text
        .lines()
        .find(|l| l.contains("floating bodies"))
        .unwrap();
    assert!(line.contains("re-run needed"), "{line}");
    let line = text
        .lines()
        .find(|l| l.contains("faster than CULLIDE"))
        .unwrap();
    assert!(!line.contains("re-run needed"), "{line}");
    // The file is not replaced without --force, and a run with versions is not stamped.
    assert!(!stamp(&[]).status.success());
    let again = Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(["claims", "--stamp", like.to_str().unwrap()])
        .args(["--like", like.to_str().unwrap()])
        .args(["--out", dir.join("again.json").to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!again.status.success());
    assert!(
        stderr(&again).contains("already carry versions"),
        "{}",
        stderr(&again)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn every_claim_of_this_build_is_listed_with_its_versions() {
    let out = Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(["claims", "--json"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let listed: Value = serde_json::from_slice(&out.stdout).unwrap();
    let listed = listed.as_array().unwrap();
    assert_eq!(listed.len(), claim_defs::all().len());
    for claim in listed {
        let def = claim_defs::find(claim["id"].as_str().unwrap()).unwrap();
        assert_eq!(claim["version"], versions::current(def, false).unwrap());
        assert_eq!(
            claim["quick_version"],
            versions::current(def, true).unwrap()
        );
    }
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

#[test]
fn against_a_baseline_without_figures_a_count_claim_is_judged_by_its_verdict() {
    let dir = scratch("gate-bare");
    let id = "paper3.same-classification";
    let run = this_build_copy(&dir, "run.json", |v| {
        assert_eq!(claim_mut(v, id)["decided_by"], "count");
        claim_mut(v, id)["evidence"] =
            json!([{"name": "windows classified as the CPU does", "kind": "count", "value": 1.0}]);
    });
    // A run from before claims kept their figures: the same verdict, nothing else to compare.
    let bare = this_build_copy(&dir, "bare.json", |v| {
        claim_mut(v, id)["evidence"] = json!([]);
    });
    let out = compare_cli(&[&run], &["--baseline", bare.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stdout(&out));
    let text = stdout(&out);
    assert!(text.contains(&format!("same verdict: {id}")), "{text}");
    assert!(text.contains("only its verdict is compared"), "{text}");
    assert_eq!(summary(&out), (claims_in(&run), 0, 0, 0));
    // Its verdict flipped: still a regression.
    let flipped = this_build_copy(&dir, "flipped.json", |v| {
        let claim = claim_mut(v, id);
        let holds = claim["holds"].as_bool().unwrap();
        claim["holds"] = json!(!holds);
    });
    let out = compare_cli(&[&flipped], &["--baseline", bare.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", stdout(&out));
    assert!(stdout(&out).contains(&format!("REGRESSED: {id}")));
    std::fs::remove_dir_all(&dir).unwrap();
}
