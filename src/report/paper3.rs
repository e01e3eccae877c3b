//! Paper 3, Oh & Jung 2004: Table 1 (texture creation, matrix product, sigmoid; GPU vs CPU)
//! regenerated beside the published numbers, GFLOP/s of both GPU formulations against both CPU
//! baselines measured side by side in one run, and Fig. 2 (the classified text image).

use super::plot::{Plot, Series};
use super::{BenchOptions, Claim, Fidelity, Figure, Section, Table};
use crate::gl::Context;
use crate::mlp::cpu::{forward, CpuProduct};
use crate::mlp::detect::{classify_cpu, classify_gpu, mask_image, shipped_detector, THRESHOLD};
use crate::mlp::tiling::max_vectors_per_texture;
use crate::mlp::window::window_batch;
use crate::mlp::{Activation, Formulation, GpuMlp, Layer, Network, StepTimes};
use anyhow::Context as _;
use image::GrayImage;
use ndarray::{s, Array1, Array2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// The evaluation photograph (assets/mlp/README.md).
const TEXT_PNG: &[u8] = include_bytes!("../../assets/mlp/text.png");

/// The four ways of evaluating a network, measured side by side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
enum Method {
    GpuFaithful,
    GpuPacked,
    CpuPlain,
    CpuOptimised,
}

impl Method {
    const ALL: [Method; 4] = [
        Method::GpuFaithful,
        Method::GpuPacked,
        Method::CpuPlain,
        Method::CpuOptimised,
    ];

    fn label(self) -> &'static str {
        match self {
            Method::GpuFaithful => "GPU faithful (1 float/texel)",
            Method::GpuPacked => "GPU packed (RGBA, 4x4/fragment)",
            Method::CpuPlain => "CPU plain loop",
            Method::CpuOptimised => "CPU matrixmultiply sgemm",
        }
    }
}

/// One network and batch to measure.
struct Case {
    name: String,
    network: Network,
    batch: Array2<f32>,
    /// Input vectors per texture (the paper's 2048 for its own row, else the renderer's max).
    max_vectors: Option<usize>,
}

/// Median step times of one method on one case, and how far its outputs are from CPU plain.
#[derive(Clone, Debug, Serialize)]
struct Measurement {
    case: String,
    method: Method,
    layers: Vec<[usize; 2]>,
    vectors: usize,
    tiles: usize,
    times_ms: StepTimes,
    total_ms: f64,
    /// From the median product time.
    matmul_gflops: f64,
    /// From the fastest product time: the renderer's capability when the machine is shared.
    best_matmul_gflops: f64,
    max_abs_diff_vs_cpu_plain: f32,
}

