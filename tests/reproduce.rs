//! `classic-gpgpu reproduce --quick` end to end, as CI runs it.

use std::path::Path;
use std::process::Command;

fn reproduce(out: &Path, extra_env: &[(&str, &str)]) -> std::process::Output {
    reproduce_with(&["--quick"], out, extra_env)
}

fn reproduce_with(args: &[&str], out: &Path, extra_env: &[(&str, &str)]) -> std::process::Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"));
    cmd.arg("reproduce")
        .args(args)
        .args(["--json", "--out"])
        .arg(out);
    for (k, v) in extra_env {
        cmd.env(k, v);
    }
    cmd.output().expect("the binary runs")
}

/// Every `src="..."` and non-anchor `href="..."` of the page.
fn referenced_files(html: &str) -> Vec<String> {
    let mut files = Vec::new();
    for attribute in ["src=\"", "href=\""] {
        for (i, _) in html.match_indices(attribute) {
            let rest = &html[i + attribute.len()..];
            let value = &rest[..rest.find('"').unwrap()];
            if !value.starts_with('#') {
                files.push(value.to_string());
            }
        }
    }
    files
}

#[test]
fn quick_reproduction_writes_every_section_and_keeps_a_good_report_on_failure() {
    let out = std::env::temp_dir().join(format!("classic-gpgpu-report-{}", std::process::id()));
    let run = reproduce(&out, &[]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );

    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    assert_eq!(results["quick"], true);
    assert!(results["renderer"]["renderer"]
        .as_str()
        .is_some_and(|r| !r.is_empty()));
    let ids: Vec<&str> = results["sections"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["id"].as_str().unwrap())
        .collect();
    for stage in classic_gpgpu::report::reproduce::stages() {
        assert!(
            ids.contains(&stage.id),
            "section {} missing from {ids:?}",
            stage.id
        );
    }
    assert_same_shape(&results);
    // Every verdict says what decided it: timing, counts, error or run size.
    for s in results["sections"].as_array().unwrap() {
        for c in s["claims"].as_array().unwrap() {
            assert!(
                c["decided_by"]
                    .as_str()
                    .is_some_and(|b| ["timing", "count", "error", "run_size"].contains(&b)),
                "section {}: claim {} does not say what decided it",
                s["id"],
                c["claim"]
            );
        }
    }
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("Quick mode"));
    let files = referenced_files(&html);
    assert!(!files.is_empty(), "the report shows no figure");
    for file in files {
        assert!(
            out.join(&file).is_file(),
            "index.html references missing {file}"
        );
    }

    // A run that fails half-way leaves the good report as it was.
    let before = std::fs::read(out.join("results.json")).unwrap();
    let failed = reproduce(&out, &[("CLASSIC_GPGPU_FAIL_SECTION", "blocks")]);
    assert!(!failed.status.success());
    let stderr = String::from_utf8_lossy(&failed.stderr);
    assert!(stderr.contains("left as it was"), "{stderr}");
    assert_eq!(std::fs::read(out.join("results.json")).unwrap(), before);
    // This run's staging folders only: other runs may be going on in the same folder.
    let staging_prefix = format!(".{}.staging-", out.file_name().unwrap().to_string_lossy());
    let leftovers: Vec<_> = std::fs::read_dir(out.parent().unwrap())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with(&staging_prefix))
        .collect();
    assert!(leftovers.is_empty(), "staging folders left behind");

    nothing_of_the_report_is_lost(&out, &before);
    std::fs::remove_dir_all(&out).ok();
}

fn section_ids(results_json: &Path) -> Vec<String> {
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(results_json).unwrap()).unwrap();
    results["sections"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["id"].as_str().unwrap().to_string())
        .collect()
}

