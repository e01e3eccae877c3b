//! `assets list` and `assets export DIR`: the inputs the project ships (the bunny, paper 3's
//! text image, detector and XOR sample, lecture 3's height map, example files of lecture 1's
//! formats), compiled into the binary, so that every line of the README runs from any folder:
//! `classic-gpgpu assets export assets` writes them as `assets/...`, the paths the README and
//! a clone of the repository use.

use std::path::{Path, PathBuf};

/// One shipped input: its path under the export folder (and under the repository's
/// `assets/`), what it is, and its bytes.
struct Asset {
    path: &'static str,
    what: &'static str,
    bytes: &'static [u8],
}

macro_rules! shipped {
    ($path:literal, $what:literal) => {
        Asset {
            path: $path,
            what: $what,
            bytes: include_bytes!(concat!("../../assets/", $path)),
        }
    };
}

const ASSETS: &[Asset] = &[
    shipped!(
        "bunny.obj",
        "the Stanford bunny (1839 vertices, 3674 triangles)"
    ),
    shipped!(
        "lecture1/path.json",
        "three keyframes for `lecture1 swept-volume --path`"
    ),
    shipped!(
        "lecture1/sites.json",
        "points, a segment and a triangle for `lecture1 voronoi`"
    ),
    shipped!(
        "lecture3/height.png",
        "the 64x64 height map `lecture3 displace` uses by default"
    ),
    shipped!(
        "mlp/text.png",
        "scikit-image's text image, paper 3's test picture here"
    ),
    shipped!(
        "mlp/text_detector.json",
        "the detector `mlp detect` uses by default"
    ),
    shipped!(
        "mlp/xor_inputs.json",
        "the four inputs of XOR, for `mlp run --input`"
    ),
    shipped!(
        "mlp/xor_network.json",
        "a 2-2-1 network computing XOR, for `mlp run`"
    ),
];

#[derive(clap::Subcommand, Debug)]
pub enum AssetsCommand {
    /// Every shipped input: its path and what it is.
    List,
    /// Write every shipped input to DIR/<its path> (`assets export assets` gives the README's
    /// `assets/...` paths). A file already there with the same bytes is left as it is; one
    /// that differs is replaced only with --force.
    Export {
        /// The folder to write into (made if missing).
        dir: PathBuf,
        /// Replace files that exist with other contents.
        #[arg(long)]
        force: bool,
    },
}

pub fn run(command: &AssetsCommand, json: bool) -> anyhow::Result<()> {
    match command {
        AssetsCommand::List => {
            if json {
                let list: Vec<serde_json::Value> = ASSETS
                    .iter()
                    .map(|a| {
                        serde_json::json!({"path": a.path, "what": a.what, "bytes": a.bytes.len()})
                    })
                    .collect();
                println!("{}", serde_json::to_string_pretty(&list)?);
            } else {
                let width = ASSETS.iter().map(|a| a.path.len()).max().unwrap_or(0);
                for a in ASSETS {
                    println!("{:width$}  {}", a.path, a.what);
                }
            }
            Ok(())
        }
        AssetsCommand::Export { dir, force } => export(dir, *force, json),
    }
}

/// Every file checked before any is written: an existing one with other bytes only with
/// `force`; then the missing and differing ones written whole.
fn export(dir: &Path, force: bool, json: bool) -> anyhow::Result<()> {
    classic_gpgpu::files::check_folder("assets export", dir)?;
    let plan: Vec<(PathBuf, &Asset)> = ASSETS.iter().map(|a| (dir.join(a.path), a)).collect();
    let same = |path: &Path, a: &Asset| std::fs::read(path).is_ok_and(|b| b == a.bytes);
    let differing: Vec<&PathBuf> = plan
        .iter()
        .filter(|(p, a)| p.exists() && !same(p, a))
        .map(|(p, _)| p)
        .collect();
    if let (Some(first), false) = (differing.first(), force) {
        anyhow::bail!(
            "assets export: {} of the {} files exist under {} with other contents (the first: \
             {}); pass --force to replace them, or give another folder",
            differing.len(),
            plan.len(),
            dir.display(),
            first.display()
        );
    }
    let mut written = Vec::new();
    for (path, asset) in plan.iter().filter(|(p, a)| !same(p, a)) {
        classic_gpgpu::files::check_output("assets export", path, &[], true, &[])?;
        classic_gpgpu::files::write_bytes(path, asset.bytes)?;
        written.push(path.display().to_string());
    }
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&serde_json::json!({
                "dir": dir.display().to_string(),
                "written": written,
                "already_there": plan.len() - written.len(),
            }))?
        );
    } else {
        println!(
            "wrote {} of the {} shipped inputs under {} ({} already there)",
            written.len(),
            plan.len(),
            dir.display(),
            plan.len() - written.len()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_file_the_readme_names_under_assets_is_shipped() {
        let readme = include_str!("../../README.md");
        for word in readme.split(|c: char| c.is_whitespace() || c == '`') {
            let word = word.trim_end_matches(['.', ',', ';', ':', ')']);
            if let Some(path) = word.strip_prefix("assets/") {
                let known = path.is_empty()
                    || path.starts_with("results/")
                    || path.starts_with("readme/")
                    || path.ends_with('/')
                    || ["paper_tables.toml", "period_gpus.toml"].contains(&path)
                    || ASSETS.iter().any(|a| a.path == path);
                assert!(
                    known,
                    "README names assets/{path}, which `assets export` lacks"
                );
            }
        }
    }
}
