//! `classic-gpgpu compare`: several runs' results.json side by side, as a page or as the
//! README's table, or one run against a baseline (`--baseline`: the regression gate, exit 1
//! when a claim regressed).

use anyhow::{bail, Context as _};
use classic_gpgpu::compare::{self, gate, CompareArgs, Run};
use std::io::Write as _;
use std::path::Path;

pub fn run(args: &CompareArgs, json: bool) -> anyhow::Result<()> {
    if let Some(baseline) = &args.baseline {
        return regression_gate(args, baseline, json);
    }
    if args.markdown {
        print!("{}", compare::markdown::grouped(&args.results)?);
        return Ok(());
    }
    let runs = compare::read(&args.results)?;
    let comparison = compare::compare(runs)?;
    compare::write_page(&comparison, &args.out, &args.results, args.force)?;
    if json {
        println!("{}", serde_json::to_string_pretty(&comparison)?);
    } else {
        for g in &comparison.groups {
            let labels: Vec<&str> = g.machines.iter().map(|m| m.label.as_str()).collect();
            // A claim's rows (one per version) follow each other; without an id, its words.
            let mut ids: Vec<&str> = g
                .claims
                .iter()
                .map(|r| if r.id.is_empty() { &r.claim } else { &r.id })
                .map(String::as_str)
                .collect();
            ids.dedup();
            // A row whose version two or more runs judged: those runs compare on it.
            let shared = g
                .claims
                .iter()
                .filter(|r| r.cells.iter().filter(|c| c.ran).count() >= 2)
                .count();
            println!(
                "{} run{} at {} ({}): {} claims; {shared} compared side by side (the same \
                 version in two or more runs); {} changed definition between the runs",
                labels.len(),
                if labels.len() == 1 { "" } else { "s" },
                if g.quick {
                    "--quick sizes"
                } else {
                    "the papers' sizes"
                },
                labels.join(", "),
                ids.len(),
                g.changed.len()
            );
        }
        println!("the page: {}", args.out.join("index.html").display());
    }
    Ok(())
}

/// `--baseline OLD NEW`: prints each changed claim and the summary line last, writes the
/// JUnit file if asked, and exits 1 when a claim regressed.
fn regression_gate(args: &CompareArgs, baseline: &Path, json: bool) -> anyhow::Result<()> {
    let [new] = args.results.as_slice() else {
        bail!(
            "--baseline compares one results.json with the baseline; {} were given",
            args.results.len()
        );
    };
    if let Some(junit) = &args.junit {
        classic_gpgpu::files::check_output(
            "--junit",
            junit,
            &[baseline, new.as_path()],
            args.force,
            &["xml"],
        )?;
    }
    let (old, new) = (Run::read(baseline)?, Run::read(new)?);
    let result = gate::gate(&old, &new);
    if let Some(junit) = &args.junit {
        classic_gpgpu::files::write_bytes(junit, result.to_junit().as_bytes())
            .context("--junit: the JUnit report was not written")?;
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&result)?);
    } else {
        print!("{}", result.to_text());
    }
    if result.regressed() > 0 {
        // The summary is the last line on stdout, and the exit status says it: no error line.
        std::io::stdout().flush().ok();
        std::process::exit(1);
    }
    Ok(())
}