/// Runs the benchmark (see the module doc).
pub fn run(opts: &BenchOptions) -> anyhow::Result<Section> {
    let ctx = opts.gl;
    let gpu = GpuMlp::new(ctx)?;
    let photo = image::load_from_memory(TEXT_PNG)
        .context("decoding assets/mlp/text.png")?
        .to_luma8();
    let cases = cases(ctx, &photo, opts.quick)?;
    let repeats = if opts.quick { 1 } else { 5 };
    let bar = opts.progress.add(indicatif::ProgressBar::new(
        (cases.len() * Method::ALL.len()) as u64,
    ));
    bar.set_style(
        indicatif::ProgressStyle::with_template("paper 3 {bar:30} {pos}/{len} {msg}")
            .expect("template"),
    );
    let mut measurements = Vec::new();
    for case in &cases {
        let reference = forward(CpuProduct::Plain, &case.network, case.batch.view()).outputs;
        for method in Method::ALL {
            bar.set_message(format!("{} / {}", case.name, method.label()));
            measurements.push(measure(&gpu, case, method, repeats, &reference)?);
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    let detection = detect_photo(opts, &gpu, &photo)?;
    let mut figures = detection.figures.clone();
    figures.push(gflops_plot(opts, &measurements)?);
    let renderer = ctx.info().renderer_line();
    let load = load_average();
    let table1 = &crate::report::published::Published::get()?.paper3.table1;
    let number = |key: &str| match key {
        "gpu_texture_creation" => table1.gpu_texture_creation,
        "gpu_matrix_multiplication" => table1.gpu_matrix_multiplication,
        "gpu_sigmoid" => table1.gpu_sigmoid,
        "cpu_matrix_multiplication" => table1.cpu_matrix_multiplication,
        _ => unreachable!("paper 3's Table 1 has no {key}"),
    };
    let paper_row = &measurements[..Method::ALL.len()];
    let get = |m: Method| paper_row.iter().find(|r| r.method == m).expect("measured");
    let speedup = get(Method::CpuPlain).total_ms / get(Method::GpuFaithful).total_ms;
    let software = renderer.contains("llvmpipe") || renderer.contains("softpipe");
    let packed = |f: fn(&Measurement) -> f64| {
        measurements
            .iter()
            .filter(|m| m.method == Method::GpuPacked)
            .map(f)
            .fold(0.0, f64::max)
    };
    let (packed_median, packed_best) = (
        packed(|m| m.matmul_gflops),
        packed(|m| m.best_matmul_gflops),
    );
    Ok(Section {
        id: "paper3".into(),
        title: "Paper 3: Oh & Jung 2004, GPU implementation of neural networks".into(),
        summary: format!(
            "The text detector's MLP (11 x 11 window = 121 inputs, 30 hidden sigmoid nodes, 1 \
             output; weights trained here on synthetic text, assets/mlp/text_detector.json) and a \
             wider synthetic network, each evaluated four ways in one run on {renderer}: the \
             paper's render passes (one float per texel, one inner product per fragment), a \
             packed variant (RGBA texels, 4 x 4 outputs per fragment), the plain CPU loop the \
             paper compared with, and matrixmultiply's sgemm. GPU passes are timed with GL timer \
             queries, texture creation and CPU work with the wall clock; each figure is the \
             median of {repeats} run(s) after a warm-up run; {} cores, load average {} at \
             the end (a software renderer shares the CPU with whatever else runs).{} The \
             batches are windows of scikit-image's text.png.",
            std::thread::available_parallelism().map_or(0, usize::from),
            load.map_or("unknown".to_string(), |l| format!("{l:.1}")),
            if opts.quick {
                " QUICK MODE: reduced sizes."
            } else {
                ""
            }
        ),
        tables: vec![
            table1_beside_paper(paper_row, &number),
            gflops_table(&measurements),
            detection.table.clone(),
        ],
        claims: vec![
            Claim {
                claim: "The GPU is about 20 times faster than CPU-only processing".into(),
                paper: format!(
                    "CPU {} vs GPU {} + {} + {} (ATI RADEON 9700 PRO)",
                    number("cpu_matrix_multiplication"),
                    number("gpu_texture_creation"),
                    number("gpu_matrix_multiplication"),
                    number("gpu_sigmoid")
                ),
                measured: format!(
                    "CPU plain loop / GPU faithful (all steps) = {speedup:.2}x on {renderer}"
                ),
                holds: if software { None } else { Some(speedup >= 20.0) },
            },
            Claim {
                claim: "Classification on the GPU gives almost the same result as without it".into(),
                paper: "Fig. 2(b), qualitative".into(),
                measured: format!(
                    "{:.4}% of text.png's pixels classified identically (faithful GPU vs CPU)",
                    100.0 * detection.agreement
                ),
                holds: Some(detection.agreement >= 0.999),
            },
            Claim {
                claim: "The packed product reaches 10 GFLOP/s on the project's 2-core machine (issue 7 target)".into(),
                paper: "not in the paper".into(),
                measured: format!(
                    "packed matrix product, best case: {packed_median:.2} GFLOP/s (median run), \
                     {packed_best:.2} GFLOP/s (fastest run)"
                ),
                holds: if software {
                    Some(packed_median >= 10.0)
                } else {
                    None
                },
            },
        ],
        figures,
        fidelity: fidelity(),
        results: serde_json::json!({
            "renderer": renderer,
            "quick": opts.quick,
            "repeats": repeats,
            "load_average_1min": load,
            "measurements": measurements,
            "detection": detection.results,
        }),
    })
}

/// The 1-minute load average (Linux), to read software-renderer timings against.
fn load_average() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/loadavg").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

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
    });
    cases.push(Case {
        name: format!("121-30-1, L = {} (all of text.png)", all.nrows()),
        network: detector,
        batch: all,
        max_vectors: None,
    });
    cases.push(wide_case(512, 4096));
    Ok(cases)
}

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
    }
}

