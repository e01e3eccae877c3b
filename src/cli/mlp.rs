//! `classic-gpgpu mlp run | detect | train` (paper 3); `mlp-bench` goes through
//! [`classic_gpgpu::report::bench_command`].

use anyhow::{bail, Context as _};
use classic_gpgpu::files;
use classic_gpgpu::gl::{period, Context};
use classic_gpgpu::mlp::chain::{Formulation, GpuMlp, GpuNetwork, StepTimes};
use classic_gpgpu::mlp::compute::ComputeMlp;
use classic_gpgpu::mlp::cpu::{forward, CpuProduct};
use classic_gpgpu::mlp::detect::{
    classify_cpu, classify_gpu, mask_image, shipped_detector, Classified, THRESHOLD,
};
use classic_gpgpu::mlp::fp24::Precision;
use classic_gpgpu::mlp::labelled::LabelledImage;
use classic_gpgpu::mlp::matmul::RADEON_9700_INPUTS_PER_PASS;
use classic_gpgpu::mlp::network::{parse_inputs, Network};
use classic_gpgpu::mlp::train::{
    evaluate, labelled_window_sets, train, window_set, TrainConfig, WindowSet, HELD_OUT_EVERY,
};
use classic_gpgpu::mlp::window::WINDOW_INPUTS;
use classic_gpgpu::values::{ranges, Count, Real};
use serde_json::json;
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
    /// Trains a text detector for `mlp detect --network`: on synthetic text (the default, which
    /// reproduces assets/mlp/text_detector.json) or on your own image + mask pairs.
    Train(TrainArgs),
}

/// Where the network is evaluated.
#[derive(clap::Args, Debug)]
struct Engine {
    /// GPU formulation: the paper's one-value-per-texel passes, the packed RGBA passes (both
    /// classic), or a tiled shared-memory compute pass per layer (compute, OpenGL 4.3; `mlp
    /// run` only) [default: faithful].
    #[arg(long, value_enum, conflicts_with = "cpu")]
    formulation: Option<FormulationArg>,
    /// Evaluate on the CPU instead of the GPU. The GPU's options (--formulation,
    /// --max-vectors, --inputs-per-pass) do not apply and are refused with it.
    #[arg(long, value_enum)]
    cpu: Option<CpuChoice>,
    /// At most this many input vectors per texture (default and upper limit: the renderer's
    /// maximum texture size; the paper's board allowed 2048). Larger batches are split into
    /// tiles.
    #[arg(long, conflicts_with = "cpu", value_parser = ranges::TEXTURE_SIDE.of::<usize>())]
    max_vectors: Option<usize>,
    /// Sum at most this many of a layer's inputs per matrix-product pass, splitting each
    /// product into as many passes as that takes, as the paper's GPU required (15 is our
    /// estimate for its ATI RADEON 9700 PRO). Faithful formulation only [default: one pass per
    /// product].
    #[arg(long, conflicts_with = "cpu", value_parser = INPUTS_PER_PASS.of::<usize>())]
    inputs_per_pass: Option<usize>,
    /// After the run, print a per-pass table to stderr: GPU time of each pass (timestamp
    /// queries, read after the run), its wall time, and the time spent waiting for the GPU.
    #[arg(long, conflicts_with = "cpu")]
    profile: bool,
    /// Run as the paper's own board, an ATI RADEON 9700 PRO (R300), would have: its 24-bit
    /// float arithmetic emulated at every step of the passes, its limits enforced by the GL
    /// layer (textures up to 2048, no float blending or filtering, no compute shaders; a step
    /// beyond them is an error naming the limit), and each product split into passes of at
    /// most 15 inputs unless --inputs-per-pass says otherwise. Faithful formulation only.
    #[arg(long, conflicts_with = "cpu")]
    period: bool,
}

/// The library's [`Formulation`], as the command line names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum FormulationArg {
    /// The paper's: one float per texel, one inner product per fragment.
    Faithful,
    /// Four floats per texel, a 4 x 4 block of outputs per fragment (MRT).
    Packed,
    /// Compute shaders: each layer one tiled product in shared memory, bias and sigmoid fused.
    Compute,
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

