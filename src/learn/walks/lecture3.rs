//! Lecture 3 walked: the max image pyramid ([`crate::lecture3::pyramid`]), the quadtree that
//! the lecture's pyramidal displacement mapping traces through and its light hierarchy is
//! searched like, built pass by pass and checked against the CPU.

use super::{panels_png, Check, Shot, Step, Walk};
use crate::gl::picture::{Panel, Scale};
use crate::gl::Context;
use crate::lecture3::pyramid::{cpu_pyramid, Extreme, PyramidBuilder};
use std::path::Path;

pub const WALK: Walk = Walk {
    id: "lecture3",
    title: "Lecture 3 walked: the image pyramid, level by level",
    source: "The tutorial's lecture 3 (Kyoung-Su Oh): the image pyramid of Oh, Ki & Lee, \
             \"Pyramidal displacement mapping\", ACM VRST 2006, as this project reconstructs it \
             from the published abstract (lecture3-sources.md).",
    run_is: "a 24 x 20 height image of three bumps, padded to 32 x 32, up to the 1 x 1 root",
    steps: STEPS,
    run,
};

const STEPS: &[Step] = &[
    Step {
        pass: "level 0: the image as a texture",
        section: "lecture 3, the image pyramid",
        step: "the height image uploaded as the pyramid's finest level, padded to a power of two",
        reads: "the image, on the CPU",
        writes: "mipmap level 0 of one R32F texture (the padding holds the identity of max, so \
                 it never wins)",
        code: &[("src/lecture3/pyramid.rs", "pyramid-upload")],
        lesson: "texture-is-array",
    },
    Step {
        pass: "levels 1 to the root",
        section: "lecture 3, the image pyramid",
        step: "each level from the one below: a node keeps the largest of its four children",
        reads: "the level below only (the texture's readable levels narrowed to it)",
        writes: "the next mipmap level of the same texture, one pass per level, down to one texel",
        code: &[
            ("src/lecture3/pyramid.rs", "pyramid-levels"),
            ("glsl/lecture3/pyramid_level.frag", "pyramid-level"),
        ],
        lesson: "reduction",
    },
];

/// The image of the small run.
const SIZE: (u32, u32) = (24, 20);

/// Three bumps of heights 0.5, 0.8 and 1 on a 24 x 20 grid, rows from the bottom.
pub fn image() -> Vec<f32> {
    let bumps = [(5.0, 6.0, 0.5), (16.0, 13.0, 0.8), (19.0, 4.0, 1.0)];
    let mut values = Vec::with_capacity((SIZE.0 * SIZE.1) as usize);
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let h = bumps
                .iter()
                .map(|&(cx, cy, top)| {
                    let d2 = (x as f32 - cx).powi(2) + (y as f32 - cy).powi(2);
                    top * (-d2 / 12.0).exp()
                })
                .fold(0.0f32, f32::max);
            values.push(h);
        }
    }
    values
}

fn run(ctx: &Context, dir: &Path) -> anyhow::Result<Vec<Shot>> {
    let values = image();
    let pyramid = PyramidBuilder::new(ctx)?.from_image(SIZE.0, SIZE.1, &values, Extreme::Max)?;
    let gpu = pyramid.read_levels()?;
    let cpu = cpu_pyramid(SIZE.0, SIZE.1, &values, Extreme::Max);
    // The padding's -f32::MAX would swamp the colour scale: drawn as the grey of zero.
    let shown: Vec<Vec<f32>> = gpu
        .iter()
        .map(|l| l.values.iter().map(|&v| v.max(0.0)).collect())
        .collect();
    let scale = Scale::of(shown.iter().map(Vec::as_slice));
    let panel = |k: usize| Panel {
        title: format!("level {k}, {} x {}", gpu[k].width, gpu[k].height),
        values: shown[k].clone(),
        width: gpu[k].width,
        height: gpu[k].height,
        scale,
    };
    let level0 = panels_png(dir, "level0.png", &[panel(0)])?;
    let above = (1..gpu.len())
        .map(|k| panels_png(dir, &format!("level{k}.png"), &[panel(k)]))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let wrong: usize = gpu
        .iter()
        .zip(&cpu)
        .map(|(g, c)| {
            if g.values.len() != c.values.len() {
                return g.values.len().max(c.values.len());
            }
            g.values
                .iter()
                .zip(&c.values)
                .filter(|(a, b)| a != b)
                .count()
        })
        .sum::<usize>()
        + gpu.len().abs_diff(cpu.len());
    let nodes: usize = cpu.iter().map(|l| l.values.len()).sum();
    let key = "height, one scale for every level (0 grey to the highest bump pale yellow), row 0 \
               at the bottom; the padding right and above the 24 x 20 image drawn grey";
    Ok(vec![
        Shot {
            pictures: vec![level0],
            key: key.into(),
            check: None,
        },
        Shot {
            pictures: above,
            key: format!("{key}; each node the largest height below it"),
            check: Some(Check {
                what: format!(
                    "every level against the CPU's pyramid (max of four, in f32): {wrong} of \
                     {nodes} nodes differ (tolerance: none, max is exact)"
                ),
                passed: wrong == 0,
            }),
        },
    ])
}
