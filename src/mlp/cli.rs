//! `classic-gpgpu mlp run | detect | train`.

use super::cpu::{forward, CpuProduct};
use super::detect::{classify_cpu, mask_image, shipped_detector, THRESHOLD};
use super::network::{parse_inputs, Network};
use super::train::{evaluate, train, window_set, TrainConfig};
use anyhow::Context as _;
use std::path::{Path, PathBuf};

/// Paper 3: the multilayer perceptron as render passes, and text detection.
#[derive(clap::Args, Debug)]
pub struct MlpArgs {
    #[command(subcommand)]
    command: MlpCommand,
}

#[derive(clap::Subcommand, Debug)]
enum MlpCommand {
    /// Runs a network file on an input file and prints the outputs and timings.
    Run(RunArgs),
    /// Classifies every pixel of a grey image as text / non-text (11 x 11 windows).
    Detect(DetectArgs),
    /// Trains the text detector on synthetic text (reproduces assets/mlp/text_detector.json).
    Train(TrainArgs),
}

#[derive(clap::Args, Debug)]
struct RunArgs {
    /// Network JSON: {"layers":[{"weights":[[..N..] x M],"bias":[..M..],"activation":"sigmoid"|"identity"}, ...]}
    #[arg(long)]
    network: PathBuf,
    /// Inputs JSON: [[..N..], ...], one row per input vector.
    #[arg(long)]
    input: PathBuf,
    /// Machine-readable output.
    #[arg(long)]
    json: bool,
}

#[derive(clap::Args, Debug)]
struct DetectArgs {
    /// The image (any format the `image` crate reads; colour is converted to grey).
    image: PathBuf,
    /// Where to write the classified image (black = text).
    #[arg(long)]
    out: Option<PathBuf>,
    /// A network file to use instead of the shipped detector (121 inputs, 1 output).
    #[arg(long)]
    network: Option<PathBuf>,
    /// Output above which a pixel is text.
    #[arg(long, default_value_t = THRESHOLD)]
    threshold: f32,
    #[arg(long)]
    json: bool,
}

#[derive(clap::Args, Debug)]
struct TrainArgs {
    /// Where to write the trained network.
    #[arg(long, default_value = "assets/mlp/text_detector.json")]
    out: PathBuf,
    /// Seed of the synthetic data, the initial weights and the sample order.
    #[arg(long, default_value_t = TrainConfig::default().seed)]
    seed: u64,
    /// Training epochs.
    #[arg(long, default_value_t = TrainConfig::default().epochs)]
    epochs: usize,
    /// Synthetic training images.
    #[arg(long, default_value_t = TrainConfig::default().images)]
    images: usize,
    #[arg(long)]
    json: bool,
}

/// Runs an `mlp` subcommand.
pub fn run(args: MlpArgs) -> anyhow::Result<()> {
    match args.command {
        MlpCommand::Run(a) => run_network(a),
        MlpCommand::Detect(a) => detect(a),
        MlpCommand::Train(a) => train_detector(a),
    }
}

fn read_network(path: &Path) -> anyhow::Result<Network> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read the network file {}", path.display()))?;
    Network::from_json(&text).with_context(|| format!("bad network file {}", path.display()))
}

fn run_network(args: RunArgs) -> anyhow::Result<()> {
    let net = read_network(&args.network)?;
    let text = std::fs::read_to_string(&args.input)
        .with_context(|| format!("cannot read the input file {}", args.input.display()))?;
    let inputs = parse_inputs(&text, net.inputs())
        .with_context(|| format!("bad input file {}", args.input.display()))?;
    let result = forward(CpuProduct::Plain, &net, inputs.view());
    let outputs: Vec<Vec<f32>> = result.outputs.outer_iter().map(|r| r.to_vec()).collect();
    let report = serde_json::json!({
        "renderer": CpuProduct::Plain.name(),
        "outputs": outputs,
        "timings_ms": {
            "texture_creation": 0.0,
            "matmul": result.product.as_secs_f64() * 1e3,
            "activation": result.activation.as_secs_f64() * 1e3,
        },
    });
    if args.json {
        println!("{report}");
    } else {
        for row in &outputs {
            let cells: Vec<String> = row.iter().map(|v| format!("{v:.6}")).collect();
            println!("{}", cells.join(" "));
        }
    }
    Ok(())
}

fn detect(args: DetectArgs) -> anyhow::Result<()> {
    let net = match &args.network {
        Some(path) => read_network(path)?,
        None => shipped_detector().context("the shipped detector")?,
    };
    anyhow::ensure!(
        net.inputs() == super::window::WINDOW_INPUTS && net.outputs() == 1,
        "the detector network must take {} inputs (an 11 x 11 window) and give 1 output; this one takes {} and gives {}",
        super::window::WINDOW_INPUTS,
        net.inputs(),
        net.outputs()
    );
    let image = image::open(&args.image)
        .with_context(|| format!("cannot read the image {}", args.image.display()))?
        .to_luma8();
    let outputs = classify_cpu(&net, &image, CpuProduct::Optimised, 1 << 16);
    let mask = mask_image(&outputs, image.width(), image.height(), args.threshold);
    let text_pixels = mask.pixels().filter(|p| p.0[0] == 0).count();
    if let Some(out) = &args.out {
        mask.save(out)
            .with_context(|| format!("cannot write {}", out.display()))?;
    }
    let report = serde_json::json!({
        "image": args.image.display().to_string(),
        "width": image.width(),
        "height": image.height(),
        "text_pixels": text_pixels,
        "text_fraction": text_pixels as f64 / outputs.len() as f64,
        "out": args.out.as_ref().map(|p| p.display().to_string()),
    });
    if args.json {
        println!("{report}");
    } else {
        println!(
            "{}: {} x {}, {} text pixels ({:.1}%)",
            args.image.display(),
            image.width(),
            image.height(),
            text_pixels,
            100.0 * text_pixels as f64 / outputs.len() as f64
        );
    }
    Ok(())
}

fn train_detector(args: TrainArgs) -> anyhow::Result<()> {
    let config = TrainConfig {
        seed: args.seed,
        epochs: args.epochs,
        images: args.images,
        ..TrainConfig::default()
    };
    let set = window_set(config.seed, config.images, config.windows_per_class);
    let trained = train(&config, &set);
    // held-out images from another seed
    let test = window_set(
        config.seed.wrapping_add(1),
        config.images / 4,
        config.windows_per_class,
    );
    let outputs = forward(CpuProduct::Optimised, &trained.network, test.inputs.view()).outputs;
    let quality = evaluate(outputs.column(0), &test.labels, THRESHOLD);
    std::fs::write(&args.out, trained.network.to_json() + "\n")
        .with_context(|| format!("cannot write {}", args.out.display()))?;
    let report = serde_json::json!({
        "config": config,
        "training_windows": set.labels.len(),
        "loss_per_epoch": trained.loss_per_epoch,
        "held_out": quality,
        "out": args.out.display().to_string(),
    });
    if args.json {
        println!("{report}");
    } else {
        println!("{}", serde_json::to_string_pretty(&report)?);
    }
    Ok(())
}