impl Engine {
    /// The classic formulation (`compute` is handled before any texture is made).
    fn formulation(&self) -> Formulation {
        match self.formulation {
            Some(FormulationArg::Packed) => Formulation::Packed,
            _ => Formulation::Faithful,
        }
    }

    fn compute(&self) -> bool {
        self.formulation == Some(FormulationArg::Compute)
    }

    /// `classic` or `compute`, as the JSON reports say which ran (null on the CPU).
    fn family(&self) -> Option<&'static str> {
        self.cpu
            .is_none()
            .then(|| if self.compute() { "compute" } else { "classic" })
    }

    /// How the outputs were computed, as the JSON reports name it.
    fn evaluated_by(&self) -> &'static str {
        match (self.cpu, self.formulation()) {
            (None, _) if self.compute() => "gpu-compute",
            (Some(CpuChoice::Plain), _) => "cpu-plain",
            (Some(CpuChoice::Optimised), _) => "cpu-optimised",
            (None, Formulation::Packed) => "gpu-packed",
            (None, Formulation::Faithful) => "gpu-faithful",
        }
    }

    /// The network's textures, its products split as `--inputs-per-pass` asks (under
    /// `--period`, by default, into the passes of the paper's board).
    fn load<'g>(&self, gpu: &'g GpuMlp, net: &Network) -> anyhow::Result<GpuNetwork<'g>> {
        let per_pass = self
            .inputs_per_pass
            .or(self.period.then_some(RADEON_9700_INPUTS_PER_PASS));
        Ok(gpu
            .load(net, self.formulation())?
            .split_products(per_pass)?)
    }

    /// The programs, at the R300's precision and under its limits with `--period`.
    fn gpu(&self, ctx: &Context) -> anyhow::Result<GpuMlp> {
        if !self.period {
            return Ok(GpuMlp::new(ctx)?);
        }
        anyhow::ensure!(
            self.formulation() == Formulation::Faithful,
            "--period emulates the ATI RADEON 9700 PRO's 24-bit arithmetic in the paper's \
             faithful passes only; the packed formulation (not the paper's) runs in fp32"
        );
        ctx.set_period(Some(period::for_paper(3)));
        Ok(GpuMlp::with_precision(ctx, Precision::Fp24)?)
    }

    /// ", as an ATI RADEON 9700 PRO (fp24 emulated)" under `--period`, else nothing.
    fn period_text(&self) -> String {
        match self.period {
            true => format!(
                ", as an {} ({} emulated, its limits enforced)",
                period::for_paper(3).name,
                Precision::Fp24.name()
            ),
            false => String::new(),
        }
    }

    /// The period GPU and its arithmetic, as the JSON reports name them (null without it).
    fn period_json(&self) -> serde_json::Value {
        match self.period {
            true => json!({
                "gpu": period::for_paper(3).name,
                "precision": Precision::Fp24.name(),
            }),
            false => serde_json::Value::Null,
        }
    }
}

/// A finite number (`--threshold nan` would mark nothing as text without a word).
/// `--threshold`: any finite output level (a network of `mlp train` ends in a sigmoid, 0 to
/// 1; one of the user's may end in an identity layer).
const THRESHOLD_RANGE: Real =
    Real::new("a threshold", -f64::MAX, f64::MAX, "a finite output level");

/// `--inputs-per-pass`: a layer's inputs summed in one pass.
const INPUTS_PER_PASS: Count = Count::new(
    "a number of inputs",
    1,
    65536,
    "more than any layer this program reads has",
);

/// One training window's memory: its inputs as f32 and its label.
const WINDOW_BYTES: u64 = (WINDOW_INPUTS * 4 + 16) as u64;

/// `--windows-per-class`: a text and a non-text window of each image are kept in memory.
const WINDOWS: Count = Count::in_memory(
    "a number of windows",
    1,
    2 * WINDOW_BYTES,
    "pair of windows",
);

/// `--epochs`: a loss of 8 bytes is kept an epoch, and each is a pass over every window.
const EPOCHS: Count = Count::in_memory("a number of epochs", 1, 8, "epoch's loss")
    .at_most(1_000_000, "each epoch trains on every window once");

