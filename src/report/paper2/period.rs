//! Paper 2 on its own GPU, the GeForce 7800 GTX: a small crowd drawn with the paper's
//! two-pass skinning and with the vertex-shader baseline, under the chip's limits and
//! today, and the two pictures compared pixel by pixel.

use crate::crowd::compute::ComputeCrowd;
use crate::crowd::{scene, CharacterModel, CrowdRenderer, Method, ModelKind};
use crate::gl::{period, Context};
use crate::report::period::{under, PeriodResults, Verdict};
use crate::report::BenchOptions;

const CHARACTERS: usize = 16;
const SIZE: (u32, u32) = (160, 120);

/// One frame of `CHARACTERS` soldiers with `method`, as RGBA bytes.
fn frame(ctx: &Context, method: Method) -> anyhow::Result<Vec<u8>> {
    let model = CharacterModel::build(ModelKind::Soldier)?;
    let mut renderer = CrowdRenderer::new(ctx, model)?;
    let target = scene::scene_target(ctx, SIZE.0, SIZE.1)?;
    let aspect = SIZE.0 as f32 / SIZE.1 as f32;
    let mut crowd = scene::table1_scene(ModelKind::Soldier, CHARACTERS, aspect, 7);
    scene::run(
        ctx,
        &mut renderer,
        &target,
        &mut crowd,
        method,
        1,
        1.0 / 30.0,
    )?;
    Ok(target.color(0).download_u8()?)
}

/// Pixels that differ, and the largest difference of a channel.
fn difference(a: &[u8], b: &[u8]) -> (usize, u8) {
    let pixels = a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p != q).count();
    let largest = a.iter().zip(b).map(|(p, q)| p.abs_diff(*q)).max();
    (pixels, largest.unwrap_or(0))
}

pub fn measure(opts: &BenchOptions) -> anyhow::Result<PeriodResults> {
    let ctx = opts.gl;
    let gpu = period::for_paper(2);
    let mut out = PeriodResults::new(gpu);
    let pixels = (SIZE.0 * SIZE.1) as usize;
    for (method, step, detail) in [
        (
            Method::TwoPass,
            "two-pass skinning: pixel-shader skinning into RGBA32F render targets, copy to a \
             VBO through a PBO, drawing pass (Sec. 2)",
            "the picture's z-buffer at 24 bits, the period's way (the chip had no float depth; \
             today's is 32-bit float); the rest fits as built: RGBA32F vertex and bone \
             textures read by the pixel shader (nearest), two render targets, no float \
             blending",
        ),
        (
            Method::VertexShader,
            "the baseline: vertex-shader skinning with bone matrices in uniforms (Table 1)",
            "the z-buffer at 24 bits, the period's way; bone matrices in uniforms fit",
        ),
    ] {
        let today = frame(ctx, method)?;
        let period_run = under(ctx, gpu, || frame(ctx, method));
        match &period_run {
            Ok(_) => out.step(step, Verdict::PeriodsWay, detail),
            Err(_) => out.step_from(step, &period_run, detail),
        }
        let (period_text, change) = match &period_run {
            Ok(image) => {
                let (differ, largest) = difference(&today, image);
                (
                    format!("{differ} of {pixels} pixels differ (largest {largest}/255)"),
                    if differ == 0 {
                        "none: skinning is fp32 on both (the paper stores RGBA 32-bit floats \
                         for the sake of accuracy), and the 24-bit z-buffer decides every \
                         visible surface as the float one does here"
                            .to_string()
                    } else {
                        format!(
                            "{differ} pixels: where two surfaces lie closer than the 24-bit \
                             z-buffer resolves, the other one wins"
                        )
                    },
                )
            }
            Err(e) => (
                format!("refused: {e:#}"),
                "the period run was refused".into(),
            ),
        };
        out.compare(
            &format!(
                "{} frame, {CHARACTERS} soldiers at {}x{}, against today's",
                method.name(),
                SIZE.0,
                SIZE.1
            ),
            "reference".into(),
            period_text,
            change,
        );
    }
    let compute = under(ctx, gpu, || {
        ComputeCrowd::new(ctx, CharacterModel::build(ModelKind::Soldier)?)
            .map_err(anyhow::Error::from)
    });
    out.step_from(
        "today's counterpart: compute-shader skinning (not the paper's)",
        &compute.map(|_| ()),
        "fits",
    );
    Ok(out)
}
