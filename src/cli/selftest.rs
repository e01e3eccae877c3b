//! `classic-gpgpu selftest`: every check of [`classic_gpgpu::selftest`] on the chosen
//! renderer; one line per check (or `--json`), a JUnit XML file with `--junit`, and a non-zero
//! exit when any check fails.

use anyhow::{bail, Context as _};
use classic_gpgpu::gl::Context;
use classic_gpgpu::selftest;
use std::path::PathBuf;

/// Arguments of `selftest`.
#[derive(clap::Args, Debug)]
pub struct SelftestArgs {
    /// Also write the results as JUnit XML to this file (FILE.xml; an existing file only
    /// with --force).
    #[arg(long, value_name = "FILE")]
    pub junit: Option<PathBuf>,
    /// Replace the --junit file when it exists (a CI job that reruns in one workspace).
    #[arg(long, requires = "junit")]
    pub force: bool,
    /// Run only the checks whose name or group contains one of these (comma separated),
    /// e.g. `--only gl,paper4`.
    #[arg(long, value_delimiter = ',')]
    pub only: Vec<String>,
}

/// Runs `selftest`.
pub fn run(args: &SelftestArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    if let Some(path) = &args.junit {
        classic_gpgpu::files::check_output("--junit", path, &[], args.force, &["xml"])?;
    }
    if args.only.iter().any(|o| o.trim().is_empty()) {
        bail!(
            "--only {:?}: an empty name matches every check, so it would select nothing; name \
             checks or groups (gl, paper1-4, lecture3), or leave out --only",
            args.only.join(",")
        );
    }
    let known = |o: &str| {
        selftest::checks()
            .iter()
            .any(|c| c.name.contains(o) || c.group == o)
    };
    if let Some(unknown) = args.only.iter().find(|o| !known(o)) {
        let names: Vec<_> = selftest::checks().iter().map(|c| c.name).collect();
        bail!(
            "--only {unknown}: no check matches it; the checks are {} (groups gl, paper1-4, \
             lecture3)",
            names.join(", ")
        );
    }
    let checks: Vec<_> = selftest::checks()
        .into_iter()
        .filter(|c| {
            args.only.is_empty()
                || args
                    .only
                    .iter()
                    .any(|o| c.name.contains(o.as_str()) || c.group == o)
        })
        .collect();
    if checks.is_empty() {
        let names: Vec<_> = selftest::checks().iter().map(|c| c.name).collect();
        bail!(
            "--only {}: no check matches; the checks are {} (groups gl, paper1-4, lecture3)",
            args.only.join(","),
            names.join(", ")
        );
    }
    let results = selftest::run(ctx, &checks);
    if let Some(path) = &args.junit {
        classic_gpgpu::files::write_bytes(path, selftest::to_junit(&results).as_bytes())
            .context("--junit: the JUnit report was not written")?;
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&results)?);
    } else {
        print!("{}", selftest::to_text(&results));
    }
    if !results.all_passed() {
        bail!(
            "{} of {} checks failed on {}",
            results.failed,
            results.checks.len(),
            results.renderer
        );
    }
    Ok(())
}
