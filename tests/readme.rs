//! The README as a newcomer uses it: every command the binary knows has a line or a table row
//! there, and no command line turns into a shell pipeline when it is pasted.

mod common;

use std::collections::BTreeSet;

fn readme() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).expect("README.md")
}

/// The subcommands `classic-gpgpu <path> --help` lists under "Commands:" (clap's own list),
/// without clap's `help`.
fn subcommands_of(path: &[String]) -> Vec<String> {
    let mut args: Vec<&str> = path.iter().map(String::as_str).collect();
    args.push("--help");
    let out = common::classic_gpgpu(&args);
    assert!(out.status.success(), "{args:?} --help failed");
    let text = String::from_utf8(out.stdout).expect("UTF-8 help");
    let mut lines = text.lines().skip_while(|l| l.trim_end() != "Commands:");
    lines.next();
    lines
        .take_while(|l| !l.trim().is_empty())
        .filter(|l| l.starts_with("  ") && !l.starts_with("   "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|name| *name != "help")
        .map(str::to_string)
        .collect()
}

/// Every command path clap knows ("info", "lecture1 voronoi", "view mlp detect", ...):
/// the leaves and the commands that have subcommands of their own.
fn every_command() -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let mut todo = vec![Vec::<String>::new()];
    while let Some(path) = todo.pop() {
        for name in subcommands_of(&path) {
            let mut child = path.clone();
            child.push(name);
            found.insert(child.join(" "));
            todo.push(child);
        }
    }
    found
}

/// The lines of the README's ```sh blocks.
fn sh_lines(readme: &str) -> Vec<&str> {
    let mut inside = false;
    let mut lines = Vec::new();
    for line in readme.lines() {
        if line.starts_with("```") {
            inside = !inside && line.trim_start_matches('`').trim() == "sh";
            continue;
        }
        if inside {
            lines.push(line);
        }
    }
    lines
}

/// A command line's code, without its trailing `# comment`.
fn code_of(line: &str) -> &str {
    line.split(" #").next().unwrap_or(line).trim()
}

#[test]
fn every_subcommand_has_a_line_or_a_table_row_in_the_readme() {
    let readme = readme();
    let commands = every_command();
    // clap lists at least the papers' commands and lecture 1's and 3's techniques.
    for known in [
        "info",
        "reproduce",
        "lecture1 voronoi",
        "lecture3 octree",
        "view mlp detect",
    ] {
        assert!(commands.contains(known), "{known} not in {commands:?}");
    }
    let table_rows: Vec<&str> = readme.lines().filter(|l| l.starts_with('|')).collect();
    let missing: Vec<&String> = commands
        .iter()
        .filter(|path| {
            let on_a_line = readme.contains(&format!("classic-gpgpu {path}"));
            let in_a_row = table_rows
                .iter()
                .any(|row| row.contains(&format!("`{path}")));
            !on_a_line && !in_a_row
        })
        .collect();
    assert!(
        missing.is_empty(),
        "these commands have no `classic-gpgpu ...` line or table row in README.md: {missing:?}"
    );
}

#[test]
fn no_readme_command_line_is_a_pipeline_of_subcommands() {
    let readme = readme();
    let commands = every_command();
    let first_words: BTreeSet<&str> = commands
        .iter()
        .filter_map(|path| path.split(' ').next())
        .collect();
    let lines = sh_lines(&readme);
    assert!(lines.len() > 20, "README's sh blocks not found");
    for line in lines {
        let code = code_of(line);
        for piece in code.split('|').skip(1) {
            let next = piece.split_whitespace().next().unwrap_or("");
            assert!(
                !first_words.contains(next),
                "README line pipes into `{next}`, a subcommand: pasted, it runs as a \
                 pipeline: {line}"
            );
        }
    }
    // The check sees a pipeline where there is one.
    assert_eq!(
        code_of("classic-gpgpu a | b  # c | d"),
        "classic-gpgpu a | b"
    );
}

