//! The one rule for every path a command writes, applied to the parsed command line before any
//! work, whatever the command: each output (a file or a folder, `--out`, `--png`, `--npy`,
//! `--dump`, `--junit`, `--screenshot`, `--guide`, `--trace`, `glsl export DIR`) is checked by
//! [`files::check_destination`] (a link to nothing or a loop of links named and refused, a
//! mount point refused), no two outputs of one run share a path (the second would replace the
//! first), and no output is one of the run's inputs. The writers check again when they write
//! ([`files::write`], [`classic_gpgpu::page::folder::Staged`]); this is where a run that would
//! fail at its end is refused at its start.
//!
//! Which options are outputs is said here, by their ids, once: a path option that is in
//! neither list fails the test that walks every option (`tests/options.rs`).

use anyhow::bail;
use classic_gpgpu::files;
use std::path::{Path, PathBuf};

/// The ids of the options (and positional arguments) that name something a command writes.
pub const OUTPUTS: &[&str] = &[
    "out",
    "png",
    "npy",
    "dump",
    "junit",
    "screenshot",
    "guide",
    "trace",
    "dir",
    "png_every",
];

/// The ids of the path options a command only reads.
pub const INPUTS: &[&str] = &[
    "a",
    "b",
    "baseline",
    "environment",
    "glsl_dir",
    "height",
    "image",
    "input",
    "keyframes",
    "like",
    "model",
    "network",
    "pair",
    "path",
    "results",
    "scene",
    "sites",
    "stamp",
];

/// What a path option names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Role {
    Output,
    Input,
}

/// The role of the option `id`, if it is a path option this module knows.
pub fn role(id: &str) -> Option<Role> {
    if OUTPUTS.contains(&id) {
        Some(Role::Output)
    } else if INPUTS.contains(&id) {
        Some(Role::Input)
    } else {
        None
    }
}

/// One path of the command line: the option as typed (`--png`, `<DIR>`) and its value.
struct Given {
    option: String,
    path: PathBuf,
}

/// Checks every output of the parsed command line by the rule (see the module's doc).
pub fn check(cmd: &clap::Command, matches: &clap::ArgMatches) -> anyhow::Result<()> {
    let (mut outputs, mut inputs) = (Vec::new(), Vec::new());
    let mut globals = Vec::new();
    collect(cmd, matches, &mut globals, &mut outputs, &mut inputs);
    // `--trace` alone (or `--trace=-`) prints the calls: no file.
    outputs.retain(|g| !(g.option == "--trace" && g.path.as_os_str() == "-"));
    for g in &outputs {
        files::check_destination(&g.option, &g.path)?;
    }
    for (i, a) in outputs.iter().enumerate() {
        for b in &outputs[i + 1..] {
            if same_destination(&a.path, &b.path) {
                bail!(
                    "{} {} and {} {} name one path for two outputs of this run, so the one \
                     written last would replace the other; give each its own path",
                    a.option,
                    a.path.display(),
                    b.option,
                    b.path.display()
                );
            }
        }
    }
    for out in &outputs {
        if let Some(input) = inputs.iter().find(|i| files::same_file(&out.path, &i.path)) {
            bail!(
                "{} {} is the input {} {}; an input is never overwritten (not even with \
                 --force), so write to another path",
                out.option,
                out.path.display(),
                input.option,
                input.path.display()
            );
        }
    }
    Ok(())
}

/// The path values of `matches` (the command `cmd` parsed) and of its subcommand, by role; a
/// global option once (clap copies its value to every level).
fn collect(
    cmd: &clap::Command,
    matches: &clap::ArgMatches,
    globals: &mut Vec<String>,
    outputs: &mut Vec<Given>,
    inputs: &mut Vec<Given>,
) {
    for arg in cmd.get_arguments() {
        let id = arg.get_id().as_str();
        let Some(role) = role(id) else { continue };
        if arg.is_global_set() {
            if globals.iter().any(|g| g == id) {
                continue;
            }
            globals.push(id.to_string());
        }
        let Ok(Some(raw)) = matches.try_get_raw(id) else {
            continue;
        };
        let values: Vec<&std::ffi::OsStr> = raw.collect();
        // `--png-every K DIR`: the folder is the second of each pair.
        let paths: Vec<&std::ffi::OsStr> = if id == "png_every" {
            values.iter().skip(1).step_by(2).copied().collect()
        } else {
            values
        };
        let option = classic_gpgpu::values::option_name(Some(arg));
        let list = match role {
            Role::Output => &mut *outputs,
            Role::Input => &mut *inputs,
        };
        list.extend(paths.into_iter().map(|p| Given {
            option: option.clone(),
            path: PathBuf::from(p),
        }));
    }
    if let Some((name, sub_matches)) = matches.subcommand() {
        if let Some(sub) = cmd.find_subcommand(name) {
            collect(sub, sub_matches, globals, outputs, inputs);
        }
    }
}

/// Whether two outputs would be one file: the same file through links, or the same place
/// when they do not exist yet.
fn same_destination(a: &Path, b: &Path) -> bool {
    files::same_file(a, b) || where_it_goes(a) == where_it_goes(b)
}

/// The full name `path` would have once written: its own when it exists, else its parent
/// folder's full name and its name, else the path made absolute.
fn where_it_goes(path: &Path) -> PathBuf {
    if let Ok(real) = std::fs::canonicalize(path) {
        return real;
    }
    let parent = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    match (std::fs::canonicalize(parent), path.file_name()) {
        (Ok(parent), Some(name)) => parent.join(name),
        _ => std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf()),
    }
}