/// `--images`: each synthetic image is drawn and sampled on the CPU.
const IMAGES: Count = Count::new(
    "a number of images",
    1,
    1_000_000,
    "each image is drawn and sampled; its windows are checked against memory too",
);

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
    /// The image, PNG (colour is converted to grey).
    image: PathBuf,
    /// Where to write the classified image (black = text). Never the input image; an existing
    /// file only with --force.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Replace --out if it exists (never the input image).
    #[arg(long, requires = "out")]
    force: bool,
    /// The network to classify with, e.g. one `mlp train` wrote (121 inputs, 1 output)
    /// [default: the shipped detector, assets/mlp/text_detector.json, built into the binary].
    #[arg(long)]
    network: Option<PathBuf>,
    /// Output above which a pixel is text.
    #[arg(long, default_value_t = THRESHOLD, value_parser = THRESHOLD_RANGE.of::<f32>())]
    threshold: f32,
    #[command(flatten)]
    engine: Engine,
}

#[derive(clap::Args, Debug)]
struct TrainArgs {
    /// Where to write the trained network (JSON); `mlp detect IMAGE --network FILE` classifies
    /// with it. An existing file is replaced only with --force.
    #[arg(long, default_value = "text_detector.json")]
    out: PathBuf,
    /// Replace --out if it exists (never one of the --pair files).
    #[arg(long)]
    force: bool,
    /// Train on your own labelled image instead of synthetic text: the image (PNG; colour
    /// becomes grey) and its mask, the same size, where dark pixels
    /// (grey below 128) are text and light ones are not, as `mlp detect --out` draws them.
    /// Repeat for more pairs.
    #[arg(long, num_args = 2, value_names = ["IMAGE", "MASK"], action = clap::ArgAction::Append)]
    pair: Vec<PathBuf>,
    /// At most this many text and this many non-text windows from each image [default: 30
    /// per synthetic image, 2000 per --pair image].
    #[arg(long, value_parser = WINDOWS.of::<usize>())]
    windows_per_class: Option<usize>,
    /// Seed of the synthetic data or of the window sampling, the initial weights and the
    /// sample order.
    #[arg(long, default_value_t = TrainConfig::default().seed,
          value_parser = ranges::SEED.of::<u64>())]
    seed: u64,
    /// Training epochs.
    #[arg(long, default_value_t = TrainConfig::default().epochs, value_parser = EPOCHS.of::<usize>())]
    epochs: usize,
    /// Synthetic training images (without --pair; with --windows-per-class, what their
    /// windows take is checked against memory too).
    #[arg(long, default_value_t = TrainConfig::default().images, value_parser = IMAGES.of::<usize>(),
          conflicts_with = "pair")]
    images: usize,
}

/// `--images` with `--windows-per-class`: the windows of every image are held in memory
/// together, checked before anything is made (each count alone is bounded by its parser).
fn check_training_counts(config: &TrainConfig, own: bool) -> anyhow::Result<()> {
    if own {
        return Ok(());
    }
    super::limits::check_memory(
        &format!(
            "--images {} --windows-per-class {}",
            config.images, config.windows_per_class
        ),
        (config.images as u64).saturating_mul(2 * config.windows_per_class as u64),
        WINDOW_BYTES,
        "windows",
        "use fewer --images or --windows-per-class",
    )
}

/// Whether the command makes a GL context: `train` never does, `run` and `detect` unless
/// `--cpu` (`--trace` is refused where there is no GL call to record).
pub fn uses_gl(args: &MlpArgs) -> bool {
    match &args.command {
        MlpCommand::Run(a) => a.engine.cpu.is_none(),
        MlpCommand::Detect(a) => a.engine.cpu.is_none(),
        MlpCommand::Train(_) => false,
    }
}

/// Windows sampled from each --pair image unless --windows-per-class says otherwise.
const PAIR_WINDOWS_PER_CLASS: usize = 2000;

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

