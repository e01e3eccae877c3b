//! The measurements: the detector network and a wide layer, each evaluated four ways side by
//! side (Table 1 and the throughput table), and text.png classified on the GPU and the CPU
//! (Fig. 2). Fig. 2's images are written here, with the outputs at hand.

use super::fig2_files::{FIG2A_FILE, FIG2B_FILE};
use crate::gl::Context;
use crate::mlp::cpu::{forward, CpuProduct};
use crate::mlp::detect::{classify_cpu, classify_gpu, mask_image, shipped_detector, THRESHOLD};
use crate::mlp::matmul::RADEON_9700_INPUTS_PER_PASS;
use crate::mlp::tiling::max_vectors_per_texture;
use crate::mlp::window::window_batch;
use crate::mlp::{Activation, Formulation, GpuMlp, Layer, Network, StepTimes};
use crate::report::BenchOptions;
use crate::timing::{Load, Runs, Spread};
use anyhow::Context as _;
use image::GrayImage;
use ndarray::{s, Array1, Array2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// The evaluation photograph (assets/mlp/README.md).
const TEXT_PNG: &[u8] = include_bytes!("../../../assets/mlp/text.png");

/// Everything the section measures.
#[derive(Clone, Debug, Serialize)]
pub struct Paper3Results {
    pub renderer: String,
    pub quick: bool,
    /// The machine's load at the end, to read software-renderer timings against.
    pub load: Option<Load>,
    /// Every case and method; the first case's rows are Table 1's.
    pub measurements: Vec<Measurement>,
    pub detection: Detection,
    /// Classic vs compute vs CPU: the 2007 formulation beside today's compute shaders.
    pub then_and_now: crate::report::then_and_now::ThenAndNow,
    /// Where the time of this run went, pass by pass.
    pub profile: Option<crate::gl::profile::ProfileTable>,
    /// The detector at the paper's board's precision and under its limits, beside fp32.
    /// The period block (absent with `--no-period`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub period: Option<super::period::PeriodResults>,
}

impl Paper3Results {
    /// The rows of the first case, the paper's shape (Table 1).
    pub fn paper_case(&self) -> Vec<&Measurement> {
        let first = &self.measurements[0].case;
        self.measurements
            .iter()
            .filter(|m| &m.case == first)
            .collect()
    }

    /// The first case's row of `method`.
    pub fn paper_row(&self, method: Method) -> &Measurement {
        self.paper_case()
            .into_iter()
            .find(|m| m.method == method)
            .expect("every method is measured on every case")
    }
}

/// The ways of evaluating a network, measured side by side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Method {
    /// The paper's passes, each product in one pass.
    GpuFaithful,
    /// The paper's passes, each product split into passes of at most
    /// [`RADEON_9700_INPUTS_PER_PASS`] inputs, as the paper's board required.
    GpuMultiPass,
    GpuPacked,
    CpuPlain,
    CpuOptimised,
}

impl Method {
    pub const ALL: [Method; 5] = [
        Method::GpuFaithful,
        Method::GpuMultiPass,
        Method::GpuPacked,
        Method::CpuPlain,
        Method::CpuOptimised,
    ];

    pub fn label(self) -> String {
        match self {
            Method::GpuFaithful => "GPU faithful (1 float/texel)".into(),
            Method::GpuMultiPass => format!(
                "GPU faithful, {RADEON_9700_INPUTS_PER_PASS} inputs/pass (RADEON 9700 estimate)"
            ),
            Method::GpuPacked => "GPU packed (RGBA, 4x4/fragment)".into(),
            Method::CpuPlain => "CPU plain loop".into(),
            Method::CpuOptimised => "CPU matrixmultiply sgemm".into(),
        }
    }

    /// The GPU formulation and per-pass input limit, or `None` for the CPU.
    fn gpu(self) -> Option<(Formulation, Option<usize>)> {
        match self {
            Method::GpuFaithful => Some((Formulation::Faithful, None)),
            Method::GpuMultiPass => {
                Some((Formulation::Faithful, Some(RADEON_9700_INPUTS_PER_PASS)))
            }
            Method::GpuPacked => Some((Formulation::Packed, None)),
            Method::CpuPlain | Method::CpuOptimised => None,
        }
    }
}

