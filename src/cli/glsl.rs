//! `glsl list` and `glsl export`: the shader files compiled into the binary
//! (`classic_gpgpu::gl::shaders`), to read or to edit and run with `--glsl-dir`.

use classic_gpgpu::gl::shaders;
use std::path::PathBuf;

#[derive(clap::Subcommand, Debug)]
pub enum GlslCommand {
    /// Every shader file: its path and its first header line (with --json: path, stage, lines,
    /// what comes before it in its stage).
    List,
    /// Write every shader file to DIR/<its path>; edit them, then run any command with
    /// `--glsl-dir DIR` (`view` reloads them as they are saved).
    Export {
        /// The folder to write into (made if missing).
        dir: PathBuf,
        /// Write each lesson's exercise template (glsl/learn/exercises/X) at glsl/learn/X, in
        /// place of the solution, to fill in.
        #[arg(long)]
        exercises: bool,
        /// Replace files that exist already.
        #[arg(long)]
        force: bool,
    },
}

pub fn run(command: &GlslCommand, json: bool) -> anyhow::Result<()> {
    match command {
        GlslCommand::List => list(json),
        GlslCommand::Export {
            dir,
            exercises,
            force,
        } => export(dir, *exercises, *force, json),
    }
}

fn list(json: bool) -> anyhow::Result<()> {
    if json {
        let files: Vec<serde_json::Value> = shaders::ALL
            .iter()
            .map(|s| {
                serde_json::json!({
                    "path": s.name,
                    "stage": shaders::Stage::of(s.name).map_or("snippet", |st| st.name()),
                    "lines": s.source.lines().count(),
                    "compiled_after": shaders::compiled_after(s.source),
                    "header": header(s.source),
                })
            })
            .collect();
        println!("{}", serde_json::to_string_pretty(&files)?);
        return Ok(());
    }
    let width = shaders::ALL.iter().map(|s| s.name.len()).max().unwrap_or(0);
    for s in shaders::ALL {
        println!("{:width$}  {}", s.name, header(s.source));
    }
    println!("{} shader files", shaders::ALL.len());
    Ok(())
}

/// The first sentence of a file's header comment (up to the first line ending in a full
/// stop), without the `//`.
fn header(source: &str) -> String {
    let mut sentence = Vec::new();
    for line in shaders::header_lines(source).filter(|l| !l.starts_with(shaders::COMPILED_AFTER)) {
        let line = line.trim_start_matches('/').trim();
        sentence.push(line);
        if line.ends_with('.') {
            break;
        }
    }
    sentence.join(" ")
}

fn export(dir: &std::path::Path, exercises: bool, force: bool, json: bool) -> anyhow::Result<()> {
    let written = shaders::export(dir, exercises, force)?;
    if json {
        let files: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        println!(
            "{}",
            serde_json::to_string_pretty(&serde_json::json!({
                "dir": dir.display().to_string(),
                "exercises": exercises,
                "written": files.len(),
                "files": files,
            }))?
        );
        return Ok(());
    }
    let what = if exercises {
        " (exercise templates in place of their solutions)"
    } else {
        ""
    };
    println!(
        "wrote {} shader files under {}{what}; edit them and run any command with --glsl-dir {}",
        written.len(),
        dir.display(),
        dir.display()
    );
    Ok(())
}
