//! Paper 4 on its own GPU, the GeForce 7800 GTX. The chip had no float depth, so depth
//! peeling as built for today (32-bit float depth with stencil) is refused; the period's way
//! peels against 24-bit depth, comparing depths in whole steps of 2^-24 of the depth range
//! (`mass::peel_depth`). Under the chip's profile the peels are summed in the paper's order
//! (n layers kept and each reduced, no blending) or with running sums blended at fp16 (the
//! only float blending the chip had), beside today's fp32 depth and fp32 running sums, all
//! against Mirtich's analytic integrals; 24-bit depth alone (fp32 sums, outside the
//! profile) shows what the depth format changes by itself.

use crate::gl::{period, TextureFormat};
use crate::mass::assemble::MassProperties;
use crate::mass::framing::Framing;
use crate::mass::gpu::GpuMass;
use crate::mass::peel::{PeelOrder, PeelSettings};
use crate::mass::peel_depth::PeelDepth;
use crate::mass::{analytic, clip, cpu_reference, models};
use crate::report::period::{under, PeriodResults, Verdict};
use crate::report::BenchOptions;

/// The object, the water level for the submerged part, and the resolution.
const MODEL: &str = "torus";
const LEVEL: f32 = 0.1;

/// How a run peels and sums.
#[derive(Clone, Copy)]
struct Way {
    order: PeelOrder,
    sums: TextureFormat,
    depth: PeelDepth,
}

const TODAY: Way = Way {
    order: PeelOrder::RunningSums,
    sums: TextureFormat::Rgba32F,
    depth: PeelDepth::Float32,
};
const DEPTH_24_ALONE: Way = Way {
    depth: PeelDepth::Fixed24,
    ..TODAY
};
const FLOAT_DEPTH_KEPT: Way = Way {
    order: PeelOrder::KeepLayers,
    ..TODAY
};
const KEEP_LAYERS_24: Way = Way {
    order: PeelOrder::KeepLayers,
    sums: TextureFormat::Rgba32F,
    depth: PeelDepth::Fixed24,
};
const FP16_SUMS_24: Way = Way {
    order: PeelOrder::RunningSums,
    sums: TextureFormat::Rgba16F,
    depth: PeelDepth::Fixed24,
};

/// Mass properties of the whole body and of its part below `LEVEL`.
fn run(
    ctx: &crate::gl::Context,
    mesh: &crate::mesh::Mesh,
    resolution: u32,
    way: Way,
) -> anyhow::Result<[MassProperties; 2]> {
    let mut gpu = GpuMass::with_depth(ctx, resolution, way.sums, way.depth)?;
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
    let resolution = if opts.quick { 32 } else { 64 };
    let mesh = models::load(MODEL).map_err(anyhow::Error::msg)?;
    let analytic = [
        analytic::volume_integrals(&mesh),
        analytic::volume_integrals(&clip::below_plane(&mesh, LEVEL)),
    ]
    .map(|i| MassProperties::from_integrals(&i, 1.0));
    let framing = Framing::fit(&mesh, resolution).map_err(anyhow::Error::msg)?;
    let waters = [None, Some(LEVEL as f64)];
    let [merged_whole, merged_below] =
        waters.map(|w| cpu_reference::close_crossings(&mesh, &framing, w, 1.0));
    let mut out = PeriodResults::new(g70);

    let float_depth = under(ctx, g70, || run(ctx, &mesh, resolution, FLOAT_DEPTH_KEPT));
    out.step_from(
        "depth peeling with 32-bit float depth and a stencil bit (Sec. 3.2, 5.2), as built today",
        &float_depth,
        "fits",
    );
    let keep = under(ctx, g70, || run(ctx, &mesh, resolution, KEEP_LAYERS_24));
    match &keep {
        Ok(_) => out.step(
            "depth peeling, the period's way: 24-bit depth with stencil, each fragment compared \
             with the previous layer in whole steps of 2^-24 of the depth range",
            Verdict::PeriodsWay,
            format!(
                "surfaces within one step of each other are one layer (the farther is lost); \
                 the CPU model finds {merged_whole} such pixels of {MODEL} at \
                 {resolution}x{resolution}, {merged_below} below the water"
            ),
        ),
        Err(_) => out.step_from("depth peeling at 24 bits", &keep, ""),
    }
    let blended = under(ctx, g70, || run(ctx, &mesh, resolution, DEPTH_24_ALONE));
    out.step_from(
        "running sums of the peels by fp32 additive blending (this project's default)",
        &blended,
        "fits",
    );
    match &keep {
        Ok(_) => out.step(
            "the paper's order: the n layers T_1..T_n and T_w kept and each reduced (Sec. 3.3, 5.2)",
            Verdict::PeriodsWay,
            "no blending: every draw checked under the chip's limits",
        ),
        Err(_) => out.step_from("the paper's order", &keep, ""),
    }
    let fp16 = under(ctx, g70, || run(ctx, &mesh, resolution, FP16_SUMS_24));
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
    let depth_alone = run(ctx, &mesh, resolution, DEPTH_24_ALONE);
    for (k, what) in ["whole body", "part below z = 0.1 (buoyancy)"]
        .into_iter()
        .enumerate()
    {
        let row = |result: &anyhow::Result<[MassProperties; 2]>| match result {
            Ok(r) => format!("{:.3}%", error(&r[k], &analytic[k])),
            Err(e) => format!("refused: {e:#}"),
        };
        let today_error = error(&today[k], &analytic[k]);
        let merged = [merged_whole, merged_below][k];
        let depth_why = format!(
            "24-bit depth changes which fragments a peel keeps only where two surfaces lie \
             within one step (2^-24 of the depth range) of each other: {merged} such pixels \
             here, so the sums are the float peels' own"
        );
        for (way, result, why) in [
            (
                "24-bit depth alone (fp32 running sums, outside the profile)",
                &depth_alone,
                depth_why.as_str(),
            ),
            (
                "on the chip: 24-bit depth, kept layers",
                &keep,
                "24-bit depth as above, and the same sums in another order: fp32 rounding only",
            ),
            (
                "on the chip: 24-bit depth, running sums at fp16",
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
                format!("{today_error:.3}% (float depth, running sums, fp32)"),
                row(result),
                change,
            );
        }
    }
    Ok(out)
}
