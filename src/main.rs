use clap::Parser;

/// The classic GPGPU papers of a 2007 tutorial, reproduced on a headless OpenGL context.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(clap::Subcommand)]
enum Command {
    /// Paper 3 (Oh & Jung 2004): a multilayer perceptron as render passes, text detection.
    Mlp(classic_gpgpu::mlp::cli::MlpArgs),
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().command {
        Command::Mlp(args) => classic_gpgpu::mlp::cli::run(args),
    }
}
