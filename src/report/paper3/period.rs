//! The period tables: paper 3 on its own board's terms. The text detector runs twice on the
//! same batches, once in today's fp32 and once as the ATI RADEON 9700 PRO (R300) would have:
//! its 24-bit fragment arithmetic emulated at every step (`mlp::fp24`), its limits enforced by
//! the GL layer (`gl::period`), each product split into passes of at most
//! [`RADEON_9700_INPUTS_PER_PASS`] inputs. The two tables have the shape of the other papers'
//! period blocks (`report::period`): one says which step fits the R300 and which took the
//! period's way, the other sets the outputs, the detection mask and the error against labelled
//! windows beside today's.

use super::fig2_files::FIG2A_FILE;
use crate::gl::{period, Context, GlError};
use crate::mlp::detect::{classify_gpu, mask_image, shipped_detector, THRESHOLD};
use crate::mlp::fp24::{forward_fp24, Precision, UNIT_ROUNDOFF};
use crate::mlp::matmul::RADEON_9700_INPUTS_PER_PASS;
use crate::mlp::train::{evaluate, window_set};
use crate::mlp::{Activation, Formulation, GpuMlp, Network};
use crate::report::period::{Comparison, Step, Verdict};
use crate::report::{BenchOptions, Figure, Table};
use anyhow::Context as _;
use image::GrayImage;
use ndarray::Array2;
use serde::Serialize;

/// The mask at fp24, with the pixels whose class changed marked.
pub const PERIOD_MASK_FILE: &str = "paper3_period_fp24_mask.png";

/// Rows of text.png classified under `--quick` (the whole photograph otherwise).
const QUICK_ROWS: u32 = 24;

/// What the period run measured: the block every paper's section carries (the board, each
/// step's verdict, the results beside today's), and the measurements behind it.
#[derive(Clone, Debug, Serialize)]
pub struct PeriodResults {
    #[serde(flatten)]
    pub block: crate::report::period::PeriodResults,
    pub inputs_per_pass: usize,
    pub photo: PhotoAtFp24,
    pub labelled: LabelledAtFp24,
}

/// text.png (or its first rows under `--quick`) at fp32 and at fp24.
#[derive(Clone, Debug, Serialize)]
pub struct PhotoAtFp24 {
    pub width: u32,
    pub rows: u32,
    /// Whether `rows` is only the photograph's first rows (`--quick`).
    pub cropped: bool,
    pub max_abs_diff: f32,
    pub mean_abs_diff: f64,
    pub fp32_text_pixels: usize,
    pub fp24_text_pixels: usize,
    /// Pixels whose class (text or not) differs between the two.
    pub changed_pixels: usize,
    /// Texture tiles of input vectors at fp24 (at most 2048 vectors each on the R300).
    pub fp24_tiles: usize,
    pub product_passes: Vec<usize>,
}

/// Labelled synthetic windows (images the detector was not trained on) at both precisions.
#[derive(Clone, Debug, Serialize)]
pub struct LabelledAtFp24 {
    pub windows: usize,
    pub fp32_accuracy: f64,
    pub fp24_accuracy: f64,
    pub fp32_mse: f64,
    pub fp24_mse: f64,
    /// The GPU at fp24 against the CPU model of the same rounding at the output furthest
    /// from it relative to its bound, and what that output allows (twice `error_bound_fp24`).
    pub max_diff_vs_cpu_model: f32,
    pub allowed_vs_cpu_model: f32,
}

/// Seed of the labelled windows: other synthetic images than the detector's training (seed 1).
const LABELLED_SEED: u64 = 77;