fn measure(
    gpu: &GpuMlp,
    case: &Case,
    method: Method,
    repeats: usize,
    reference: &Array2<f32>,
) -> anyhow::Result<Measurement> {
    let mut runs: Vec<(StepTimes, usize, Array2<f32>)> = Vec::new();
    // one run more than counted: the first draw of a program compiles its shader variant
    // (llvmpipe JIT), and llvmpipe's first timer query of a context reads garbage
    for round in 0..=repeats {
        let run = match method {
            Method::GpuFaithful | Method::GpuPacked => {
                let formulation = if method == Method::GpuFaithful {
                    Formulation::Faithful
                } else {
                    Formulation::Packed
                };
                let loaded = gpu.load(&case.network, formulation)?;
                let out = loaded.forward(case.batch.view(), case.max_vectors)?;
                (out.times, out.tiles, out.outputs)
            }
            Method::CpuPlain | Method::CpuOptimised => {
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
                (times, 1, out.outputs)
            }
        };
        if round > 0 {
            runs.push(run);
        }
    }
    let median = |f: fn(&StepTimes) -> f64| {
        let mut v: Vec<f64> = runs.iter().map(|r| f(&r.0)).collect();
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
        .map(|r| r.0.matmul)
        .fold(f64::INFINITY, f64::min);
    let diff = runs[0]
        .2
        .iter()
        .zip(reference.iter())
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    Ok(Measurement {
        case: case.name.clone(),
        method,
        layers: case
            .network
            .layers()
            .iter()
            .map(|l| [l.inputs(), l.outputs()])
            .collect(),
        vectors: case.batch.nrows(),
        tiles: runs[0].1,
        total_ms: times.texture_creation + times.matmul + times.activation + times.readback,
        matmul_gflops: flops / (times.matmul * 1e-3) / 1e9,
        best_matmul_gflops: flops / (fastest * 1e-3) / 1e9,
        times_ms: times,
        max_abs_diff_vs_cpu_plain: diff,
    })
}

fn ms(v: f64) -> String {
    format!("{v:.3}")
}

/// Table 1 with the paper's numbers in the first columns.
fn table1_beside_paper(row: &[Measurement], paper: &dyn Fn(&str) -> f64) -> Table {
    let get = |m: Method| row.iter().find(|r| r.method == m).expect("measured");
    let (f, p, c, o) = (
        get(Method::GpuFaithful),
        get(Method::GpuPacked),
        get(Method::CpuPlain),
        get(Method::CpuOptimised),
    );
    let line = |op: &str, pg: String, pc: String, value: fn(&Measurement) -> String| {
        vec![
            op.to_string(),
            pg,
            pc,
            value(f),
            value(p),
            value(c),
            value(o),
        ]
    };
    let na = || "-".to_string();
    Table {
        caption: format!(
            "Table 1 beside the paper: processing times per elementary operation, {} \
             (paper: ATI RADEON 9700 PRO, unit not stated; here: ms)",
            f.case
        ),
        header: [
            "operation",
            "paper GPU",
            "paper CPU",
            "GPU faithful",
            "GPU packed",
            "CPU plain",
            "CPU sgemm",
        ]
        .map(String::from)
        .to_vec(),
        rows: vec![
            line(
                "texture creation",
                format!("{}", paper("gpu_texture_creation")),
                na(),
                |m| ms(m.times_ms.texture_creation),
            ),
            line(
                "matrix multiplication",
                format!("{}", paper("gpu_matrix_multiplication")),
                format!("{}", paper("cpu_matrix_multiplication")),
                |m| ms(m.times_ms.matmul),
            ),
            line("sigmoid", format!("{}", paper("gpu_sigmoid")), na(), |m| {
                ms(m.times_ms.activation)
            }),
            line("readback", na(), na(), |m| ms(m.times_ms.readback)),
            line(
                "total",
                format!(
                    "{:.3}",
                    paper("gpu_texture_creation")
                        + paper("gpu_matrix_multiplication")
                        + paper("gpu_sigmoid")
                ),
                format!("{}", paper("cpu_matrix_multiplication")),
                |m| ms(m.total_ms),
            ),
        ],
    }
}

/// GFLOP/s of the matrix product, every case and method side by side.
fn gflops_table(measurements: &[Measurement]) -> Table {
    Table {
        caption: "Matrix product throughput, the four methods side by side (GFLOP/s = 2 M N L / \
                  median product time; best = fastest run; max |diff| against the CPU plain \
                  loop's outputs)"
            .into(),
        header: [
            "case",
            "method",
            "tiles",
            "texture ms",
            "product ms",
            "sigmoid ms",
            "total ms",
            "GFLOP/s",
            "best GFLOP/s",
            "max |diff|",
        ]
        .map(String::from)
        .to_vec(),
        rows: measurements
            .iter()
            .map(|m| {
                vec![
                    m.case.clone(),
                    m.method.label().to_string(),
                    m.tiles.to_string(),
                    ms(m.times_ms.texture_creation),
                    ms(m.times_ms.matmul),
                    ms(m.times_ms.activation),
                    ms(m.total_ms),
                    format!("{:.2}", m.matmul_gflops),
                    format!("{:.2}", m.best_matmul_gflops),
                    format!("{:.1e}", m.max_abs_diff_vs_cpu_plain),
                ]
            })
            .collect(),
    }
}

/// GFLOP/s of the detector's product against the batch size, the four methods.
fn gflops_plot(opts: &BenchOptions, measurements: &[Measurement]) -> anyhow::Result<Figure> {
    let file = "paper3_gflops.png";
    let series = Method::ALL
        .iter()
        .map(|&method| {
            let points = measurements
                .iter()
                .filter(|m| m.method == method && m.layers.len() == 2)
                .map(|m| (m.vectors as f64, m.matmul_gflops))
                .collect();
            Series::new(method.label(), points)
        })
        .collect();
    Plot {
        title: "121-30-1 text detector: matrix product throughput".into(),
        x_label: "input vectors L".into(),
        y_label: "GFLOP/s (median run)".into(),
        log_x: true,
        log_y: true,
        series,
    }
    .write_png(&opts.out_dir.join(file))?;
    Ok(Figure {
        file: file.into(),
        caption: "Matrix product GFLOP/s of the detector network against the batch size L, GPU \
                  passes (faithful, packed) and CPU baselines (plain loop, sgemm), one run"
            .into(),
    })
}

struct Detection {
    table: Table,
    figures: Vec<Figure>,
    agreement: f64,
    results: serde_json::Value,
}

/// Fig. 2 regenerated: text.png classified on the GPU (both formulations) and the CPU.
fn detect_photo(opts: &BenchOptions, gpu: &GpuMlp, photo: &GrayImage) -> anyhow::Result<Detection> {
    let net = shipped_detector()?;
    let (w, h) = photo.dimensions();
    let cpu = classify_cpu(&net, photo, CpuProduct::Optimised, 1 << 18);
    let mut rows = Vec::new();
    let mut results = serde_json::Map::new();
    let mut agreement = 0.0;
    let mut figures = vec![Figure {
        file: "paper3_fig2a_text.png".into(),
        caption: "Fig. 2(a): the test image (scikit-image text.png, public domain)".into(),
    }];
    photo
        .save(opts.out_dir.join("paper3_fig2a_text.png"))
        .context("writing paper3_fig2a_text.png")?;
    for formulation in [Formulation::Faithful, Formulation::Packed] {
        let loaded = gpu.load(&net, formulation)?;
        let (out, times) = classify_gpu(&loaded, photo, 1 << 18)?;
        let same = out
            .iter()
            .zip(&cpu)
            .filter(|(g, c)| (**g > THRESHOLD) == (**c > THRESHOLD))
            .count() as f64
            / cpu.len() as f64;
        let text = out.iter().filter(|&&v| v > THRESHOLD).count();
        if formulation == Formulation::Faithful {
            agreement = same;
            let file = "paper3_fig2b_mask.png";
            mask_image(&out, w, h, THRESHOLD)
                .save(opts.out_dir.join(file))
                .with_context(|| format!("writing {file}"))?;
            figures.push(Figure {
                file: file.into(),
                caption: "Fig. 2(b): every pixel classified by the MLP on the GPU in one batch \
                          (black = text)"
                    .into(),
            });
        }
        rows.push(vec![
            format!("{formulation:?}"),
            format!("{:.2}%", 100.0 * text as f64 / cpu.len() as f64),
            format!("{:.4}%", 100.0 * same),
            ms(times.texture_creation + times.matmul + times.activation + times.readback),
        ]);
        results.insert(
            format!("{formulation:?}").to_lowercase(),
            serde_json::json!({"text_pixels": text, "agreement_with_cpu": same, "times_ms": times}),
        );
    }
    let cpu_text = cpu.iter().filter(|&&v| v > THRESHOLD).count();
    rows.push(vec![
        "CPU (sgemm)".into(),
        format!("{:.2}%", 100.0 * cpu_text as f64 / cpu.len() as f64),
        "100%".into(),
        "-".into(),
    ]);
    Ok(Detection {
        table: Table {
            caption: format!(
                "Fig. 2: text detection on text.png ({w} x {h} = {} pixels, one batch)",
                cpu.len()
            ),
            header: ["evaluated by", "text pixels", "same class as CPU", "GPU ms"]
                .map(String::from)
                .to_vec(),
            rows,
        },
        figures,
        agreement,
        results: serde_json::Value::Object(results),
    })
}

fn fidelity() -> Vec<Fidelity> {
    let row = |f: &str, p: &str, c: &str| Fidelity::new(f, p, c, "");
    vec![
        row(
            "Matrix product as one rectangle (Moravanszky): each vertex carries the row of W and the column of X, each pixel takes one inner product",
            "Section 3, eq. 2, Fig. 1",
            "glsl/mlp/product.vert, glsl/mlp/product.frag, src/mlp/matmul.rs",
        ),
        row(
            "Bias + sigmoid in one pass, 1D bias texture addressed by the vertical position",
            "Section 3, eq. 3",
            "glsl/mlp/bias_sigmoid.vert, glsl/mlp/bias_sigmoid.frag, src/mlp/activation.rs",
        ),
        row(
            "Render-target texture of one layer is the next layer's X; nothing read back until the end",
            "Section 3, last paragraph",
            "src/mlp/chain.rs",
        ),
        row(
            "Input vectors accumulated into one texture, up to the maximum texture size (2048 on the paper's board)",
            "Section 4, footnote 1",
            "src/mlp/textures.rs, src/mlp/tiling.rs",
        ),
        row(
            "11 x 11 grey window, 30 hidden nodes, output thresholded into text / non-text",
            "Section 4, Fig. 2",
            "src/mlp/window.rs, src/mlp/train.rs, src/mlp/detect.rs",
        ),
        row(
            "Not in the paper: packed RGBA variant (4 x 4 outputs per fragment, MRT)",
            "-",
            "glsl/mlp/packed_product.frag, src/mlp/packed.rs",
        ),
        row(
            "Differences: the paper's weights and training data are unpublished (trained here on synthetic font8x8 text); a 2004 pixel shader needed several passes per product, GLSL 330 loops over N in one",
            "Section 3-4",
            "src/mlp/synth.rs, src/mlp/train.rs",
        ),
    ]
}

/// The paper-3 section.
pub struct Paper3;

impl super::Paper for Paper3 {
    const ID: &'static str = "paper3";
    const TITLE: &'static str = "Paper 3: Oh & Jung 2004, GPU implementation of neural networks";
    type Options = super::NoOptions;
    type Results = super::LegacySection;

    fn measure(opts: &BenchOptions, _: &super::NoOptions) -> anyhow::Result<super::LegacySection> {
        run(opts).map(super::LegacySection)
    }

    fn section(_: &BenchOptions, results: &super::LegacySection) -> anyhow::Result<Section> {
        Ok(results.section())
    }
}
