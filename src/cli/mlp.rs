//! `classic-gpgpu mlp run | detect | train` and `classic-gpgpu mlp-bench`.

use anyhow::Context as _;
use classic_gpgpu::gl::Context;
use classic_gpgpu::mlp::chain::{Formulation, GpuMlp, StepTimes};
use classic_gpgpu::mlp::cpu::{forward, CpuProduct};
use classic_gpgpu::mlp::detect::{
    classify_cpu, classify_gpu, mask_image, shipped_detector, THRESHOLD,
};
use classic_gpgpu::mlp::network::{parse_inputs, Network};
use classic_gpgpu::mlp::train::{evaluate, train, window_set, TrainConfig};
use classic_gpgpu::mlp::window::WINDOW_INPUTS;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Paper 3: the multilayer perceptron as render passes, and text detection.
#[derive(clap::Args, Debug)]
pub struct MlpArgs {
    #[command(subcommand)]
    command: MlpCommand,
}

#[derive(clap::Subcommand, Debug)]
enum MlpCommand {
    /// Runs a network file on an input file and prints the outputs and the step timings.
    Run(RunArgs),
    /// Classifies every pixel of a grey image as text / non-text (11 x 11 windows, one batch).
    Detect(DetectArgs),
    /// Trains the text detector on synthetic text (reproduces assets/mlp/text_detector.json).
    Train(TrainArgs),
}

/// Where the network is evaluated.
#[derive(clap::Args, Debug)]
struct Engine {
    /// GPU formulation: the paper's one-value-per-texel passes, or the packed RGBA passes.
    #[arg(long, value_enum, default_value = "faithful")]
    formulation: Formulation,
    /// Evaluate on the CPU instead of the GPU.
    #[arg(long, value_enum)]
    cpu: Option<CpuChoice>,
    /// At most this many input vectors per texture (default: the renderer's maximum texture
    /// size; the paper's board allowed 2048). Larger batches are split into tiles.
    #[arg(long)]
    max_vectors: Option<usize>,
}

#[derive(Clone, Copy, Debug, clap::ValueEnum)]
enum CpuChoice {
    /// The plain inner-product loop.
    Plain,
    /// matrixmultiply's sgemm.
    Optimised,
}

impl From<CpuChoice> for CpuProduct {
    fn from(c: CpuChoice) -> CpuProduct {
        match c {
            CpuChoice::Plain => CpuProduct::Plain,
            CpuChoice::Optimised => CpuProduct::Optimised,
        }
    }
}

#[derive(clap::Args, Debug)]
struct RunArgs {
    /// Network JSON: {"layers":[{"weights":[[..N..] x M],"bias":[..M..],"activation":"sigmoid"|"identity"}, ...]}
    #[arg(long)]
    network: PathBuf,
    /// Inputs JSON: [[..N..], ...], one row per input vector.
    #[arg(long)]
    input: PathBuf,
    #[command(flatten)]
    engine: Engine,
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
    #[command(flatten)]
    engine: Engine,
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
}

/// Runs an `mlp` subcommand; `context` makes the GL context when one is needed.
pub fn run(
    args: MlpArgs,
    json: bool,
    context: impl FnOnce() -> anyhow::Result<Context>,
) -> anyhow::Result<()> {
    match args.command {
        MlpCommand::Run(a) => run_network(a, json, context),
        MlpCommand::Detect(a) => detect(a, json, context),
        MlpCommand::Train(a) => train_detector(a, json),
    }
}

fn read_network(path: &Path) -> anyhow::Result<Network> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read the network file {}", path.display()))?;
    Network::from_json(&text).with_context(|| format!("bad network file {}", path.display()))
}

/// Outputs (L x M) of a batch, where it ran, its step times and tiles.
struct Evaluated {
    outputs: ndarray::Array2<f32>,
    renderer: String,
    times: StepTimes,
    network_upload_ms: f64,
    tiles: usize,
}

fn evaluate_batch(
    net: &Network,
    batch: ndarray::ArrayView2<f32>,
    engine: &Engine,
    context: impl FnOnce() -> anyhow::Result<Context>,
) -> anyhow::Result<Evaluated> {
    if let Some(cpu) = engine.cpu {
        let kind = CpuProduct::from(cpu);
        let result = forward(kind, net, batch);
        return Ok(Evaluated {
            outputs: result.outputs,
            renderer: kind.name().to_string(),
            times: StepTimes {
                matmul: result.product.as_secs_f64() * 1e3,
                activation: result.activation.as_secs_f64() * 1e3,
                ..StepTimes::default()
            },
            network_upload_ms: 0.0,
            tiles: 1,
        });
    }
    let ctx = context()?;
    let gpu = GpuMlp::new(&ctx)?;
    let loaded = gpu.load(net, engine.formulation)?;
    let result = loaded.forward(batch, engine.max_vectors)?;
    Ok(Evaluated {
        outputs: result.outputs,
        renderer: ctx.info().renderer_line(),
        times: result.times,
        network_upload_ms: loaded.upload_ms,
        tiles: result.tiles,
    })
}