pub fn measure(opts: &BenchOptions, photo: &GrayImage) -> anyhow::Result<PeriodResults> {
    let ctx = opts.gl;
    let net = shipped_detector()?;
    let r300 = period::for_paper(3);
    let rows = if opts.quick {
        QUICK_ROWS.min(photo.height())
    } else {
        photo.height()
    };
    let full_height = photo.height();
    let photo = image::imageops::crop_imm(photo, 0, 0, photo.width(), rows).to_image();
    let fp32_gpu = GpuMlp::new(ctx)?;
    let fp32_outputs = classify_gpu(
        &fp32_gpu.load(&net, Formulation::Faithful)?,
        &photo,
        1 << 18,
        None,
    )?
    .outputs;
    let images = if opts.quick { 8 } else { 40 };
    let windows = window_set(LABELLED_SEED, images, 30);
    let fp32_windows = fp32_gpu
        .load(&net, Formulation::Faithful)?
        .forward(windows.inputs.view(), None)?
        .outputs;
    // the R300's run: its limits on the context for as long as it lasts
    let (fp24, windows_fp24) = under_period(ctx, r300, || {
        let gpu = GpuMlp::with_precision(ctx, Precision::Fp24)?;
        let loaded = gpu
            .load(&net, Formulation::Faithful)?
            .split_products(Some(RADEON_9700_INPUTS_PER_PASS))?;
        let classified = classify_gpu(&loaded, &photo, 1 << 18, None)?;
        let windows_out = loaded.forward(windows.inputs.view(), None)?;
        Ok((classified, windows_out))
    })
    .with_context(|| format!("paper 3 as the {}", r300.name))?;
    let fp24_outputs = &fp24.outputs;
    for outputs in [&fp32_outputs, fp24_outputs] {
        anyhow::ensure!(
            outputs.iter().all(|v| v.is_finite()),
            "period: a text.png output is not finite"
        );
    }
    write_mask(opts, &photo, &fp32_outputs, fp24_outputs)?;
    let diffs: Vec<f32> = fp32_outputs
        .iter()
        .zip(fp24_outputs)
        .map(|(a, b)| (a - b).abs())
        .collect();
    let text = |outputs: &[f32]| outputs.iter().filter(|&&v| v > THRESHOLD).count();
    let photo_result = PhotoAtFp24 {
        width: photo.width(),
        rows,
        cropped: rows < full_height,
        max_abs_diff: diffs.iter().copied().fold(0.0, f32::max),
        mean_abs_diff: diffs.iter().map(|&d| f64::from(d)).sum::<f64>() / diffs.len() as f64,
        fp32_text_pixels: text(&fp32_outputs),
        fp24_text_pixels: text(fp24_outputs),
        changed_pixels: fp32_outputs
            .iter()
            .zip(fp24_outputs)
            .filter(|(a, b)| (**a > THRESHOLD) != (**b > THRESHOLD))
            .count(),
        fp24_tiles: fp24.batches,
        product_passes: windows_fp24.product_passes.clone(),
    };
    let labelled = labelled_result(&net, &windows, &fp32_windows, &windows_fp24.outputs);
    anyhow::ensure!(
        labelled.max_diff_vs_cpu_model <= labelled.allowed_vs_cpu_model,
        "period: the GPU at fp24 is {} from the CPU model of the rounding, beyond the {} the \
         rounding allows",
        labelled.max_diff_vs_cpu_model,
        labelled.allowed_vs_cpu_model
    );
    let block = crate::report::period::PeriodResults {
        gpu: r300.name.clone(),
        steps: steps(&net, r300, &photo_result),
        comparisons: comparisons(&photo_result, &labelled),
    };
    Ok(PeriodResults {
        block,
        inputs_per_pass: RADEON_9700_INPUTS_PER_PASS,
        photo: photo_result,
        labelled,
    })
}

/// `run` with the context under `gpu`'s limits, which are lifted again whatever happens.
fn under_period<T>(
    ctx: &Context,
    gpu: &'static period::PeriodGpu,
    run: impl FnOnce() -> Result<T, GlError>,
) -> Result<T, GlError> {
    let before = ctx.period();
    ctx.set_period(Some(gpu));
    let result = run();
    ctx.set_period(before);
    result
}