fn read_grey(path: &Path, what: &str) -> anyhow::Result<image::GrayImage> {
    // Only PNG is built in (the `image` crate's `png` feature): say so, rather than the
    // crate's "format not supported", when the file is another format.
    let format = image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .ok()
        .and_then(|r| r.format());
    if let Some(format) = format.filter(|f| *f != image::ImageFormat::Png) {
        bail!(
            "the {what} {} is a {} image; this program reads PNG only: convert it to PNG \
             first",
            path.display(),
            format!("{format:?}").to_uppercase()
        );
    }
    Ok(classic_gpgpu::files::read_image(path, what)?.to_luma8())
}

/// Outputs (L x M) of a batch, where it ran, its step times, tiles and passes.
struct Evaluated {
    outputs: ndarray::Array2<f32>,
    renderer: String,
    times: StepTimes,
    /// `None` on the CPU.
    network_upload_ms: Option<f64>,
    tiles: usize,
    product_passes: Vec<usize>,
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
            network_upload_ms: None,
            tiles: 1,
            product_passes: Vec::new(),
        });
    }
    let ctx = context()?;
    super::profile::start(&ctx, engine.profile);
    if engine.period {
        // the R300's limits hold from here on: a compute pass is refused, naming the limit
        ctx.set_period(Some(period::for_paper(3)));
    }
    if engine.compute() {
        anyhow::ensure!(
            engine.max_vectors.is_none() && engine.inputs_per_pass.is_none(),
            "--max-vectors and --inputs-per-pass split the classic passes; the compute \
             formulation takes the whole batch and product in one pass per layer"
        );
        let mlp = ComputeMlp::new(&ctx)?;
        let loaded = mlp.load(net)?;
        let result = loaded.forward(batch)?;
        return Ok(Evaluated {
            outputs: result.outputs,
            renderer: ctx.info().renderer_line(),
            times: result.times,
            network_upload_ms: Some(loaded.upload_ms),
            tiles: 1,
            product_passes: vec![1; net.layers().len()],
        });
    }
    let gpu = engine.gpu(&ctx)?;
    let loaded = engine.load(&gpu, net)?;
    let result = loaded.forward(batch, engine.max_vectors)?;
    super::profile::print(&ctx);
    Ok(Evaluated {
        outputs: result.outputs,
        renderer: ctx.info().renderer_line(),
        times: result.times,
        network_upload_ms: Some(loaded.upload_ms),
        tiles: result.tiles,
        product_passes: result.product_passes,
    })
}