/// Median step times of one method on one case, and how far its outputs are from CPU plain.
#[derive(Clone, Debug, Serialize)]
pub struct Measurement {
    pub case: String,
    pub method: Method,
    /// [N, M] of every layer.
    pub layers: Vec<[usize; 2]>,
    pub vectors: usize,
    pub tiles: usize,
    /// Rendering passes of each layer's matrix product per tile (empty on the CPU).
    pub product_passes: Vec<usize>,
    /// The median of every step over the timed runs.
    pub times_ms: StepTimes,
    pub total_ms: f64,
    /// The timed runs (after one warm-up run) and the spread of their product times.
    pub runs: usize,
    pub matmul_spread_ms: Spread,
    /// The spread of the whole evaluation (every step) over the timed runs.
    pub total_spread_ms: Spread,
    /// From the median product time.
    pub matmul_gflops: f64,
    /// From the fastest product time: the renderer's capability when the machine is shared.
    pub best_matmul_gflops: f64,
    pub max_abs_diff_vs_cpu_plain: f32,
}

/// Fig. 2: text.png classified by both GPU formulations and the CPU.
#[derive(Clone, Debug, Serialize)]
pub struct Detection {
    pub width: u32,
    pub height: u32,
    /// Pixels the CPU (sgemm) calls text.
    pub cpu_text_pixels: usize,
    pub faithful: DetectionRun,
    pub packed: DetectionRun,
}

impl Detection {
    pub fn pixels(&self) -> usize {
        (self.width * self.height) as usize
    }
}

/// One GPU formulation's classification of text.png.
#[derive(Clone, Debug, Serialize)]
pub struct DetectionRun {
    pub text_pixels: usize,
    /// Share of pixels given the same class as the CPU.
    pub agreement_with_cpu: f64,
    /// The median over `runs` runs (at the papers' sizes, the runs of the "all of text.png"
    /// case, which is this very classification).
    pub times_ms: StepTimes,
    pub runs: usize,
}

/// One network and batch to measure.
struct Case {
    name: String,
    network: Network,
    batch: Array2<f32>,
    /// Input vectors per texture (the paper's 2048 for its own row, else the renderer's max).
    max_vectors: Option<usize>,
    /// Whether the batch is every pixel of text.png, row by row: Fig. 2's classification.
    whole_photo: bool,
}

// region: workload runs
/// Timed runs per measurement under `--quick` (see [`BenchOptions::runs`]).
const QUICK_RUNS: usize = 1;
// endregion

pub fn measure(opts: &BenchOptions) -> anyhow::Result<Paper3Results> {
    crate::timing::mark("paper3: start");
    let ctx = opts.gl;
    let gpu = GpuMlp::new(ctx)?;
    let photo = image::load_from_memory(TEXT_PNG)
        .context("decoding assets/mlp/text.png")?
        .to_luma8();
    let cases = cases(ctx, &photo, opts.quick)?;
    let runs = opts.runs(QUICK_RUNS);
    let bar = opts.progress.add(indicatif::ProgressBar::new(
        (cases.len() * Method::ALL.len()) as u64,
    ));
    bar.set_style(
        indicatif::ProgressStyle::with_template("paper 3 {bar:30} {pos}/{len} {msg}")
            .expect("template"),
    );
    let mut measurements = Vec::new();
    let mut detection = None;
    for case in &cases {
        let mut measured = Vec::new();
        for method in Method::ALL {
            bar.set_message(format!("{} / {}", case.name, method.label()));
            let label = method.label();
            let _scope = match method.gpu() {
                Some(_) => crate::gl::profile::scope(ctx, &label),
                None => crate::gl::profile::cpu_scope(ctx, &label),
            };
            measured.push(measure_case(&gpu, case, method, runs)?);
            crate::timing::mark(&format!("paper3: {} / {label}", case.name));
            bar.inc(1);
        }
        // every method against the plain CPU loop's outputs, measured above (not run again)
        let reference = measured
            .iter()
            .find(|(m, _)| m.method == Method::CpuPlain)
            .map(|(_, outputs)| outputs.clone())
            .expect("the plain CPU loop is one of the methods");
        if case.whole_photo {
            // Fig. 2 is this case: every pixel of text.png through the detector, one batch
            let _scope = crate::gl::profile::cpu_scope(ctx, "Fig. 2: text.png classified");
            detection = Some(detection_of(opts, &photo, &measured)?);
        }
        for (mut measurement, outputs) in measured {
            measurement.max_abs_diff_vs_cpu_plain = outputs
                .iter()
                .zip(reference.iter())
                .map(|(a, b)| (a - b).abs())
                .fold(0.0f32, f32::max);
            measurements.push(measurement);
        }
    }
    bar.finish_and_clear();
    crate::timing::mark("paper3: detection");
    let period = if crate::report::period::requested() {
        let _scope = crate::gl::profile::scope(ctx, "period: text.png at fp24 (R300)");
        Some(super::period::measure(opts, &photo)?)
    } else {
        None
    };
    let detection = match detection {
        Some(detection) => detection,
        None => {
            // --quick has no case of the whole photograph: classify it on its own
            let _scope = crate::gl::profile::scope(ctx, "Fig. 2: text.png classified");
            detect_photo(opts, &gpu, &photo)?
        }
    };
    Ok(Paper3Results {
        renderer: ctx.info().renderer_line(),
        quick: opts.quick,
        load: Load::now(),
        measurements,
        detection,
        then_and_now: super::then_and_now::measure(opts)?,
        profile: None,
        period,
    })
}

