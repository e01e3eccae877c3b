//! Paper 4 on its own GPU, the GeForce 7800 GTX. The chip had no float depth, so depth
//! peeling as built here (32-bit float depth with stencil) is refused at once; the rest of
//! the path is then run under every other limit of the chip (the same profile with float
//! depth added, and named so), in the paper's order (n layers kept and each reduced, no
//! blending) and with running sums blended at fp16 (the only float blending the chip had),
//! beside today's fp32 running sums, all against Mirtich's analytic integrals.

use crate::gl::{period, PeriodGpu, TextureFormat};
use crate::mass::assemble::MassProperties;
use crate::mass::gpu::GpuMass;
use crate::mass::peel::{PeelOrder, PeelSettings};
use crate::mass::{analytic, clip, models};
use crate::report::period::{under, PeriodResults, Verdict};
use crate::report::BenchOptions;
use std::sync::OnceLock;

/// The G70 profile with 32-bit float depth added: the one limit step 1 is refused on,
/// lifted (and named) so that the other limits are checked on the rest of the path.
fn g70_with_float_depth() -> &'static PeriodGpu {
    static GPU: OnceLock<PeriodGpu> = OnceLock::new();
    GPU.get_or_init(|| {
        let mut gpu = period::for_paper(4).clone();
        gpu.name = format!("{} with float depth added", gpu.name);
        gpu.texture_formats.value.extend([
            "DEPTH32F_STENCIL8".to_string(),
            "DEPTH_COMPONENT32F".to_string(),
        ]);
        gpu
    })
}

/// The object, the water level for the submerged part, and the resolution.
const MODEL: &str = "torus";
const LEVEL: f32 = 0.1;

/// How a run sums its peels.
#[derive(Clone, Copy)]
struct Way {
    order: PeelOrder,
    sums: TextureFormat,
}

const TODAY: Way = Way {
    order: PeelOrder::RunningSums,
    sums: TextureFormat::Rgba32F,
};
const KEEP_LAYERS: Way = Way {
    order: PeelOrder::KeepLayers,
    sums: TextureFormat::Rgba32F,
};
const FP16_SUMS: Way = Way {
    order: PeelOrder::RunningSums,
    sums: TextureFormat::Rgba16F,
};

/// Mass properties of the whole body and of its part below `LEVEL`.
fn run(
    ctx: &crate::gl::Context,
    mesh: &crate::mesh::Mesh,
    resolution: u32,
    way: Way,
) -> anyhow::Result<[MassProperties; 2]> {
    let mut gpu = GpuMass::with_sum_format(ctx, resolution, way.sums)?;
    gpu.set_settings(PeelSettings {
        order: way.order,
        ..PeelSettings::default()
    })?;
    let whole = gpu.integrate(mesh, None, None)?;
    let below = gpu.integrate(mesh, Some(LEVEL as f64), None)?;
    Ok([whole, below].map(|r| MassProperties::from_integrals(&r.integrals, 1.0)))
}

/// The largest relative error of mass and the three moments, in percent.
fn error(got: &MassProperties, want: &MassProperties) -> f64 {
    got.relative_errors(want).into_iter().fold(0.0, f64::max) * 100.0
}

pub fn measure(opts: &BenchOptions) -> anyhow::Result<PeriodResults> {
    let ctx = opts.gl;
    let g70 = period::for_paper(4);
    let lifted = g70_with_float_depth();
    let resolution = if opts.quick { 32 } else { 64 };
    let mesh = models::load(MODEL).map_err(anyhow::Error::msg)?;
    let analytic = [
        analytic::volume_integrals(&mesh),
        analytic::volume_integrals(&clip::below_plane(&mesh, LEVEL)),
    ]
    .map(|i| MassProperties::from_integrals(&i, 1.0));
    let mut out = PeriodResults::new(g70);

    let peeling = under(ctx, g70, || run(ctx, &mesh, resolution, KEEP_LAYERS));
    out.step_from(
        "depth peeling with 32-bit float depth and a stencil bit (Sec. 3.2, 5.2)",
        &peeling,
        "fits",
    );
    if peeling.is_err() {
        out.step(
            "depth peeling, the period's way",
            Verdict::Refused,
            "not built here: the chip peeled against a 24-bit depth buffer, which needs the \
             peel test to compare depths at 24 bits; the steps below are run under every \
             other limit of the chip (float depth added to its profile)",
        );
    }
    let fp32_sums = under(ctx, lifted, || run(ctx, &mesh, resolution, TODAY));
    out.step_from(
        "running sums of the peels by fp32 additive blending (this project's default)",
        &fp32_sums,
        "fits",
    );
    let keep = under(ctx, lifted, || run(ctx, &mesh, resolution, KEEP_LAYERS));
    match &keep {
        Ok(_) => out.step(
            "the paper's order: the n layers T_1..T_n and T_w kept and each reduced (Sec. 3.3, 5.2)",
            Verdict::PeriodsWay,
            "no blending: every draw checked under the chip's other limits",
        ),
        Err(_) => out.step_from("the paper's order", &keep, ""),
    }
    let fp16 = under(ctx, lifted, || run(ctx, &mesh, resolution, FP16_SUMS));
    match &fp16 {
        Ok(_) => out.step(
            "running sums blended at fp16 (RGBA16F), the float blending the chip had",
            Verdict::PeriodsWay,
            "each addition rounded to 11 significant bits; the reduction reads them in fp32",
        ),
        Err(_) => out.step_from("running sums at fp16", &fp16, ""),
    }
    out.step(
        "buffer reduction, ping-pong RGBA32F without blending (Sec. 3.3)",
        if keep.is_ok() {
            Verdict::Fits
        } else {
            Verdict::Refused
        },
        "fits: nearest reads of fp32 textures, three render targets",
    );

    let today = run(ctx, &mesh, resolution, TODAY)?;
    for (k, what) in ["whole body", "part below z = 0.1 (buoyancy)"]
        .into_iter()
        .enumerate()
    {
        let row = |result: &anyhow::Result<[MassProperties; 2]>| match result {
            Ok(r) => format!("{:.3}%", error(&r[k], &analytic[k])),
            Err(e) => format!("refused: {e:#}"),
        };
        let today_error = error(&today[k], &analytic[k]);
        for (way, result, why) in [
            (
                "kept layers, fp32",
                &keep,
                "the same sums in another order: fp32 rounding only",
            ),
            (
                "running sums at fp16",
                &fp16,
                "each blended addition rounds the running sum to 11 significant bits (up to \
                 2^-10 relative, the rounding being the driver's), small beside the grid's own \
                 error at this resolution, so the error against the analytic method moves \
                 either way",
            ),
        ] {
            let change = match result {
                Ok(r) => format!(
                    "{:+.3} points; {:.3}% from today's result: {why}",
                    error(&r[k], &analytic[k]) - today_error,
                    error(&r[k], &today[k])
                ),
                Err(_) => "refused".into(),
            };
            out.compare(
                &format!(
                    "{MODEL} {what} at {resolution}x{resolution}: largest error of mass and \
                     moments against the analytic method, {way}"
                ),
                format!("{today_error:.3}% (running sums, fp32)"),
                row(result),
                change,
            );
        }
    }
    Ok(out)
}
