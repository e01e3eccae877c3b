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