fn labelled_result(
    net: &Network,
    windows: &crate::mlp::train::WindowSet,
    fp32: &Array2<f32>,
    fp24: &Array2<f32>,
) -> LabelledAtFp24 {
    let mse = |outputs: &Array2<f32>| {
        outputs
            .column(0)
            .iter()
            .zip(&windows.labels)
            .map(|(y, t)| f64::from(y - t).powi(2))
            .sum::<f64>()
            / windows.labels.len() as f64
    };
    let model = forward_fp24(net, windows.inputs.view());
    let bound = same_steps_bound(net, windows.inputs.view());
    // the worst output relative to what its own bound allows
    let (max_diff, allowed) = fp24
        .iter()
        .zip(&model)
        .zip(&bound)
        .map(|((g, c), e)| ((g - c).abs(), 2.0 * e))
        .max_by(|a, b| (a.0 / a.1).total_cmp(&(b.0 / b.1)))
        .unwrap_or((0.0, 0.0));
    LabelledAtFp24 {
        windows: windows.labels.len(),
        fp32_accuracy: evaluate(fp32.column(0), &windows.labels, THRESHOLD).accuracy,
        fp24_accuracy: evaluate(fp24.column(0), &windows.labels, THRESHOLD).accuracy,
        fp32_mse: mse(fp32),
        fp24_mse: mse(fp24),
        max_diff_vs_cpu_model: max_diff,
        allowed_vs_cpu_model: allowed,
    }
}

/// A sigmoid evaluated at fp24 on two implementations that differ only in `exp` (GLSL allows
/// `exp` 3 + 2|x| fp32 ulps): after the rounding to fp24 of `exp`, of `1 + exp` and of the
/// quotient, each side may stand up to one fp24 unit apart, so the outputs (below 1) differ by
/// at most 4 units of 2^-16, the fp24 spacing just below 1, with margin.
const SIGMOID_APART: f64 = 4.0 / 65_536.0;

/// What fp24 justifies between the GPU and the CPU model of its rounding
/// ([`forward_fp24`]), per output. Both make the same rounded steps in the same order (an
/// identity layer agrees bit for bit: tests/mlp_fp24.rs), so the first layer's sums are equal
/// and the two part only at its sigmoid, by [`SIGMOID_APART`]. From there on a later layer
/// carries that difference through `|W|`, and its own roundings, now of different values,
/// may differ by the usual fp24 bound `gamma_n sum |w x|` (Higham 3.1; the unit roundoff of
/// fp24 after fp32, four more rounded steps per term, as `fp24::error_bound_fp24` counts
/// them); a sigmoid scales the difference by at most 1/4 and adds its own. Twice this is
/// what the report allows: the old bound, which let the first layer's roundings differ too,
/// allowed about 2e4 times the difference seen.
fn same_steps_bound(net: &Network, batch: ndarray::ArrayView2<f32>) -> Array2<f32> {
    let u = UNIT_ROUNDOFF + f64::from(f32::EPSILON) / 2.0;
    let layers = net.layers();
    let Some(first) = layers.first() else {
        return Array2::zeros((batch.nrows(), 0));
    };
    let one = Network::new(vec![first.clone()]).expect("a layer of a valid network");
    let mut values = forward_fp24(&one, batch).mapv(f64::from);
    let apart = match first.activation {
        Activation::Sigmoid => SIGMOID_APART,
        Activation::Identity => 0.0,
    };
    let mut errors = Array2::<f64>::from_elem(values.raw_dim(), apart);
    for layer in &layers[1..] {
        let n = (layer.inputs() + 1 + 4) as f64;
        let gamma = n * u / (1.0 - n * u) + 4.0 * u;
        let w = layer.weights.mapv(f64::from);
        let abs_w = w.mapv(f64::abs);
        let bias = layer.bias.mapv(f64::from);
        let sum_abs = values.mapv(f64::abs).dot(&abs_w.t()) + bias.mapv(f64::abs);
        let mut m = values.dot(&w.t()) + &bias;
        let mut e = errors.dot(&abs_w.t()) + sum_abs * gamma;
        if layer.activation == Activation::Sigmoid {
            m.mapv_inplace(|v| 1.0 / (1.0 + (-v).exp()));
            e.mapv_inplace(|v| (0.25 * v).min(1.0) + SIGMOID_APART);
        }
        values = m;
        errors = e;
    }
    errors.mapv(|e| e as f32)
}

