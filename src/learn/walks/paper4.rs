//! Paper 4 walked (Kim, Kim, Ko & Terzopoulos 2006): the mass properties of a torus at 32 x 32
//! pixels, peel by peel, then the sums.

use super::{buffer_png, Check, Shot, Step, Walk};
use crate::gl::Context;
use crate::mass::gpu::GpuMass;
use crate::mass::integrands::{CHANNELS, TARGETS};
use crate::mass::reduce::Accumulator;
use std::path::Path;

pub const WALK: Walk = Walk {
    id: "paper4",
    title: "Paper 4 walked: mass properties by depth peeling",
    source: "Kim, Kim, Ko & Terzopoulos, \"Fast GPU computation of the mass properties of a \
             general shape and its application to buoyancy simulation\", The Visual Computer \
             22(8), 2006, sections 3.1 to 3.3.",
    run_is: "the paper's torus framed in 32 x 32 pixels, the resolution the paper found enough",
    steps: STEPS,
    run,
};

/// The framebuffer side of the small run.
pub const RESOLUTION: u32 = 32;

const STEPS: &[Step] = &[
    Step {
        pass: "peel 1: the nearest layer and its integrands",
        section: "Sec. 3.1 and 3.2",
        step: "the integrands of each pixel's column, written to three render targets",
        reads: "the body's triangles, seen from above, nearest fragment kept by the depth test",
        writes: "three RGBA32F targets: rx, ry, rz, V (eq. 4), then Ixx, Ixy, Ixz and Iyy, Iyz, \
                 Izz (eq. 6), each signed by the way its surface faces",
        code: &[
            ("src/mass/peel.rs", "peel-pass"),
            ("glsl/mass/peel_main.frag", "peel-main"),
        ],
        lesson: "several-outputs",
    },
    Step {
        pass: "peels 2 to n: the layers behind",
        section: "Sec. 3.2",
        step:
            "depth peeling: each pass keeps the fragments behind the depth the previous pass kept",
        reads: "the triangles again, and the previous peel's depth texture",
        writes: "the same three targets for the next layer; peeling stops when a layer draws \
                 nothing (an occlusion query) or no pixel met a further surface",
        code: &[("glsl/mass/peel_main.frag", "peel-main")],
        lesson: "depth-peeling",
    },
    Step {
        pass: "add each peel into the running sums",
        section: "Sec. 3.3",
        step: "the integrands of all layers summed per pixel (additive blending)",
        reads: "a peel's three targets and its depth (pixels it did not reach are skipped)",
        writes: "three running-sum targets, the same size",
        code: &[
            ("src/mass/reduce.rs", "add-peel"),
            ("glsl/mass/accumulate.frag", "accumulate"),
        ],
        lesson: "scatter-and-blend",
    },
    Step {
        pass: "reduction to one sum per integrand",
        section: "Sec. 3.3",
        step: "the sum of the integrands over the pixels by reduction",
        reads: "the running sums",
        writes: "a smaller target per pass (ping-pong), each texel the sum of a block, down to \
                 one texel per target, read back as the ten integrals",
        code: &[
            ("src/mass/reduce.rs", "reduce-passes"),
            ("glsl/mass/reduce_sum.frag", "reduce-sum"),
        ],
        lesson: "reduction",
    },
];

/// The side of a block of the reduction shown (32 / 4 = 8 texels a side).
const BLOCK: u32 = 4;

