//! Every command that writes a folder follows one rule (`page::folder::Staged`): a folder
//! holding a file it did not write is refused without --force, and the file survives with
//! it; a rerun removes the files of its own earlier run that it does not write again; a link
//! to a folder is followed (the link stays), a link to nothing is refused. And `selftest
//! --junit` is a single-file writer like the others.

mod common;

use classic_gpgpu::page::folder::{list_files, MARKER};
use common::{assert_ok, assert_refused, classic_gpgpu, stderr};
use std::path::Path;
use std::process::Output;

fn text(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `args` with `DIR` replaced by `dir` (and `--force` added when asked).
fn run(args: &[&str], dir: &Path, force: bool) -> Output {
    let mut full: Vec<&str> = args
        .iter()
        .map(|a| if *a == "DIR" { text(dir) } else { a })
        .collect();
    if force {
        full.push("--force");
    }
    classic_gpgpu(&full)
}

/// A folder of the user's (no marker) with their `notes.txt`: refused without --force (the
/// message names the file and the way out), written with it, and the note is still there,
/// untouched.
fn foreign_file_is_refused_then_kept(args: &[&str], dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    let notes = dir.join("notes.txt");
    std::fs::write(&notes, "the user's notes").unwrap();
    assert_refused(&run(args, dir, false), &["notes.txt", "--force"]);
    assert_eq!(
        list_files(dir).unwrap(),
        ["notes.txt"],
        "written while refused"
    );
    assert_ok(&run(args, dir, true));
    assert_eq!(std::fs::read_to_string(&notes).unwrap(), "the user's notes");
    assert!(dir.join(MARKER).is_file());
    assert!(list_files(dir).unwrap().len() > 1, "nothing written");
}

/// Nothing beside the folder: no staging folder, no lock left by a finished run.
fn assert_nothing_beside(parent: &Path, names: &[&str]) {
    let mut found: Vec<String> = std::fs::read_dir(parent)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    found.sort();
    assert_eq!(found, names);
}

#[test]
fn mass_dump_owns_its_folder_and_a_shallower_dump_leaves_no_deeper_peel() {
    let root = common::temp_dir("folder-writers", "mass");
    let dir = root.join("peels");
    let knot = ["mass", "knot", "--resolution", "8", "--dump", "DIR"];
    assert_ok(&run(&knot, &dir, false));
    let deep = list_files(&dir).unwrap();
    assert!(
        deep.iter().any(|f| f.starts_with("peel4")),
        "the knot has four layers: {deep:?}"
    );
    // The cube has two layers: the knot's peel3 and peel4 must not survive as if they were
    // the cube's.
    let cube = ["mass", "cube", "--resolution", "8", "--dump", "DIR"];
    assert_ok(&run(&cube, &dir, false));
    let shallow = list_files(&dir).unwrap();
    assert!(
        shallow.iter().any(|f| f.starts_with("peel1")),
        "{shallow:?}"
    );
    assert!(
        !shallow
            .iter()
            .any(|f| f.starts_with("peel3") || f.starts_with("peel4")),
        "stale peels of the earlier dump: {shallow:?}"
    );
    assert!(shallow.len() < deep.len());
    foreign_file_is_refused_then_kept(&cube, &root.join("theirs"));
    assert_nothing_beside(&root, &["peels", "theirs"]);
    std::fs::remove_dir_all(root).ok();
}

#[test]
fn collide_dump_follows_a_link_and_keeps_the_users_files() {
    let root = common::temp_dir("folder-writers", "collide");
    let (a, b) = (root.join("a.obj"), root.join("b.obj"));
    for (path, shape) in [(&a, "cube"), (&b, "sphere")] {
        assert_ok(&classic_gpgpu(&[
            "mesh",
            "generate",
            shape,
            "--out",
            text(path),
        ]));
    }
    let args = ["collide", text(&a), text(&b), "--dump", "DIR"];
    let real = root.join("real");
    std::fs::create_dir_all(&real).unwrap();
    let link = root.join("link");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    assert_ok(&run(&args, &link, false));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(real.join("snapshot.png").is_file() && real.join(MARKER).is_file());
    // Again through the link: its own files, no --force needed.
    assert_ok(&run(&args, &link, false));
    // A link to a folder of the user's.
    let theirs = root.join("theirs");
    std::fs::create_dir_all(&theirs).unwrap();
    let their_link = root.join("their-link");
    std::os::unix::fs::symlink(&theirs, &their_link).unwrap();
    foreign_file_is_refused_then_kept(&args, &their_link);
    // A link to nothing is refused, and nothing is made where it points.
    let dangling = root.join("dangling");
    std::os::unix::fs::symlink(root.join("nowhere"), &dangling).unwrap();
    assert_refused(&run(&args, &dangling, true), &["does not exist", "nowhere"]);
    assert!(!root.join("nowhere").exists());
    std::fs::remove_dir_all(root).ok();
}

#[test]
fn buoyancy_frames_of_a_longer_run_do_not_outlive_a_shorter_one() {
    let root = common::temp_dir("folder-writers", "buoyancy");
    let dir = root.join("frames");
    let run_steps = |steps: &str, force: bool| {
        run(
            &[
                "buoyancy",
                "--bodies",
                "2",
                "--steps",
                steps,
                "--resolution",
                "8",
                "--png-every",
                "2",
                "DIR",
            ],
            &dir,
            force,
        )
    };
    assert_ok(&run_steps("4", false));
    assert!(dir.join("frame00002.png").is_file());
    assert_ok(&run_steps("2", false));
    assert_eq!(list_files(&dir).unwrap(), ["frame00000.png"]);
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    // The folder has the command's marker, so it is its own: the user's file put there
    // later stays, and is never replaced.
    assert_ok(&run_steps("2", false));
    assert_eq!(list_files(&dir).unwrap(), ["frame00000.png", "notes.txt"]);
    // A folder without the marker is someone else's.
    let theirs = root.join("theirs");
    std::fs::create_dir_all(&theirs).unwrap();
    std::fs::write(theirs.join("notes.txt"), "mine").unwrap();
    let args = [
        "buoyancy",
        "--bodies",
        "2",
        "--steps",
        "2",
        "--resolution",
        "8",
        "--png-every",
        "2",
        "DIR",
    ];
    assert_refused(&run(&args, &theirs, false), &["notes.txt", "--force"]);
    assert_ok(&run(&args, &theirs, true));
    assert_eq!(
        list_files(&theirs).unwrap(),
        ["frame00000.png", "notes.txt"]
    );
    std::fs::remove_dir_all(root).ok();
}

#[test]
fn every_bench_refuses_a_folder_of_the_users_before_any_work() {
    let root = common::temp_dir("folder-writers", "benches");
    let dir = root.join("figures");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    for bench in [
        "collide-bench",
        "mass-bench",
        "crowd-bench",
        "mlp-bench",
        "lecture3-bench",
    ] {
        let out = run(&[bench, "--quick", "--out", "DIR"], &dir, false);
        assert_refused(&out, &[bench, "notes.txt", "--force"]);
        assert_eq!(list_files(&dir).unwrap(), ["notes.txt"], "{bench}");
    }
    // A file where the folder goes: said plainly, not "File exists (os error 17)".
    let file = root.join("file");
    std::fs::write(&file, "x").unwrap();
    let out = run(&["mlp-bench", "--quick", "--out", "DIR"], &file, false);
    assert_refused(&out, &["--out", "not a folder"]);
    assert!(!stderr(&out).contains("os error"), "{}", stderr(&out));
    assert_nothing_beside(&root, &["figures", "file"]);
    std::fs::remove_dir_all(root).ok();
}

#[test]
fn learn_png_and_lecture3_npy_follow_the_rule() {
    let root = common::temp_dir("folder-writers", "learn");
    let lesson = ["learn", "texture-is-array", "--png", "DIR"];
    foreign_file_is_refused_then_kept(&lesson, &root.join("lesson"));
    // Another lesson's pictures are not this lesson's: refused without --force.
    let mine = root.join("mine");
    assert_ok(&run(&lesson, &mine, false));
    assert_ok(&run(&lesson, &mine, false));
    let other = ["learn", "ping-pong", "--png", "DIR"];
    assert_refused(&run(&other, &mine, false), &["--force"]);

    let octree = [
        "lecture3",
        "octree",
        "--resolution",
        "8",
        "--points",
        "200",
        "--size",
        "16",
        "--npy",
        "DIR",
    ];
    foreign_file_is_refused_then_kept(&octree, &root.join("octree"));
    let file = root.join("file.npy");
    std::fs::write(&file, "x").unwrap();
    let out = run(&octree, &file, true);
    assert_refused(&out, &["--npy", "not a folder"]);
    assert!(!stderr(&out).contains("os error"), "{}", stderr(&out));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "x");
    std::fs::remove_dir_all(root).ok();
}