/// The fp24 mask (black = text) with the pixels whose class differs from fp32's in red.
fn write_mask(
    opts: &BenchOptions,
    photo: &GrayImage,
    fp32: &[f32],
    fp24: &[f32],
) -> anyhow::Result<()> {
    let (width, height) = photo.dimensions();
    let mask = mask_image(fp24, width, height, THRESHOLD);
    let rgba: Vec<u8> = mask
        .pixels()
        .zip(fp32.iter().zip(fp24))
        .flat_map(|(p, (a, b))| {
            if (*a > THRESHOLD) != (*b > THRESHOLD) {
                [255, 0, 0, 255]
            } else {
                [p.0[0], p.0[0], p.0[0], 255]
            }
        })
        .collect();
    let path = opts.out_dir.join(PERIOD_MASK_FILE);
    crate::files::write_png(&path, &rgba, width, height)
        .with_context(|| format!("writing {PERIOD_MASK_FILE}"))?;
    let what = "the fp24 mask: white text, red where fp24 and fp32 disagree";
    crate::gl::drawn::record(&path, crate::gl::drawn::Drawn::Image { what: what.into() });
    Ok(())
}

/// Each step of the faithful passes: what it asks of the GPU in this run against the R300's
/// limit. The fp24 run above went through the GL layer under those limits, so each step ran;
/// the split products and the 24-bit arithmetic are the period's way, the rest fits as built.
fn steps(net: &Network, r300: &period::PeriodGpu, photo: &PhotoAtFp24) -> Vec<Step> {
    let max = r300.max_texture_size.value;
    let widest = net
        .layers()
        .iter()
        .map(|l| l.inputs().max(l.outputs()))
        .max()
        .unwrap_or(0);
    let pixels = (photo.width * photo.rows) as usize;
    let per_tile = pixels.min(max as usize);
    let passes: Vec<String> = photo.product_passes.iter().map(|p| p.to_string()).collect();
    let blended = if r300.float_blending.value.is_empty() {
        "the R300 blended no float target".to_string()
    } else {
        format!("the R300 blended {}", r300.float_blending.value.join(", "))
    };
    let step = |step: &str, verdict: Verdict, detail: String| Step {
        step: step.into(),
        verdict,
        detail,
    };
    vec![
        step(
            "Texture W and the 1D bias texture (R32F)",
            Verdict::Fits,
            format!(
                "at most {widest} texels a side (the 121-30-1 detector); the R300 allocated R32F \
                 textures up to {max} a side"
            ),
        ),
        step(
            "Texture X: input vectors accumulated per texture",
            Verdict::Fits,
            format!(
                "{pixels} vectors in {} tile(s) of at most {per_tile}; the R300's textures \
                 were at most {max} wide",
                photo.fp24_tiles
            ),
        ),
        step(
            "Matrix product W x X",
            Verdict::PeriodsWay,
            format!(
                "{} pass(es) per layer of at most {} inputs (our estimate of what the board's \
                 ps_2_0 programs held; today one pass), the running sum read back from the \
                 previous target, never blended: {blended}",
                passes.join(" + "),
                RADEON_9700_INPUTS_PER_PASS
            ),
        ),
        step(
            "Bias + sigmoid",
            Verdict::Fits,
            "one pass reading W x X and the bias texture at texel centres (nearest), the only \
             way the R300 read float textures"
                .into(),
        ),
        step(
            "Layer chaining through render targets",
            Verdict::Fits,
            format!(
                "one R32F colour target per pass; the R300 wrote up to {} float targets, \
                 unblended",
                r300.max_draw_buffers.value
            ),
        ),
        step(
            "Arithmetic",
            Verdict::PeriodsWay,
            format!(
                "{}-bit floats in the fragment pipeline (16-bit mantissa, 7-bit exponent), \
                 emulated by rounding every intermediate result; today fp32",
                r300.fragment_float_bits.value
            ),
        ),
    ]
}