/// The step times; the GPU-only steps are null on the CPU rather than a zero never measured.
fn timings_json(times: &StepTimes, on_gpu: bool) -> serde_json::Value {
    let gpu_only = |ms: f64| on_gpu.then_some(ms);
    json!({
        "texture_creation": gpu_only(times.texture_creation),
        "matmul": times.matmul,
        "activation": times.activation,
        "readback": gpu_only(times.readback),
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
    anyhow::ensure!(
        result.outputs.iter().all(|v| v.is_finite()),
        "{} on {}: an output is not a finite number",
        args.network.display(),
        args.input.display()
    );
    let outputs: Vec<Vec<f32>> = result.outputs.outer_iter().map(|r| r.to_vec()).collect();
    if json {
        let mut timings = timings_json(&result.times, args.engine.cpu.is_none());
        timings["network_upload"] = json!(result.network_upload_ms);
        let report = json!({
            "renderer": result.renderer,
            "evaluated_by": args.engine.evaluated_by(),
            "formulation": args.engine.family(),
            "period": args.engine.period_json(),
            "tiles": result.tiles,
            "product_passes": result.product_passes,
            "outputs": outputs,
            "timings_ms": timings,
        });
        println!("{report}");
    } else {
        println!(
            "# {}{} ({} tile(s))",
            result.renderer,
            args.engine.period_text(),
            result.tiles
        );
        for row in &outputs {
            let cells: Vec<String> = row.iter().map(|v| format!("{v:.7}")).collect();
            println!("{}", cells.join(" "));
        }
        let t = &result.times;
        match args.engine.cpu {
            Some(_) => println!(
                "# ms: matrix product {:.3}, bias + sigmoid {:.3}",
                t.matmul, t.activation
            ),
            None => println!(
                "# ms: texture creation {:.3}, matrix product {:.3} ({} pass(es) per layer), \
                 bias + sigmoid {:.3}, readback {:.3}",
                t.texture_creation,
                t.matmul,
                passes_text(&result.product_passes),
                t.activation,
                t.readback
            ),
        }
    }
    Ok(())
}

/// "9 + 2": the product passes of each layer.
fn passes_text(per_layer: &[usize]) -> String {
    let counts: Vec<String> = per_layer.iter().map(usize::to_string).collect();
    counts.join(" + ")
}

fn detect(
    args: DetectArgs,
    json: bool,
    context: impl FnOnce() -> anyhow::Result<Context>,
) -> anyhow::Result<()> {
    if let Some(out) = &args.out {
        let mut inputs = vec![args.image.as_path()];
        inputs.extend(args.network.as_deref());
        files::check_output("--out", out, &inputs, args.force, &["png"])?;
    }
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
    anyhow::ensure!(
        !args.engine.compute(),
        "mlp detect runs the classic formulations (faithful, packed) or the CPU; --formulation \
         compute is for mlp run"
    );
    let image = read_grey(&args.image, "image")?;
    let start = Instant::now();
    let (classified, renderer, product_passes) = match args.engine.cpu {
        Some(cpu) => {
            let kind = CpuProduct::from(cpu);
            let classified = classify_cpu(&net, &image, kind, 1 << 18);
            (classified, kind.name().to_string(), Vec::new())
        }
        None => {
            let ctx = context()?;
            super::profile::start(&ctx, args.engine.profile);
            let gpu = args.engine.gpu(&ctx)?;
            let loaded = args.engine.load(&gpu, &net)?;
            let classified = classify_gpu(&loaded, &image, 1 << 18, args.engine.max_vectors)?;
            super::profile::print(&ctx);
            (
                classified,
                ctx.info().renderer_line(),
                loaded.product_passes(),
            )
        }
    };
    let wall_ms = start.elapsed().as_secs_f64() * 1e3;
    let Classified {
        outputs,
        times,
        batches,
    } = classified;
    anyhow::ensure!(
        outputs.iter().all(|v| v.is_finite()),
        "{}: a pixel's network output is not a finite number",
        args.image.display()
    );
    let mask = mask_image(&outputs, image.width(), image.height(), args.threshold);
    let text_pixels = outputs.iter().filter(|&&v| v > args.threshold).count();
    if let Some(out) = &args.out {
        files::write_image(out, &mask.into())
            .with_context(|| format!("cannot write the mask {}", out.display()))?;
    }
    let fraction = text_pixels as f64 / outputs.len() as f64;
    if json {
        let mut timings = timings_json(&times, args.engine.cpu.is_none());
        timings["wall"] = json!(wall_ms);
        let report = json!({
            "image": args.image.display().to_string(),
            "width": image.width(),
            "height": image.height(),
            "network": args.network.as_ref().map(|p| p.display().to_string()),
            "renderer": renderer,
            "evaluated_by": args.engine.evaluated_by(),
            "period": args.engine.period_json(),
            "batches": batches,
            "product_passes": product_passes,
            "text_pixels": text_pixels,
            "text_fraction": fraction,
            "threshold": args.threshold,
            "out": args.out.as_ref().map(|p| p.display().to_string()),
            "timings_ms": timings,
        });
        println!("{report}");
    } else {
        println!(
            "{}: {} x {}, {} text pixels ({:.1}%) on {renderer}{}, {wall_ms:.1} ms{}",
            args.image.display(),
            image.width(),
            image.height(),
            text_pixels,
            100.0 * fraction,
            args.engine.period_text(),
            args.out
                .as_ref()
                .map(|p| format!(", mask written to {}", p.display()))
                .unwrap_or_default()
        );
    }
    Ok(())
}

/// The training and held-out windows, and what they came from (for the report).
struct TrainingData {
    train: WindowSet,
    held_out: WindowSet,
    source: serde_json::Value,
}

/// Synthetic text (the shipped detector's data), held out: images of the next seed.
fn synthetic_data(config: &TrainConfig) -> TrainingData {
    let held_out_images = (config.images / 4).max(1);
    TrainingData {
        train: window_set(config.seed, config.images, config.windows_per_class),
        held_out: window_set(
            config.seed.wrapping_add(1),
            held_out_images,
            config.windows_per_class,
        ),
        source: json!({
            "synthetic_images": config.images,
            "held_out": format!(
                "{held_out_images} other synthetic images (seed {})",
                config.seed.wrapping_add(1)
            ),
        }),
    }
}

/// The user's image + mask pairs, held out: one window in [`HELD_OUT_EVERY`].
fn pair_data(pairs: &[PathBuf], config: &TrainConfig) -> anyhow::Result<TrainingData> {
    let mut pages = Vec::new();
    let mut described = Vec::new();
    for pair in pairs.chunks(2) {
        let [image_path, mask_path] = pair else {
            bail!("--pair takes two files, an image and its mask");
        };
        let image = read_grey(image_path, "training image")?;
        let mask = read_grey(mask_path, "mask")?;
        let page = LabelledImage::from_mask(image, &mask)
            .with_context(|| format!("--pair {} {}", image_path.display(), mask_path.display()))?;
        described.push(json!({
            "image": image_path.display().to_string(),
            "mask": mask_path.display().to_string(),
            "pixels": page.text.len(),
            "text_pixels": page.text_pixels(),
        }));
        pages.push(page);
    }
    let (train, held_out) = labelled_window_sets(&pages, config.windows_per_class, config.seed)
        .context("--pair masks")?;
    Ok(TrainingData {
        train,
        held_out,
        source: json!({
            "pairs": described,
            "held_out": format!("1 in {HELD_OUT_EVERY} of the windows sampled from the same images"),
        }),
    })
}

fn train_detector(args: TrainArgs, json: bool) -> anyhow::Result<()> {
    let inputs: Vec<&Path> = args.pair.iter().map(PathBuf::as_path).collect();
    files::check_output("--out", &args.out, &inputs, args.force, &[])?;
    let own = !args.pair.is_empty();
    let defaults = TrainConfig::default();
    let config = TrainConfig {
        seed: args.seed,
        epochs: args.epochs,
        images: if own {
            args.pair.len() / 2
        } else {
            args.images
        },
        windows_per_class: args.windows_per_class.unwrap_or(if own {
            PAIR_WINDOWS_PER_CLASS
        } else {
            defaults.windows_per_class
        }),
        ..defaults
    };
    check_training_counts(&config, own)?;
    let data = if own {
        pair_data(&args.pair, &config)?
    } else {
        synthetic_data(&config)
    };
    let trained = train(&config, &data.train);
    let outputs = forward(
        CpuProduct::Optimised,
        &trained.network,
        data.held_out.inputs.view(),
    )
    .outputs;
    let quality = evaluate(outputs.column(0), &data.held_out.labels, THRESHOLD);
    files::write_bytes(&args.out, (trained.network.to_json() + "\n").as_bytes())
        .with_context(|| format!("cannot write {}", args.out.display()))?;
    let report = json!({
        "config": config,
        "data": data.source,
        "training_windows": data.train.labels.len(),
        "loss_per_epoch": trained.loss_per_epoch,
        "held_out": quality,
        "out": args.out.display().to_string(),
    });
    if json {
        println!("{report}");
    } else {
        let loss = &trained.loss_per_epoch;
        println!(
            "trained on {} windows for {} epochs (loss {:.4} -> {:.4}); held out ({}): \
             accuracy {:.1}%, precision {:.1}%, recall {:.1}%",
            data.train.labels.len(),
            config.epochs,
            loss.first().copied().unwrap_or_default(),
            loss.last().copied().unwrap_or_default(),
            data.source["held_out"].as_str().unwrap_or(""),
            100.0 * quality.accuracy,
            100.0 * quality.precision,
            100.0 * quality.recall
        );
        println!(
            "network written to {0}; classify with it: classic-gpgpu mlp detect IMAGE --network {0}",
            args.out.display()
        );
    }
    Ok(())
}