#[test]
fn selftest_junit_is_an_xml_file_replaced_only_with_force() {
    let root = common::temp_dir("folder-writers", "junit");
    let check = ["selftest", "--only", "1d-float-texture", "--junit"];
    let with = |file: &Path, force: bool| {
        let mut args = check.to_vec();
        args.push(text(file));
        if force {
            args.push("--force");
        }
        classic_gpgpu(&args)
    };
    let txt = root.join("results.txt");
    assert_refused(&with(&txt, false), &["--junit", ".xml"]);
    assert!(!txt.exists());
    let xml = root.join("results.xml");
    std::fs::write(&xml, "the user's file").unwrap();
    assert_refused(&with(&xml, false), &["--junit", "exists", "--force"]);
    assert_eq!(std::fs::read_to_string(&xml).unwrap(), "the user's file");
    assert_ok(&with(&xml, true));
    assert!(std::fs::read_to_string(&xml)
        .unwrap()
        .contains("<testsuite"));
    std::fs::remove_dir_all(root).ok();
}

#[test]
fn reproduce_out_through_a_link_writes_the_folder_and_keeps_the_link() {
    let root = common::temp_dir("folder-writers", "reproduce");
    let real = root.join("real");
    std::fs::create_dir_all(&real).unwrap();
    let link = root.join("report");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let args = ["reproduce", "--quick", "--only", "blocks", "--out", "DIR"];
    assert_ok(&run(&args, &link, false));
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(real.join("results.json").is_file() && real.join(MARKER).is_file());
    let dangling = root.join("dangling");
    std::os::unix::fs::symlink(root.join("nowhere"), &dangling).unwrap();
    assert_refused(&run(&args, &dangling, false), &["--out", "does not exist"]);
    assert!(!root.join("nowhere").exists());
    std::fs::remove_dir_all(root).ok();
}