// region: workload cases
/// The cases: the paper's shape (one 2048-vector texture), one texture at this renderer's
/// maximum, the whole photograph (tiled), and a wide synthetic network.
fn cases(ctx: &Context, photo: &GrayImage, quick: bool) -> anyhow::Result<Vec<Case>> {
    let detector = shipped_detector()?;
    let all = window_batch(photo, 0..photo.height());
    let max = max_vectors_per_texture(ctx, Formulation::Faithful);
    let first = |l: usize| all.slice(s![..l.min(all.nrows()), ..]).to_owned();
    let paper_l = if quick { 512 } else { 2048 };
    let mut cases = vec![Case {
        name: format!("121-30-1, L = {paper_l} (paper: <= 2048 per texture)"),
        network: detector.clone(),
        batch: first(paper_l),
        max_vectors: Some(2048),
        whole_photo: false,
    }];
    if quick {
        cases.push(wide_case(128, 2048));
        return Ok(cases);
    }
    let one_texture = max.min(all.nrows());
    cases.push(Case {
        name: format!("121-30-1, L = {one_texture} (one texture)"),
        network: detector.clone(),
        batch: first(one_texture),
        max_vectors: None,
        whole_photo: false,
    });
    cases.push(Case {
        name: format!("121-30-1, L = {} (all of text.png)", all.nrows()),
        network: detector,
        batch: all,
        max_vectors: None,
        whole_photo: true,
    });
    // 2048 vectors: a 512 x 512 x 2048 product, half a giga multiply-add per run, is long
    // enough that the passes' fixed costs do not show in its GFLOPS (this layer is ours, not
    // the paper's: its batch was 4096, twice the time).
    cases.push(wide_case(512, 2048));
    Ok(cases)
}
// endregion

/// A `width`-`width` sigmoid layer on `l` random vectors (seeded).
fn wide_case(width: usize, l: usize) -> Case {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let r = 1.0 / (width as f32).sqrt();
    let network = Network::new(vec![Layer {
        weights: Array2::from_shape_simple_fn((width, width), || rng.gen_range(-r..r)),
        bias: Array1::from_shape_simple_fn(width, || rng.gen_range(-0.5..0.5)),
        activation: Activation::Sigmoid,
    }])
    .expect("valid");
    let batch = Array2::from_shape_simple_fn((l, width), || rng.gen_range(0.0..1.0));
    Case {
        name: format!("{width}-{width}, L = {l} (wide layer)"),
        network,
        batch,
        max_vectors: None,
        whole_photo: false,
    }
}

/// One run of `method` on `case`.
struct Run {
    times: StepTimes,
    tiles: usize,
    product_passes: Vec<usize>,
    outputs: Array2<f32>,
}

fn run_once(gpu: &GpuMlp, case: &Case, method: Method) -> anyhow::Result<Run> {
    if let Some((formulation, inputs_per_pass)) = method.gpu() {
        let loaded = gpu
            .load(&case.network, formulation)?
            .split_products(inputs_per_pass)?;
        let out = loaded.forward(case.batch.view(), case.max_vectors)?;
        return Ok(Run {
            times: out.times,
            tiles: out.tiles,
            product_passes: out.product_passes,
            outputs: out.outputs,
        });
    }
    let kind = if method == Method::CpuPlain {
        CpuProduct::Plain
    } else {
        CpuProduct::Optimised
    };
    let out = forward(kind, &case.network, case.batch.view());
    let times = StepTimes {
        matmul: out.product.as_secs_f64() * 1e3,
        activation: out.activation.as_secs_f64() * 1e3,
        ..StepTimes::default()
    };
    Ok(Run {
        times,
        tiles: 1,
        product_passes: Vec::new(),
        outputs: out.outputs,
    })
}