fn timings_json(e: &Evaluated) -> serde_json::Value {
    serde_json::json!({
        "texture_creation": e.times.texture_creation,
        "matmul": e.times.matmul,
        "activation": e.times.activation,
        "readback": e.times.readback,
        "network_upload": e.network_upload_ms,
    })
}

fn run_network(
    args: RunArgs,
    json: bool,
    context: impl FnOnce() -> anyhow::Result<Context>,
) -> anyhow::Result<()> {
    let net = read_network(&args.network)?;
    let text = std::fs::read_to_string(&args.input)
        .with_context(|| format!("cannot read the input file {}", args.input.display()))?;
    let inputs = parse_inputs(&text, net.inputs())
        .with_context(|| format!("bad input file {}", args.input.display()))?;
    let result = evaluate_batch(&net, inputs.view(), &args.engine, context)?;
    let outputs: Vec<Vec<f32>> = result.outputs.outer_iter().map(|r| r.to_vec()).collect();
    if json {
        let report = serde_json::json!({
            "renderer": result.renderer,
            "evaluated_by": match args.engine.cpu {
                Some(CpuChoice::Plain) => "cpu-plain",
                Some(CpuChoice::Optimised) => "cpu-optimised",
                None if args.engine.formulation == Formulation::Packed => "gpu-packed",
                None => "gpu-faithful",
            },
            "tiles": result.tiles,
            "outputs": outputs,
            "timings_ms": timings_json(&result),
        });
        println!("{report}");
    } else {
        println!("# {} ({} tile(s))", result.renderer, result.tiles);
        for row in &outputs {
            let cells: Vec<String> = row.iter().map(|v| format!("{v:.7}")).collect();
            println!("{}", cells.join(" "));
        }
        let t = &result.times;
        println!(
            "# ms: texture creation {:.3}, matrix product {:.3}, bias + sigmoid {:.3}, readback {:.3}",
            t.texture_creation, t.matmul, t.activation, t.readback
        );
    }
    Ok(())
}

fn detect(
    args: DetectArgs,
    json: bool,
    context: impl FnOnce() -> anyhow::Result<Context>,
) -> anyhow::Result<()> {
    let net = match &args.network {
        Some(path) => read_network(path)?,
        None => shipped_detector().context("the shipped detector")?,
    };
    anyhow::ensure!(
        net.inputs() == WINDOW_INPUTS && net.outputs() == 1,
        "the detector network must take {WINDOW_INPUTS} inputs (an 11 x 11 window) and give 1 output; this one takes {} and gives {}",
        net.inputs(),
        net.outputs()
    );
    let image = image::open(&args.image)
        .with_context(|| format!("cannot read the image {}", args.image.display()))?
        .to_luma8();
    let start = Instant::now();
    let (outputs, renderer, times) = match args.engine.cpu {
        Some(cpu) => {
            let kind = CpuProduct::from(cpu);
            let out = classify_cpu(&net, &image, kind, 1 << 18);
            (out, kind.name().to_string(), StepTimes::default())
        }
        None => {
            let ctx = context()?;
            let gpu = GpuMlp::new(&ctx)?;
            let loaded = gpu.load(&net, args.engine.formulation)?;
            let (out, times) = classify_gpu(&loaded, &image, 1 << 18)?;
            (out, ctx.info().renderer_line(), times)
        }
    };
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let mask = mask_image(&outputs, image.width(), image.height(), args.threshold);
    let text_pixels = outputs.iter().filter(|&&v| v > args.threshold).count();
    if let Some(out) = &args.out {
        mask.save(out)
            .with_context(|| format!("cannot write the mask {}", out.display()))?;
    }
    let fraction = text_pixels as f64 / outputs.len() as f64;
    if json {
        let report = serde_json::json!({
            "image": args.image.display().to_string(),
            "width": image.width(),
            "height": image.height(),
            "renderer": renderer,
            "text_pixels": text_pixels,
            "text_fraction": fraction,
            "threshold": args.threshold,
            "out": args.out.as_ref().map(|p| p.display().to_string()),
            "timings_ms": {
                "texture_creation": times.texture_creation,
                "matmul": times.matmul,
                "activation": times.activation,
                "readback": times.readback,
                "wall": wall_ms,
            },
        });
        println!("{report}");
    } else {
        println!(
            "{}: {} x {}, {} text pixels ({:.1}%) on {renderer}, {wall_ms:.1} ms{}",
            args.image.display(),
            image.width(),
            image.height(),
            text_pixels,
            100.0 * fraction,
            args.out
                .as_ref()
                .map(|p| format!(", mask written to {}", p.display()))
                .unwrap_or_default()
        );
    }
    Ok(())
}

fn train_detector(args: TrainArgs, json: bool) -> anyhow::Result<()> {
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
    if json {
        println!("{report}");
    } else {
        println!("{}", serde_json::to_string_pretty(&report)?);
    }
    Ok(())
}