/// `--only` merges into the report it finds, refuses to mix renderers, sizes or run counts without
/// `--force`, a file as `--out` is refused before any work, and the staging folders of killed
/// runs are cleaned up.
fn nothing_of_the_report_is_lost(out: &Path, results_before: &[u8]) {
    let all = section_ids(&out.join("results.json"));
    let name = out.file_name().unwrap().to_string_lossy();
    let stale = out.with_file_name(format!(".{name}.staging-4294967"));
    std::fs::create_dir_all(&stale).unwrap();

    let merged = reproduce_with(&["--quick", "--only", "blocks"], out, &[]);
    assert!(
        merged.status.success(),
        "{}",
        String::from_utf8_lossy(&merged.stderr)
    );
    assert_eq!(section_ids(&out.join("results.json")), all);
    assert_ne!(
        std::fs::read(out.join("results.json")).unwrap(),
        results_before
    );
    assert!(!stale.exists(), "a dead run's staging folder was kept");
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    for file in referenced_files(&html) {
        assert!(out.join(&file).is_file(), "merged report lost {file}");
    }

    let mixed = reproduce_with(&["--only", "blocks"], out, &[]);
    assert!(!mixed.status.success());
    let stderr = String::from_utf8_lossy(&mixed.stderr);
    assert!(stderr.contains("--force"), "{stderr}");
    assert_eq!(section_ids(&out.join("results.json")), all);

    // Timed another way (--runs): refused too, before any work.
    let other_runs = reproduce_with(&["--quick", "--only", "blocks", "--runs", "2"], out, &[]);
    assert!(!other_runs.status.success());
    let stderr = String::from_utf8_lossy(&other_runs.stderr);
    assert!(
        stderr.contains("--runs 2") && stderr.contains("--force"),
        "{stderr}"
    );
    assert_eq!(section_ids(&out.join("results.json")), all);

    // A report that does not say how it was timed (made before --runs): refused as well.
    let results = out.join("results.json");
    let kept = std::fs::read(&results).unwrap();
    let mut unstated: serde_json::Value = serde_json::from_slice(&kept).unwrap();
    unstated.as_object_mut().unwrap().remove("runs").unwrap();
    std::fs::write(&results, serde_json::to_vec(&unstated).unwrap()).unwrap();
    let unstated_runs = reproduce_with(&["--quick", "--only", "blocks"], out, &[]);
    assert!(!unstated_runs.status.success());
    let stderr = String::from_utf8_lossy(&unstated_runs.stderr);
    assert!(
        stderr.contains("not stated") && stderr.contains("--force"),
        "{stderr}"
    );
    std::fs::write(&results, kept).unwrap();

    let file = out.with_file_name(format!("{name}-a-file"));
    std::fs::write(&file, "not a folder").unwrap();
    // The first section is made to fail: the error must be the --out check's, made first.
    let refused = reproduce_with(
        &["--quick"],
        &file,
        &[("CLASSIC_GPGPU_FAIL_SECTION", "blocks")],
    );
    assert!(!refused.status.success());
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains(&*file.to_string_lossy()) && stderr.contains("not a folder"),
        "{stderr}"
    );
    assert!(
        !stderr.contains("on purpose"),
        "refused only after running: {stderr}"
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "not a folder");
    std::fs::remove_file(file).ok();
}

/// The names a reader finds in the report: per section its id and title, the tables (caption
/// up to the first ':' or '(', where the measured details begin), figures, claims, fidelity
/// features and result keys.
fn shape(results: &serde_json::Value) -> serde_json::Value {
    let names = |v: &serde_json::Value, key: &str, field: &str| -> Vec<String> {
        v[key]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x[field].as_str().unwrap().to_string())
            .collect()
    };
    let sections: Vec<serde_json::Value> = results["sections"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let tables: Vec<String> = names(s, "tables", "caption")
                .iter()
                .map(|c| c.split([':', '(']).next().unwrap().trim().to_string())
                .collect();
            let mut keys: Vec<&String> = s["results"].as_object().unwrap().keys().collect();
            keys.sort();
            serde_json::json!({
                "id": s["id"],
                "title": s["title"],
                "tables": tables,
                "figures": names(s, "figures", "file"),
                "claims": names(s, "claims", "claim"),
                "fidelity": names(s, "fidelity", "feature"),
                "results": keys,
            })
        })
        .collect();
    serde_json::Value::Array(sections)
}

/// The report's shape equals `tests/data/reproduce_quick_shape.json`: a refactoring of the
/// report layer must not lose or rename a section, table, figure, claim or result. A change
/// meant to alter the report updates that file (`CLASSIC_GPGPU_UPDATE_SHAPE=1` rewrites it).
fn assert_same_shape(results: &serde_json::Value) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/reproduce_quick_shape.json");
    let got = shape(results);
    if std::env::var_os("CLASSIC_GPGPU_UPDATE_SHAPE").is_some() {
        std::fs::write(&path, serde_json::to_string_pretty(&got).unwrap() + "\n").unwrap();
    }
    let want: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let (got, want) = (got.as_array().unwrap(), want.as_array().unwrap());
    for (g, w) in got.iter().zip(want) {
        for key in [
            "id", "title", "tables", "figures", "claims", "fidelity", "results",
        ] {
            assert_eq!(g[key], w[key], "section {}: {key} differs", w["id"]);
        }
    }
    assert_eq!(got.len(), want.len(), "number of sections");
}
