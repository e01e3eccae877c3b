use clap::Parser;

/// The classic GPGPU papers of a 2007 tutorial, reproduced on a headless OpenGL context.
#[derive(Parser)]
#[command(version, about)]
struct Cli {}

fn main() {
    let _ = Cli::parse();
}