#[test]
fn the_install_lines_work_as_root_and_as_a_user() {
    let readme = readme();
    let lines = sh_lines(&readme);
    let installs: Vec<&&str> = lines
        .iter()
        .filter(|l| l.contains("apt-get install"))
        .collect();
    assert!(!installs.is_empty(), "no apt-get install line");
    for line in installs {
        let code = code_of(line);
        assert!(code.contains(" -y "), "no -y: {line}");
        assert!(
            !code.starts_with("sudo "),
            "sudo is missing where one runs as root (containers): {line}"
        );
    }
    let cargo_install = lines
        .iter()
        .find(|l| l.starts_with("cargo install"))
        .expect("a cargo install line");
    assert!(cargo_install.contains("--locked"), "{cargo_install}");
    // The Rust version before the build, and the same as Cargo.toml's.
    let toml = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml")).unwrap();
    let version = toml
        .lines()
        .find_map(|l| l.strip_prefix("rust-version = "))
        .expect("rust-version in Cargo.toml")
        .trim_matches('"');
    let said = readme
        .find(&format!("Rust {version}"))
        .expect("the Rust version");
    assert!(said < readme.find("cargo install").unwrap());
}

#[test]
fn bench_output_folders_are_ignored_by_git() {
    let ignore =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/.gitignore")).unwrap();
    for bench in every_command().iter().filter(|c| c.ends_with("-bench")) {
        assert!(
            ignore.lines().any(|l| l.trim_matches('/') == bench),
            "{bench}'s default output folder is not in .gitignore"
        );
    }
}

/// The README's `classic-gpgpu ...` lines (with any `VAR=value` before the name), in order:
/// the line and its code.
fn command_lines(readme: &str) -> Vec<(&str, &str)> {
    sh_lines(readme)
        .into_iter()
        .map(|line| (line, code_of(line)))
        .filter(|(_, code)| {
            code.split_whitespace()
                .find(|word| !word.contains('='))
                .is_some_and(|word| word == "classic-gpgpu")
        })
        .collect()
}

/// A line whose comment says this fails on purpose: it must exit non-zero, with an error and
/// no panic.
const FAILS_ON_PURPOSE: &str = "fails until";

/// Where the test runs a README line otherwise than as written, and why: a line whose code is
/// `matches` gets `appended` (the first that matches). Nothing else is changed.
struct Substitution {
    matches: fn(&str) -> bool,
    appended: &'static str,
    why: &'static str,
}

const SUBSTITUTIONS: &[Substitution] = &[
    Substitution {
        matches: |code| code == "classic-gpgpu reproduce",
        appended: " --quick",
        why: "the full report takes minutes; --quick runs every section at small sizes",
    },
    Substitution {
        matches: |code| {
            code.split_whitespace()
                .nth(1)
                .is_some_and(|c| c.ends_with("-bench"))
                && !code.contains("--quick")
        },
        appended: " --quick",
        why: "a benchmark runs its section at the papers' sizes, for minutes",
    },
    Substitution {
        matches: |code| code.split_whitespace().any(|w| w == "view"),
        appended: " --headless --frames 2 --screenshot {view}.png",
        why: "a test has no display: the same demo drawn on the headless renderer (tests/view.rs \
              runs the windows under Xvfb)",
    },
    Substitution {
        matches: |code| {
            (code.contains("lecture1 distance-field") || code.contains("lecture1 swept-volume"))
                && !code.contains("--resolution")
        },
        appended: " --resolution 32",
        why: "a field of 64^3 voxels over the bunny takes a minute on a software renderer; 32^3 \
              runs the same passes",
    },
];

/// The code the test runs for README line number `n` (its code as written, or substituted).
fn as_run(code: &str, n: usize) -> (String, Option<&'static str>) {
    match SUBSTITUTIONS.iter().find(|s| (s.matches)(code)) {
        Some(s) => (
            format!(
                "{code}{}",
                s.appended.replace("{view}", &format!("view-{n}"))
            ),
            Some(s.why),
        ),
        None => (code.to_string(), None),
    }
}

/// Whether zink (on lavapipe) starts here; the README's zink line needs mesa-vulkan-drivers.
fn zink_starts() -> bool {
    std::process::Command::new(env!("CARGO_BIN_EXE_classic-gpgpu"))
        .arg("info")
        .env("GALLIUM_DRIVER", "zink")
        .env("LIBGL_ALWAYS_SOFTWARE", "1")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).contains("zink"))
}