/// Input vectors of the warm-up run (see [`warm_up`]).
const WARM_UP_VECTORS: usize = 256;

/// One untimed run before the counted ones, on the first [`WARM_UP_VECTORS`] input vectors of
/// the batch. On the GPU the first draw of a program compiles its shader variant (llvmpipe
/// JIT, on the calling thread, outside the timer queries) and llvmpipe's first timer query
/// of a context reads garbage; both need the same programs and passes, not the same amount
/// of work. On the CPU nothing carries over from one run to the next but the code and the
/// allocator (every run allocates its outputs afresh), so a short run warms it as well.
fn warm_up(gpu: &GpuMlp, case: &Case, method: Method) -> anyhow::Result<()> {
    let l = case.batch.nrows().min(WARM_UP_VECTORS);
    let head = Case {
        name: case.name.clone(),
        network: case.network.clone(),
        batch: case.batch.slice(s![..l, ..]).to_owned(),
        max_vectors: case.max_vectors,
        whole_photo: false,
    };
    run_once(gpu, &head, method)?;
    Ok(())
}

fn measure_case(
    gpu: &GpuMlp,
    case: &Case,
    method: Method,
    rules: Runs,
) -> anyhow::Result<(Measurement, Array2<f32>)> {
    warm_up(gpu, case, method)?;
    let mut runs = rules.run(|_| run_once(gpu, case, method))?;
    let products: Vec<f64> = runs.iter().map(|r| r.times.matmul).collect();
    let median = |f: fn(&StepTimes) -> f64| {
        let mut v: Vec<f64> = runs.iter().map(|r| f(&r.times)).collect();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let times = StepTimes {
        texture_creation: median(|t| t.texture_creation),
        matmul: median(|t| t.matmul),
        activation: median(|t| t.activation),
        readback: median(|t| t.readback),
    };
    let flops = case.network.flops_per_input() * case.batch.nrows() as f64;
    let fastest = runs
        .iter()
        .map(|r| r.times.matmul)
        .fold(f64::INFINITY, f64::min);
    let outputs = std::mem::take(&mut runs[0].outputs);
    anyhow::ensure!(
        outputs.iter().all(|v| v.is_finite()),
        "{}: {} gave a non-finite output",
        case.name,
        method.label()
    );
    let measurement = Measurement {
        case: case.name.clone(),
        method,
        layers: case
            .network
            .layers()
            .iter()
            .map(|l| [l.inputs(), l.outputs()])
            .collect(),
        vectors: case.batch.nrows(),
        tiles: runs[0].tiles,
        product_passes: runs[0].product_passes.clone(),
        total_ms: times.total(),
        runs: runs.len(),
        matmul_spread_ms: Spread::of(&products),
        total_spread_ms: Spread::of(&runs.iter().map(|r| r.times.total()).collect::<Vec<_>>()),
        matmul_gflops: flops / (times.matmul * 1e-3) / 1e9,
        best_matmul_gflops: flops / (fastest * 1e-3) / 1e9,
        times_ms: times,
        // set by the caller, once the plain CPU loop has been measured
        max_abs_diff_vs_cpu_plain: 0.0,
    };
    Ok((measurement, outputs))
}

/// Fig. 2 from the measurements of the case that is text.png's every pixel in one batch (the
/// batch [`classify_gpu`] and [`classify_cpu`] make of it, with one band and the renderer's
/// tiles): the CPU's classes are sgemm's, the GPU runs' times their medians; the faithful
/// GPU's mask is written as Fig. 2(b).
fn detection_of(
    opts: &BenchOptions,
    photo: &GrayImage,
    measured: &[(Measurement, Array2<f32>)],
) -> anyhow::Result<Detection> {
    let (width, height) = photo.dimensions();
    let outputs_of = |method: Method| {
        measured
            .iter()
            .find(|(m, _)| m.method == method)
            .expect("every method is measured on every case")
    };
    let cpu = outputs_of(Method::CpuOptimised).1.column(0).to_vec();
    anyhow::ensure!(
        cpu.len() == (width * height) as usize,
        "Fig. 2: {} outputs for {width} x {height} pixels",
        cpu.len()
    );
    crate::files::write_image(&opts.out_dir.join(FIG2A_FILE), &photo.clone().into())
        .with_context(|| format!("writing {FIG2A_FILE}"))?;
    recorded_image(opts, FIG2A_FILE, "the input photograph (text.png)");
    let run_of = |method: Method| -> anyhow::Result<DetectionRun> {
        let (measurement, outputs) = outputs_of(method);
        let out = outputs.column(0).to_vec();
        if method == Method::GpuFaithful {
            let mask = mask_image(&out, width, height, THRESHOLD);
            crate::files::write_image(&opts.out_dir.join(FIG2B_FILE), &mask.into())
                .with_context(|| format!("writing {FIG2B_FILE}"))?;
            recorded_image(
                opts,
                FIG2B_FILE,
                "the network's mask: white where it finds text",
            );
        }
        Ok(detection_run(
            &out,
            &cpu,
            measurement.times_ms,
            measurement.runs,
        ))
    };
    Ok(Detection {
        width,
        height,
        cpu_text_pixels: cpu.iter().filter(|&&v| v > THRESHOLD).count(),
        faithful: run_of(Method::GpuFaithful)?,
        packed: run_of(Method::GpuPacked)?,
    })
}

/// A GPU classification's text pixels and agreement with the CPU's classes.
fn detection_run(out: &[f32], cpu: &[f32], times_ms: StepTimes, runs: usize) -> DetectionRun {
    let same = out
        .iter()
        .zip(cpu)
        .filter(|(g, c)| (**g > THRESHOLD) == (**c > THRESHOLD))
        .count();
    DetectionRun {
        text_pixels: out.iter().filter(|&&v| v > THRESHOLD).count(),
        agreement_with_cpu: same as f64 / cpu.len() as f64,
        times_ms,
        runs,
    }
}

/// Fig. 2 regenerated on its own (under `--quick`): text.png classified on the GPU (both formulations) and the CPU; the
/// test image and the faithful GPU's mask are written as Fig. 2(a) and 2(b).
fn detect_photo(opts: &BenchOptions, gpu: &GpuMlp, photo: &GrayImage) -> anyhow::Result<Detection> {
    let net = shipped_detector()?;
    let (width, height) = photo.dimensions();
    let cpu = classify_cpu(&net, photo, CpuProduct::Optimised, 1 << 18).outputs;
    crate::files::write_image(&opts.out_dir.join(FIG2A_FILE), &photo.clone().into())
        .with_context(|| format!("writing {FIG2A_FILE}"))?;
    recorded_image(opts, FIG2A_FILE, "the input photograph (text.png)");
    let classify = |formulation: Formulation| -> anyhow::Result<DetectionRun> {
        let loaded = gpu.load(&net, formulation)?;
        let classified = classify_gpu(&loaded, photo, 1 << 18, None)?;
        let out = classified.outputs;
        anyhow::ensure!(
            out.iter().all(|v| v.is_finite()),
            "text.png: the {formulation:?} GPU passes gave a non-finite output"
        );
        if formulation == Formulation::Faithful {
            let mask = mask_image(&out, width, height, THRESHOLD);
            crate::files::write_image(&opts.out_dir.join(FIG2B_FILE), &mask.into())
                .with_context(|| format!("writing {FIG2B_FILE}"))?;
            recorded_image(
                opts,
                FIG2B_FILE,
                "the network's mask: white where it finds text",
            );
        }
        Ok(detection_run(&out, &cpu, classified.times, 1))
    };
    let faithful = classify(Formulation::Faithful)?;
    let packed = classify(Formulation::Packed)?;
    Ok(Detection {
        width,
        height,
        cpu_text_pixels: cpu.iter().filter(|&&v| v > THRESHOLD).count(),
        faithful,
        packed,
    })
}

/// Note what the image `file` in the report shows ([`crate::gl::drawn`]).
fn recorded_image(opts: &BenchOptions, file: &str, what: &str) {
    let shown = crate::gl::drawn::Drawn::Image { what: what.into() };
    crate::gl::drawn::record(&opts.out_dir.join(file), shown);
}