/// The results at fp24 beside fp32, each with by how much and why it changes.
fn comparisons(p: &PhotoAtFp24, l: &LabelledAtFp24) -> Vec<Comparison> {
    let pixels = (p.width * p.rows) as usize;
    let share = |n: usize| format!("{n} ({:.2}%)", 100.0 * n as f64 / pixels as f64);
    let percent = |v: f64| format!("{:.2}%", 100.0 * v);
    let photo = format!(
        "text.png, {} x {}{}",
        p.width,
        p.rows,
        if p.cropped { " (its first rows)" } else { "" }
    );
    let rounding = "each step rounded to 17 significant bits instead of 24";
    let compare = |result: String, today: String, period: String, change: String| Comparison {
        result,
        today,
        period,
        change,
    };
    vec![
        compare(
            format!("{photo}: detector outputs"),
            "reference".into(),
            format!(
                "max |diff| {:.3e}, mean {:.3e}",
                p.max_abs_diff, p.mean_abs_diff
            ),
            format!(
                "{rounding}; the outputs move by at most {:.1e}",
                p.max_abs_diff
            ),
        ),
        compare(
            format!("{photo}: pixels called text (output > {THRESHOLD})"),
            share(p.fp32_text_pixels),
            share(p.fp24_text_pixels),
            if p.changed_pixels == 0 {
                "none: no output lies close enough to the threshold for the rounding to move \
                 it across"
                    .into()
            } else {
                format!(
                    "{} pixel(s) change class: outputs within the rounding's reach of the \
                     threshold cross it (red in the figure)",
                    p.changed_pixels
                )
            },
        ),
        compare(
            format!("{} labelled windows: accuracy", l.windows),
            percent(l.fp32_accuracy),
            percent(l.fp24_accuracy),
            format!(
                "{:+.3} points ({rounding})",
                100.0 * (l.fp24_accuracy - l.fp32_accuracy)
            ),
        ),
        compare(
            format!(
                "{} labelled windows: mean squared error against the labels",
                l.windows
            ),
            format!("{:.6}", l.fp32_mse),
            format!("{:.6}", l.fp24_mse),
            format!("{:+.2e} ({rounding})", l.fp24_mse - l.fp32_mse),
        ),
        compare(
            "GPU at fp24 against the CPU model of the same rounding (src/mlp/fp24.rs)".into(),
            "-".into(),
            format!("max |diff| {:.2e}", l.max_diff_vs_cpu_model),
            format!(
                "within the {:.2e} fp24 allows where the two differ only in exp (twice the \
                 bound of the layers after the first sigmoid): the shaders round as the model \
                 does",
                l.allowed_vs_cpu_model
            ),
        ),
    ]
}

/// The steps table and the results table, as every paper's period block has them.
pub fn tables(results: &PeriodResults) -> Vec<Table> {
    results.block.tables()
}

pub fn figure(results: &PeriodResults) -> Figure {
    Figure {
        file: PERIOD_MASK_FILE.into(),
        caption: format!(
            "Period: {} classified at the {}'s 24-bit precision (black = text), red where the \
             class differs from fp32 ({} pixel(s))",
            FIG2A_FILE, results.block.gpu, results.photo.changed_pixels
        ),
    }
}
