//! `reproduce` owns only what it wrote: a folder it did not make is refused (and with --force
//! nothing of it is removed), two runs never write one report at once, a rerun of one section
//! keeps every file of the others, and an interrupted or failed swap loses nothing.

use std::path::Path;
use std::process::{Command, Output};

mod common;
use common::{assert_ok, assert_refused, stderr};

const MARKER: &str = classic_gpgpu::page::folder::MARKER;

/// `reproduce --quick --only blocks --out OUT` with `extra` arguments and environment.
fn blocks(out: &Path, extra: &[&str], env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"));
    cmd.args([
        "reproduce",
        "--quick",
        "--only",
        "blocks",
        "--json",
        "--out",
    ])
    .arg(out)
    .args(extra);
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.output().expect("the binary runs")
}

/// Every file under `dir` with its bytes.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let files = classic_gpgpu::page::folder::list_files(dir).unwrap();
    files
        .into_iter()
        .map(|f| {
            let bytes = std::fs::read(dir.join(&f)).unwrap();
            (f, bytes)
        })
        .collect()
}

#[test]
fn a_folder_it_did_not_make_is_refused_and_nothing_of_it_is_removed() {
    let dir = common::temp_dir("report-folder", "foreign");
    let out = dir.join("mine");
    std::fs::create_dir_all(out.join("photos")).unwrap();
    std::fs::write(out.join("notes.txt"), "my notes").unwrap();
    std::fs::write(out.join("photos/a.txt"), "a").unwrap();
    let before = snapshot(&out);
    // Refused before any work (the section would fail if it ran).
    let fail = [("CLASSIC_GPGPU_FAIL_SECTION", "blocks")];
    let refused = blocks(&out, &[], &fail);
    assert_refused(&refused, &["notes.txt", "did not write", "--force"]);
    assert!(!stderr(&refused).contains("on purpose"));
    assert_eq!(snapshot(&out), before);
    // A results.json does not make a folder a report.
    std::fs::write(out.join("results.json"), "{\"mine\": true}").unwrap();
    assert_refused(&blocks(&out, &[], &fail), &["did not write", "--force"]);
    std::fs::remove_file(out.join("results.json")).unwrap();

    // With --force the report goes in beside the user's files, which stay.
    assert_ok(&blocks(&out, &["--force"], &[]));
    assert!(out.join(MARKER).is_file());
    assert!(out.join("results.json").is_file());
    for (file, bytes) in &before {
        assert_eq!(&std::fs::read(out.join(file)).unwrap(), bytes, "{file}");
    }
    // The marker lists the report's files only.
    let marker = std::fs::read_to_string(out.join(MARKER)).unwrap();
    assert!(marker.contains("\tresults.json") && !marker.contains("notes.txt"));
    // Now the folder is a report: a rerun needs no --force and still keeps the user's files.
    assert_ok(&blocks(&out, &[], &[]));
    for (file, bytes) in &before {
        assert_eq!(&std::fs::read(out.join(file)).unwrap(), bytes, "{file}");
    }
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_rerun_of_one_section_keeps_every_file_of_the_others() {
    let dir = common::temp_dir("report-folder", "merge");
    let out = dir.join("report");
    assert_ok(&blocks(&out, &[], &[]));
    // Give the report a second section that wrote a file its figures do not list (as Fig. 10
    // writes every peel's targets and shows some), the marker naming it as that section's.
    let results_path = out.join("results.json");
    let mut results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&results_path).unwrap()).unwrap();
    let mut other = results["sections"][0].clone();
    other["id"] = "paper4".into();
    other["figures"] = serde_json::json!([]);
    results["sections"].as_array_mut().unwrap().push(other);
    std::fs::write(&results_path, serde_json::to_vec(&results).unwrap()).unwrap();
    std::fs::create_dir_all(out.join("fig10_bunny")).unwrap();
    std::fs::write(out.join("fig10_bunny/peel2_target1.png"), "peel").unwrap();
    let mut marker = std::fs::read_to_string(out.join(MARKER)).unwrap();
    marker.push_str("paper4\tfig10_bunny/peel2_target1.png\n");
    std::fs::write(out.join(MARKER), marker).unwrap();

    assert_ok(&blocks(&out, &[], &[]));
    assert_eq!(
        std::fs::read(out.join("fig10_bunny/peel2_target1.png")).unwrap(),
        b"peel"
    );
    let merged: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&results_path).unwrap()).unwrap();
    let ids: Vec<&str> = merged["sections"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["id"].as_str().unwrap())
        .collect();
    assert_eq!(ids, ["blocks", "paper4"]);
    let marker = std::fs::read_to_string(out.join(MARKER)).unwrap();
    assert!(
        marker.contains("paper4\tfig10_bunny/peel2_target1.png"),
        "{marker}"
    );
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn a_second_run_into_the_same_report_is_refused_while_the_first_holds_it() {
    let dir = common::temp_dir("report-folder", "lock");
    let out = dir.join("report");
    assert_ok(&blocks(&out, &[], &[]));
    let before = snapshot(&out);
    // Hold the lock as a running reproduce does.
    let lock = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(dir.join(".report.classic-gpgpu-lock"))
        .unwrap();
    rustix::fs::flock(&lock, rustix::fs::FlockOperation::NonBlockingLockExclusive).unwrap();
    let second = blocks(&out, &[], &[]);
    assert_refused(&second, &["another", "is writing this report", "run again"]);
    assert_eq!(snapshot(&out), before);
    drop(lock);
    assert_ok(&blocks(&out, &[], &[]));
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn an_interrupted_or_failed_swap_loses_nothing() {
    let dir = common::temp_dir("report-folder", "swap");
    let out = dir.join("report");
    assert_ok(&blocks(&out, &[], &[]));
    let before = snapshot(&out);

    // Killed between the two renames: the report is aside, nothing at --out.
    let killed = blocks(&out, &[], &[("CLASSIC_GPGPU_SWAP_FAULT", "kill")]);
    assert!(!killed.status.success());
    assert!(!out.exists());
    // The next run restores it first (this one then fails on purpose: nothing else changes).
    let next = blocks(&out, &[], &[("CLASSIC_GPGPU_FAIL_SECTION", "blocks")]);
    assert_refused(&next, &["restored", "on purpose"]);
    assert_eq!(snapshot(&out), before);

    // The second rename fails: the old report is back, and the message says where the new one is.
    let names = || -> Vec<String> {
        std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(".report.staging-"))
            .collect()
    };
    let earlier = names();
    let failed = blocks(&out, &[], &[("CLASSIC_GPGPU_SWAP_FAULT", "fail")]);
    assert_refused(&failed, &["the finished report is in", "is as it was"]);
    assert_eq!(snapshot(&out), before);
    let err = stderr(&failed);
    let staging = dir.join(
        names()
            .into_iter()
            .find(|n| !earlier.contains(n))
            .expect("the finished report is kept"),
    );
    assert!(err.contains(&*staging.to_string_lossy()), "{err}");
    assert!(staging.join("results.json").is_file() && staging.join(MARKER).is_file());
    // A later run leaves it there and says so.
    let later = blocks(&out, &[], &[]);
    assert_ok(&later);
    assert!(stderr(&later).contains("finished report of an interrupted run"));
    assert!(staging.join("results.json").is_file());
    std::fs::remove_dir_all(dir).ok();
}
