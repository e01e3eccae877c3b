//! `classic-gpgpu claims`: every claim this build can make, with its id and its versions at
//! the papers' sizes and at `--quick` sizes, and what each version is a hash of (the rule's
//! regions, the published values, the workload's regions). No run is needed: a kept run's
//! claim is current when its version is the one listed here. `--stamp` gives a run from before
//! per-claim versions this build's ([`classic_gpgpu::compare::stamp`]).

use anyhow::Context as _;
use classic_gpgpu::compare::{stamp, Run};
use classic_gpgpu::report::claim_defs;
use std::path::PathBuf;

/// Arguments of `claims`.
#[derive(clap::Args, Debug)]
pub struct ClaimsArgs {
    /// Give the claims of OLD_JSON (a results.json from before per-claim versions) this
    /// build's ids and versions, written to --out: for a kept run that cannot be made again,
    /// whose claims have not changed since. Needs --like and --out.
    #[arg(long, value_name = "OLD_JSON", requires_all = ["like", "out"])]
    pub stamp: Option<PathBuf>,
    /// A results.json of this build: an old claim takes the id of its claim with the same
    /// section and words.
    #[arg(long, value_name = "RESULTS_JSON", requires = "stamp")]
    pub like: Option<PathBuf>,
    /// Claims (ids, comma separated) whose rule, published value or sizes changed since the
    /// old run: they keep no version ("re-run needed").
    #[arg(long, value_delimiter = ',', requires = "stamp")]
    pub except: Vec<String>,
    /// Where the stamped copy goes (FILE.json: a new file, an existing one only with --force,
    /// never OLD_JSON).
    #[arg(long, value_name = "FILE", requires = "stamp")]
    pub out: Option<PathBuf>,
    /// Replace the --out file when it exists.
    #[arg(long, requires = "out")]
    pub force: bool,
}

pub fn run(args: &ClaimsArgs, json: bool) -> anyhow::Result<()> {
    if let (Some(old), Some(like), Some(out)) = (&args.stamp, &args.like, &args.out) {
        classic_gpgpu::files::check_output(
            "--out",
            out,
            &[old.as_path(), like.as_path()],
            args.force,
            &["json"],
        )?;
        // Read as a run first: the same bounds and checks as `compare`.
        Run::read(old)?;
        let text =
            std::fs::read_to_string(old).with_context(|| format!("reading {}", old.display()))?;
        let like = Run::read(like)?;
        let (stamped, ids) = stamp::stamp(&text, &old.display().to_string(), &like, &args.except)?;
        classic_gpgpu::files::write_bytes(out, stamped.as_bytes())?;
        println!(
            "{}: {} claims stamped ({}), written to {}",
            old.display(),
            ids.len(),
            ids.join(", "),
            out.display()
        );
        return Ok(());
    }
    let listed = claim_defs::listed().map_err(anyhow::Error::msg)?;
    if json {
        println!("{}", serde_json::to_string_pretty(&listed)?);
        return Ok(());
    }
    for claim in &listed {
        println!(
            "{}  {}  quick {}{}",
            claim.id,
            claim.version,
            claim.quick_version,
            claim
                .band
                .map_or(String::new(), |b| format!("  band {:.0}%", 100.0 * b))
        );
        println!("    rule: {}", claim.rule.join(", "));
        if !claim.published.is_empty() {
            println!(
                "    published: assets/paper_tables.toml {}",
                claim.published.join(", ")
            );
        }
        println!("    workload: {}", claim.workload.join(", "));
    }
    println!("{} claims", listed.len());
    Ok(())
}
