//! Every option of every command held to the rules of values and paths, walked from clap's own
//! list (`classic-gpgpu options`, hidden), so that a new option that skips a rule fails here:
//! each number refuses a value above its range and a negative one, naming the option and the
//! value, before any work, and states its range in `--help`; each path option is an input or an
//! output, and each output refuses a link to nothing before any work. And the global options:
//! `--trace` takes its file after `=`, so it never swallows a subcommand or a lesson, and is
//! refused where no GL call is made; `--json` is refused where nothing is printed as JSON; two
//! outputs of one run never share a path.

use common::classic_gpgpu;
use serde_json::Value;
use std::path::Path;
use std::time::{Duration, Instant};

mod common;

/// Every command's options, as `classic-gpgpu options` lists them.
fn commands() -> Vec<Value> {
    let out = classic_gpgpu(&["options"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    v["commands"].as_array().unwrap().clone()
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Each option of `kinds` with its command's words: (command words, option).
fn options_of(kinds: &[&str]) -> Vec<(Vec<String>, Value)> {
    let mut found = Vec::new();
    for command in commands() {
        let words: Vec<String> = command["command"]
            .as_str()
            .unwrap()
            .split_whitespace()
            .map(String::from)
            .collect();
        for option in command["options"].as_array().unwrap() {
            if kinds.contains(&option["kind"].as_str().unwrap()) {
                found.push((words.clone(), option.clone()));
            }
        }
    }
    found
}

/// Runs the binary; requires a refusal (exit 1, or clap's 2) without a panic, within a time
/// no work fits in, and returns stderr.
fn refused_at_once(args: &[String]) -> String {
    let start = Instant::now();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(args)
        .output()
        .unwrap();
    let err = stderr(&out);
    assert!(
        matches!(out.status.code(), Some(1 | 2)),
        "{args:?}: {:?} {err}",
        out.status
    );
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    // Not a timing of the program: a refusal takes milliseconds, and a value that was not
    // refused would run for hours or allocate beyond memory first.
    assert!(
        start.elapsed() < Duration::from_secs(60),
        "{args:?} took {:?}",
        start.elapsed()
    );
    err
}

/// A value past the top of any range this program has, and one below the bottom of any.
fn huge_and_negative(kind: &str) -> [&'static str; 2] {
    match kind {
        "count" => ["1e30", "-5"],
        // Past fp64's largest: every real range is finite.
        "real" => ["1e309", "-1e309"],
        // Both WIDTHxHEIGHT and X,Y: the first number is out of range either way.
        _ => ["99999999999x99999999999,1", "-5x-5,-5"],
    }
}

#[test]
fn every_number_refuses_a_huge_and_a_negative_value_naming_the_option() {
    let numbers = options_of(&["count", "real", "pair"]);
    assert!(numbers.len() > 60, "only {} numeric options", numbers.len());
    for (words, option) in numbers {
        let long = option["long"]
            .as_str()
            .unwrap_or_else(|| panic!("{words:?}: a numeric positional argument: {option}"));
        for value in huge_and_negative(option["kind"].as_str().unwrap()) {
            let mut args = words.clone();
            args.extend([format!("--{long}"), value.to_string()]);
            let err = refused_at_once(&args);
            assert!(
                err.contains(&format!("--{long}"))
                    && err.contains(
                        value
                            .split(',')
                            .next()
                            .unwrap_or(value)
                            .split('x')
                            .next()
                            .unwrap()
                    ),
                "{args:?}: the refusal names neither the option nor the value: {err}"
            );
            assert!(
                err.contains(" from ") && err.contains(" to "),
                "{args:?}: the refusal gives no range: {err}"
            );
        }
    }
}

#[test]
fn every_number_states_its_range_in_the_help() {
    for (words, option) in options_of(&["count", "real", "pair"]) {
        let help = option["help"].as_str().unwrap();
        assert!(
            help.contains("[range: ") && help.contains(" from ") && help.ends_with(")]"),
            "{words:?} --{}: the help states no range: {help:?}",
            option["long"]
        );
    }
}

#[test]
fn every_path_is_an_input_or_an_output() {
    for (words, option) in options_of(&["path"]) {
        assert!(
            option["role"].is_string(),
            "{words:?} {}: a path option that src/cli/paths.rs does not name as an input or \
             an output, so the rule of outputs would not see it",
            option["id"]
        );
    }
}

/// A command line for each output option (OUT stands for the path); the inputs need not
/// exist, since an output is refused before any input is read.
const OUTPUTS: &[(&str, &str)] = &[
    (" --trace", "--trace=OUT info"),
    ("collide --dump", "collide a.obj b.obj --dump OUT"),
    ("collide-bench --out", "collide-bench --out OUT"),
    ("mass --dump", "mass cube --dump OUT"),
    ("buoyancy --png-every", "buoyancy --png-every 2 OUT"),
    ("mass-bench --out", "mass-bench --out OUT"),
    ("mesh generate --out", "mesh generate cube --out OUT"),
    ("reproduce --out", "reproduce --out OUT"),
    ("crowd --png", "crowd --png OUT"),
    ("crowd-bench --out", "crowd-bench --out OUT"),
    ("mlp detect --out", "mlp detect image.png --out OUT"),
    ("mlp train --out", "mlp train --out OUT"),
    ("mlp-bench --out", "mlp-bench --out OUT"),
    (
        "lecture1 voronoi --png",
        "lecture1 voronoi sites.json --png OUT",
    ),
    (
        "lecture1 voronoi --npy",
        "lecture1 voronoi sites.json --png v.png --npy OUT",
    ),
    (
        "lecture1 distance-field --npy",
        "lecture1 distance-field m.obj --npy OUT",
    ),
    (
        "lecture1 swept-volume --out",
        "lecture1 swept-volume m.obj --path p.json --out OUT",
    ),
    (
        "lecture1 penetration --png",
        "lecture1 penetration a.obj b.obj --png OUT",
    ),
    (
        "lecture1 penetration --npy",
        "lecture1 penetration a.obj b.obj --npy OUT",
    ),
    ("lecture3 octree --npy", "lecture3 octree --npy OUT"),
    ("lecture3 octree --png", "lecture3 octree --png OUT"),
    ("lecture3 pyramid --npy", "lecture3 pyramid --npy OUT"),
    ("lecture3 pyramid --png", "lecture3 pyramid --png OUT"),
    ("lecture3 displace --out", "lecture3 displace --out OUT"),
    ("lecture3 displace --npy", "lecture3 displace --npy OUT"),
    ("lecture3 displace --png", "lecture3 displace --png OUT"),
    ("lecture3 light --npy", "lecture3 light --npy OUT"),
    ("lecture3 light --png", "lecture3 light --png OUT"),
    ("lecture3 random --npy", "lecture3 random --npy OUT"),
    ("lecture3 random --png", "lecture3 random --png OUT"),
    ("lecture3 depth-mask --png", "lecture3 depth-mask --png OUT"),
    ("lecture3 height-map --out", "lecture3 height-map --out OUT"),
    ("lecture3-bench --out", "lecture3-bench --out OUT"),
    ("selftest --junit", "selftest --junit OUT"),
    (
        "view --screenshot",
        "view --headless --frames 1 --screenshot OUT mass cube",
    ),
    ("glsl export <DIR>", "glsl export OUT"),
    ("learn --png", "learn 1 --png OUT"),
    ("learn --guide", "learn --guide OUT"),
    ("learn --out", "learn reduction --bench --out OUT"),
    ("compare --out", "compare r.json --out OUT"),
    (
        "compare --junit",
        "compare --baseline old.json new.json --junit OUT",
    ),
    ("assets export <DIR>", "assets export OUT"),
    (
        "claims --out",
        "claims --stamp old.json --like new.json --out OUT",
    ),
];

/// Every output option, named as [`OUTPUTS`] names it ("lecture3 octree --png").
fn outputs() -> Vec<String> {
    options_of(&["path", "text"])
        .into_iter()
        .filter(|(_, o)| o["role"] == "output")
        .map(|(words, o)| {
            let name = match o["long"].as_str() {
                Some(long) => format!("--{long}"),
                None => format!("<{}>", o["id"].as_str().unwrap().to_uppercase()),
            };
            format!("{} {name}", words.join(" "))
        })
        .collect()
}

#[test]
fn every_output_refuses_a_link_to_nothing_before_any_work() {
    let dir = common::temp_dir("options", "dangling");
    let listed: Vec<&str> = OUTPUTS.iter().map(|(o, _)| *o).collect();
    let all = outputs();
    for output in &all {
        assert!(
            listed.contains(&output.as_str()),
            "the output {output:?} has no command line in this test's OUTPUTS: add one, so \
             that the rule of outputs is checked for it"
        );
    }
    assert_eq!(all.len(), OUTPUTS.len(), "{all:?}");
    for (i, (output, line)) in OUTPUTS.iter().enumerate() {
        let link = dir.join(format!("link{i}"));
        let nowhere = dir.join(format!("nowhere{i}"));
        std::os::unix::fs::symlink(&nowhere, &link).unwrap();
        let args: Vec<String> = line
            .split_whitespace()
            .map(|w| w.replace("OUT", link.to_str().unwrap()))
            .collect();
        let err = refused_at_once(&args);
        assert!(
            err.contains(link.to_str().unwrap()) && err.contains("does not exist"),
            "{output}: {err}"
        );
        assert!(
            std::fs::symlink_metadata(&link).unwrap().is_symlink(),
            "{output}: the link was replaced"
        );
        assert!(!nowhere.exists(), "{output}: written through the link");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_loop_of_links_and_a_mount_point_are_refused_as_outputs() {
    let dir = common::temp_dir("options", "loop");
    let (a, b) = (dir.join("a.png"), dir.join("b.png"));
    std::os::unix::fs::symlink(&b, &a).unwrap();
    std::os::unix::fs::symlink(&a, &b).unwrap();
    let err = refused_at_once(&["crowd".into(), "--png".into(), a.display().to_string()]);
    assert!(err.contains("loop"), "{err}");
    // /proc is where the kernel's file system is mounted, on every Linux.
    if classic_gpgpu::files::is_mount_point(Path::new("/proc")) {
        let err = refused_at_once(&["reproduce".into(), "--out".into(), "/proc".into()]);
        assert!(err.contains("--out /proc: a mount point"), "{err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn two_outputs_of_one_run_never_share_a_path() {
    let dir = common::temp_dir("options", "shared");
    let f = dir.join("f.png");
    let f = f.to_str().unwrap();
    for args in [
        vec![
            format!("--trace={f}"),
            "selftest".into(),
            "--junit".into(),
            f.into(),
        ],
        vec![
            format!("--trace={f}"),
            "crowd".into(),
            "--png".into(),
            f.into(),
        ],
        vec![
            "lecture1".into(),
            "voronoi".into(),
            "s.json".into(),
            "--png".into(),
            f.into(),
            "--npy".into(),
            format!("{}/./f.png", dir.display()),
        ],
    ] {
        let err = refused_at_once(&args);
        assert!(err.contains("one path for two outputs"), "{args:?}: {err}");
    }
    assert!(!Path::new(f).exists());
    // An output over an input: the input is named.
    let input = dir.join("in.obj");
    std::fs::write(&input, "v 0 0 0\n").unwrap();
    let input = input.display().to_string();
    let err = refused_at_once(&[
        "collide".into(),
        input.clone(),
        "b.obj".into(),
        "--dump".into(),
        input.clone(),
    ]);
    assert!(err.contains("is the input <A>"), "{err}");
    assert_eq!(std::fs::read_to_string(&input).unwrap(), "v 0 0 0\n");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn trace_never_takes_a_subcommand_or_a_lesson_as_its_file() {
    let dir = common::temp_dir("options", "trace");
    // `--trace info` traces `info`: the calls are printed.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(["--trace", "info"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("renderer") && text.contains("gl"), "{text}");
    assert!(!dir.join("info").exists());
    // `learn --trace 1` runs lesson 1 and prints its calls.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(["learn", "--trace", "1"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(!dir.join("1").exists());
    // The file goes after `=`; a word after a bare --trace that the command cannot take is
    // named with how to write the file.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(["--trace", "calls.txt", "info"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let err = stderr(&out);
    assert!(!out.status.success());
    assert!(
        err.contains("'calls.txt'") && err.contains("--trace=calls.txt"),
        "{err}"
    );
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .args(["--trace=calls.txt", "info"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        std::fs::read_to_string(dir.join("calls.txt"))
            .unwrap()
            .lines()
            .count()
            > 1
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn trace_and_json_are_refused_where_they_would_do_nothing() {
    let dir = common::temp_dir("options", "ignored");
    let file = dir.join("t.txt");
    let trace = format!("--trace={}", file.display());
    for args in [
        vec![trace.as_str(), "mesh", "generate", "cube", "--out", "c.obj"],
        vec![trace.as_str(), "glsl", "list"],
        vec!["--trace", "learn", "--list"],
        vec!["--trace", "learn", "1", "--hint", "1"],
        vec![trace.as_str(), "mlp", "train", "--out", "n.json"],
    ] {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        let err = refused_at_once(&args);
        assert!(
            err.contains("--trace") && err.contains("no GL call"),
            "{args:?}: {err}"
        );
    }
    assert!(!file.exists());
    let folder = dir.to_str().unwrap();
    for (args, needle) in [
        (
            vec!["--glsl-dir", folder, "glsl", "list"],
            "no shader would be read",
        ),
        (
            vec!["--renderer", "osmesa", "compare", "r.json"],
            "no renderer",
        ),
    ] {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        let err = refused_at_once(&args);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    for args in [
        vec![
            "--json",
            "view",
            "--headless",
            "--frames",
            "1",
            "--screenshot",
            "v.png",
            "mass",
            "cube",
        ],
        vec!["--json", "compare", "--markdown", "r.json"],
    ] {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        let err = refused_at_once(&args);
        assert!(
            err.contains("--json") && err.contains("nothing to print as JSON"),
            "{err}"
        );
    }
    // --json honoured by hints and solutions.
    for args in [
        &["learn", "1", "--hint", "2", "--json"][..],
        &["learn", "1", "--solution", "--json"],
    ] {
        let v = common::json_of(args);
        assert!(v["lesson"].is_string() && v["shader"].is_string(), "{v}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn options_that_would_change_nothing_are_refused_with_the_reason() {
    let dir = common::temp_dir("options", "nothing");
    let cube = dir.join("cube.obj");
    let cube = cube.to_str().unwrap();
    common::json_of(&["mesh", "generate", "cube", "--out", cube, "--json"]);
    for (args, needles) in [
        (
            vec!["compare", "--markdown", "r.json", "--out", "page"],
            vec!["--out", "--markdown"],
        ),
        (
            vec![
                "lecture1",
                "pairwise",
                cube,
                "--tile",
                "4",
                "--formulation",
                "compute",
            ],
            vec!["--tile 4", "--formulation compute"],
        ),
        (vec!["selftest", "--only", ""], vec!["--only", "empty"]),
        (
            vec!["lecture1", "compare", "--triangles", "300,310"],
            vec!["--triangles 300 and 310", "336 triangles"],
        ),
        (
            vec!["lecture1", "avatar-ccd", "--tolerance", "1e5"],
            vec!["--tolerance 100000", "environment's size"],
        ),
    ] {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        let err = refused_at_once(&args);
        for needle in needles {
            assert!(err.contains(needle), "{args:?}: {needle:?} not in {err}");
        }
    }
    assert!(!dir.join("page").exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_count_the_command_rounds_is_said() {
    let out = classic_gpgpu(&["lecture1", "compare", "--triangles", "300,600", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("--triangles 300: the knotted tube is made of whole rings, so it has 336"),
        "{err}"
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows[0]["asked_triangles"], 300);
    assert_eq!(rows[0]["triangles"], 336);
    assert_eq!(rows[1]["asked_triangles"], 600);
    assert_eq!(rows[1]["triangles"], 600);
}