fn run(ctx: &Context, dir: &Path) -> anyhow::Result<Vec<Shot>> {
    let mesh = crate::mass::models::load("torus").map_err(anyhow::Error::msg)?;
    let gpu = GpuMass::new(ctx, RESOLUTION)?;
    gpu.peeler().set_capture(true);
    let result = gpu.integrate(&mesh, None, None);
    let peels = gpu.peeler().take_captured();
    gpu.peeler().set_capture(false);
    let result = result?;
    anyhow::ensure!(!peels.is_empty(), "the torus drew no peel");
    let dims = (RESOLUTION, RESOLUTION);
    let mut shots = Vec::new();

    // Peel 1, all three targets.
    let first = &peels[0];
    let pictures = (0..TARGETS)
        .map(|t| {
            buffer_png(
                dir,
                &format!("peel1_target{t}.png"),
                "peel 1",
                &first.targets[t],
                4,
                CHANNELS[t],
                dims,
            )
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    shots.push(Shot {
        pictures,
        key: "one panel per channel, row 0 at the bottom; blue below zero, red to yellow above, \
              grey zero where the peel reached no surface; each panel on its own scale"
            .into(),
        check: None,
    });

    // The later peels: the first target (the volume integrands) of each.
    let pictures = peels[1..]
        .iter()
        .enumerate()
        .map(|(k, peel)| {
            buffer_png(
                dir,
                &format!("peel{}_target0.png", k + 2),
                &format!("peel {}", k + 2),
                &peel.targets[0],
                4,
                CHANNELS[0],
                dims,
            )
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    shots.push(Shot {
        pictures,
        key: format!(
            "{} peels in all; target 0 of each later peel (rx, ry, rz, V), same colours as peel \
             1; a surface facing up counts negative, one facing down positive, so each pixel's \
             column of layers adds up to the solid between them",
            result.peels
        ),
        check: None,
    });

    // The running sums: the peels added (here on the CPU, from the captured peels, since the
    // peeler keeps its own sums), uploaded into an accumulator to be reduced on the GPU.
    let sums: Vec<Vec<f32>> = (0..TARGETS)
        .map(|t| {
            let mut sum = vec![0f32; first.targets[t].len()];
            for peel in &peels {
                for (s, v) in sum.iter_mut().zip(&peel.targets[t]) {
                    *s += v;
                }
            }
            sum
        })
        .collect();
    shots.push(Shot {
        pictures: vec![buffer_png(
            dir,
            "sums_target0.png",
            "running sums",
            &sums[0],
            4,
            CHANNELS[0],
            dims,
        )?],
        key: "target 0 of the running sums after the last peel (rx, ry, rz, V): each pixel's \
              column integrated through the body; drawn from the captured peels added on the \
              CPU, the values the blended pass leaves"
            .into(),
        check: None,
    });

    // The reduction on the GPU, over those sums.
    let accumulator = Accumulator::new(ctx, RESOLUTION, RESOLUTION)?;
    for (texture, sum) in accumulator.sums().iter().zip(&sums) {
        texture.upload_f32(sum)?;
    }
    let blocks = accumulator.reduce(Some(BLOCK))?;
    let side = RESOLUTION / BLOCK;
    let block_v: Vec<f32> = blocks.iter().flat_map(|b| b[0].map(|v| v as f32)).collect();
    let total = accumulator.reduce(None)?;
    let cpu_total: f64 = sums[0].iter().skip(3).step_by(4).map(|&v| v as f64).sum();
    let gpu_total = total[0][0][3];
    let error = (gpu_total - cpu_total).abs() / cpu_total.abs().max(1e-30);
    shots.push(Shot {
        pictures: vec![buffer_png(
            dir,
            "reduced_4x4.png",
            &format!("sums of {BLOCK}x{BLOCK} blocks"),
            &block_v,
            4,
            CHANNELS[0],
            (side, side),
        )?],
        key: format!(
            "the reduction part way: each texel the sum of a {BLOCK}x{BLOCK} block of the \
             running sums ({side} x {side} texels); further passes end at one texel per target"
        ),
        check: Some(Check {
            what: format!(
                "the GPU's reduced V ({gpu_total:.6}) against the CPU's sum of the same texels \
                 ({cpu_total:.6}): relative difference {error:.1e} (tolerance 1e-5, fp32 \
                 additions in another order)"
            ),
            passed: error <= 1e-5,
        }),
    });
    Ok(shots)
}