/// Every `classic-gpgpu ...` line of the README, in order, as a new user runs them: in one
/// empty folder, with the built binary first on `PATH` as `classic-gpgpu`, each line through
/// `sh -c` (so `&&` and `VAR=value` work as pasted). Lines run as written except where
/// [`SUBSTITUTIONS`] says; a line whose comment says it [`FAILS_ON_PURPOSE`] must fail cleanly.
/// The first line that breaks fails the test, named with its output. Prints how many ran.
#[test]
fn every_readme_command_line_runs_in_order_from_an_empty_folder() {
    let readme = readme();
    let lines = command_lines(&readme);
    assert!(lines.len() > 50, "{} command lines", lines.len());
    let root = common::temp_dir("readme", "lines");
    let (bin, work) = (root.join("bin"), root.join("work"));
    std::fs::create_dir_all(&bin).unwrap();
    std::fs::create_dir_all(&work).unwrap();
    std::os::unix::fs::symlink(
        env!("CARGO_BIN_EXE_classic-gpgpu"),
        bin.join("classic-gpgpu"),
    )
    .unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let zink = zink_starts();
    let (mut ran, mut substituted, mut skipped) = (0, 0, 0);
    for (n, (line, code)) in lines.iter().enumerate() {
        if code.contains("GALLIUM_DRIVER=zink") && !zink {
            eprintln!("skipped (zink does not start here): {line}");
            skipped += 1;
            continue;
        }
        let (run, why) = as_run(code, n);
        if let Some(why) = why {
            eprintln!("runs as `{run}`: {why}");
            substituted += 1;
        }
        let out = std::process::Command::new("sh")
            .args(["-c", &run])
            .current_dir(&work)
            .env("PATH", &path)
            // The README's lines use the default renderer unless a line names another.
            .env_remove(classic_gpgpu::gl::RENDERER_ENV)
            .env_remove("GALLIUM_DRIVER")
            .env_remove("LIBGL_ALWAYS_SOFTWARE")
            .output()
            .expect("sh runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        let said = format!(
            "README line {} of {}: {line}\nran: {run}\nexit: {:?}\nstdout (end): {}\nstderr: {stderr}",
            n + 1,
            lines.len(),
            out.status.code(),
            tail(&String::from_utf8_lossy(&out.stdout))
        );
        assert!(!stderr.contains("panicked"), "a panic: {said}");
        if line.contains(FAILS_ON_PURPOSE) {
            assert!(!out.status.success(), "said to fail, but passed: {said}");
            assert!(
                stderr.contains("error") || !out.stdout.is_empty(),
                "no word why: {said}"
            );
        } else {
            assert!(out.status.success(), "{said}");
        }
        ran += 1;
    }
    eprintln!("{ran} README lines run ({substituted} substituted), {skipped} skipped, 0 failed");
    std::fs::remove_dir_all(&root).ok();
}

/// The last lines of `text`.
fn tail(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(15)..].join("\n")
}

#[test]
fn the_substitutions_touch_only_the_lines_they_name() {
    assert_eq!(
        as_run("classic-gpgpu reproduce", 0).0,
        "classic-gpgpu reproduce --quick"
    );
    assert_eq!(as_run("classic-gpgpu reproduce --quick", 0).1, None);
    assert_eq!(
        as_run("classic-gpgpu mass-bench", 0).0,
        "classic-gpgpu mass-bench --quick"
    );
    assert_eq!(
        as_run("classic-gpgpu view mass bunny", 7).0,
        "classic-gpgpu view mass bunny --headless --frames 2 --screenshot view-7.png"
    );
    assert_eq!(as_run("classic-gpgpu mass bunny --dump peels/", 0).1, None);
    let readme = readme();
    let lines = command_lines(&readme);
    assert!(lines.iter().any(|(l, _)| l.contains(FAILS_ON_PURPOSE)));
    assert!(lines
        .iter()
        .any(|(_, c)| c.starts_with("GALLIUM_DRIVER=softpipe classic-gpgpu")));
    // Every substitution is used by some line (a stale one is a silent edit waiting).
    for s in SUBSTITUTIONS {
        assert!(
            lines.iter().any(|(_, c)| (s.matches)(c)),
            "unused: {}",
            s.why
        );
    }
}

/// The report's timing policy is said in the README in the same words.
#[test]
fn the_readme_states_the_reports_timing_policy() {
    let flat = readme()
        .lines()
        .map(|l| l.trim().trim_start_matches("- "))
        .collect::<Vec<_>>()
        .join(" ");
    assert!(
        flat.contains(classic_gpgpu::report::timing_policy::IN_WORDS),
        "README lacks the policy: {}",
        classic_gpgpu::report::timing_policy::IN_WORDS
    );
}
