//! The section's pictures (the tutorial's first debugging tip: look at the intermediate
//! data): the pyramid levels, displacement-mapped frames and their verdicts against the
//! exact tracer, the indirect lighting, the random numbers, the depth-masked picture.

use crate::gl::dump::{frames_png, picture_png};
use crate::gl::picture::{Panel, Scale};
use crate::gl::Context;
use crate::lecture3::displacement::compare::Verdict;
use crate::lecture3::displacement::{Camera, DisplacementRenderer, Method};
use crate::lecture3::light_hierarchy::shade::Terms;
use crate::lecture3::light_hierarchy::IndirectLighting;
use crate::lecture3::pyramid::{Extreme, Level, PyramidBuilder};
use crate::lecture3::pyramid_atlas::atlas_layout;
use crate::lecture3::HeightMap;
use crate::report::BenchOptions;
use std::path::Path;

pub const PYRAMID_PNG: &str = "lecture3_pyramid.png";
pub const ORBIT_PNG: &str = "lecture3_displacement_orbit.png";
pub const GRAZING_PNG: &str = "lecture3_displacement_grazing.png";
pub const LIGHT_PNG: &str = "lecture3_indirect_light.png";
pub const RANDOM_PNG: &str = "lecture3_random.png";
pub const DEPTH_MASK_PNG: &str = "lecture3_depth_mask.png";

/// An RGBA8 image, rows from the bottom (as GL reads them).
pub struct Rgba {
    pub width: u32,
    pub height: u32,
    pub data: Vec<u8>,
}

impl Rgba {
    pub fn new(width: u32, height: u32) -> Rgba {
        Rgba {
            width,
            height,
            data: vec![0; (width * height * 4) as usize],
        }
    }

    fn put(&mut self, x: u32, y: u32, pixel: [u8; 4]) {
        let i = ((y * self.width + x) * 4) as usize;
        self.data[i..i + 4].copy_from_slice(&pixel);
    }

    /// `other` copied with its bottom-left corner at (x, y).
    fn paste(&mut self, other: &Rgba, x: u32, y: u32) {
        for row in 0..other.height {
            for col in 0..other.width {
                let i = ((row * other.width + col) * 4) as usize;
                let p = [
                    other.data[i],
                    other.data[i + 1],
                    other.data[i + 2],
                    other.data[i + 3],
                ];
                self.put(x + col, y + row, p);
            }
        }
    }

    /// Images side by side, `gap` pixels apart.
    pub fn row(images: &[Rgba], gap: u32) -> Rgba {
        let width = images.iter().map(|i| i.width + gap).sum::<u32>() - gap;
        let height = images.iter().map(|i| i.height).max().unwrap_or(1);
        let mut out = Rgba::new(width, height);
        let mut x = 0;
        for image in images {
            out.paste(image, x, 0);
            x += image.width + gap;
        }
        out
    }

    /// Images stacked, the first on top.
    pub fn column(images: &[Rgba], gap: u32) -> Rgba {
        let height = images.iter().map(|i| i.height + gap).sum::<u32>() - gap;
        let width = images.iter().map(|i| i.width).max().unwrap_or(1);
        let mut out = Rgba::new(width, height);
        let mut y = height;
        for image in images {
            y -= image.height;
            out.paste(image, 0, y);
            y = y.saturating_sub(gap);
        }
        out
    }

    /// As an image, top row first.
    pub fn to_image(&self) -> image::RgbaImage {
        let rows: Vec<u8> = self
            .data
            .chunks_exact(self.width as usize * 4)
            .rev()
            .flatten()
            .copied()
            .collect();
        image::RgbaImage::from_raw(self.width, self.height, rows).expect("4 bytes a pixel")
    }

    /// Written as PNG, top row first.
    pub fn save(&self, path: &Path) -> anyhow::Result<()> {
        Ok(crate::gl::dump::rgba_png(
            &self.data,
            (self.width, self.height),
            path,
        )?)
    }
}

/// Pyramids of one `image`-sized picture (as read back from the GPU), each laid out as its
/// atlas (level 0, the levels above in a column to its right) in a panel of its own, all on
/// one colour key from 0 to 1; the atlas's empty area and the nodes that cover no image pixel
/// (padding to a power of two) are left at 0, the neutral grey.
pub fn pyramid_png(pyramids: &[Vec<Level>], image: (u32, u32), path: &Path) -> anyhow::Result<()> {
    let names = ["max", "min", "mean"];
    let panels: Vec<Panel> = pyramids
        .iter()
        .enumerate()
        .map(|(k, levels)| {
            let sizes: Vec<_> = levels.iter().map(|l| (l.width, l.height)).collect();
            let ((aw, ah), offsets) = atlas_layout(&sizes);
            let (pw, ph) = sizes.first().copied().unwrap_or((1, 1));
            let mut values = vec![0.0f32; (aw * ah) as usize];
            for (level, &(ox, oy)) in levels.iter().zip(&offsets) {
                let (sx, sy) = (pw / level.width, ph / level.height);
                for (i, &v) in level.values.iter().enumerate() {
                    let (x, y) = (i as u32 % level.width, i as u32 / level.width);
                    let padding = x * sx >= image.0 || y * sy >= image.1;
                    if !padding {
                        values[((oy + y) * aw + ox + x) as usize] = v;
                    }
                }
            }
            Panel {
                title: format!(
                    "{} pyramid: level 0, levels 1.. to its right",
                    names.get(k).unwrap_or(&"")
                ),
                values,
                width: aw,
                height: ah,
                scale: Scale::fixed(0.0, 1.0),
            }
        })
        .collect();
    let width = panels.iter().map(|p| p.width).sum::<u32>();
    let side = (1200 / width.max(1)).max(1);
    let height = panels.iter().map(|p| p.height).max().unwrap_or(1) * side + 120;
    Ok(picture_png(&panels, (1200, height), path)?)
}

/// The pyramids [`pyramid_png`] draws: max, min and mean of `map`, drawn on the GPU and read
/// back.
pub fn gpu_pyramids(ctx: &Context, map: &HeightMap) -> anyhow::Result<Vec<Vec<Level>>> {
    let builder = PyramidBuilder::new(ctx)?;
    PYRAMID_KINDS
        .iter()
        .map(|&extreme| {
            Ok(builder
                .from_image(map.width(), map.height(), map.heights(), extreme)?
                .read_levels()?)
        })
        .collect()
}

/// The pyramids of the picture, left to right.
pub const PYRAMID_KINDS: [Extreme; 3] = [Extreme::Max, Extreme::Min, Extreme::Mean];

/// A frame of one method and its verdicts against the exact tracer.
pub struct JudgedFrame {
    pub method: String,
    /// RGBA8, rows from the bottom.
    pub colour: Vec<u8>,
    pub verdicts: Vec<Verdict>,
}

/// The verdicts' colours and meanings, as the grazing picture's legend says them.
const VERDICT_COLOURS: [([u8; 4], &str); 7] = [
    (
        [150, 150, 150, 255],
        "exact hit (the frame's own colour, in grey)",
    ),
    ([230, 30, 30, 255], "wrong surface"),
    ([255, 160, 0, 255], "outside tolerance"),
    ([40, 90, 255, 255], "ill-conditioned"),
    ([200, 0, 200, 255], "wall drawn for surface, or the reverse"),
    ([0, 190, 120, 255], "wrong normal or colour"),
    ([0, 0, 0, 255], "not compared (background)"),
];

/// The verdicts as colours: exact hits grey, wrong surface red, outside tolerance orange,
/// ill-conditioned blue, wall drawn for surface (or the reverse) magenta, wrong normal or
/// colour green, not compared black.
fn verdict_picture(frame: &JudgedFrame, side: u32) -> Rgba {
    let mut out = Rgba::new(side, side);
    for (i, v) in frame.verdicts.iter().enumerate() {
        let c = &frame.colour[4 * i..4 * i + 4];
        let grey = ((c[0] as u32 + c[1] as u32 + c[2] as u32) / 6) as u8;
        let pixel = match v {
            Verdict::NotCompared => VERDICT_COLOURS[6].0,
            Verdict::Exact => [grey, grey, grey, 255],
            Verdict::WrongSurface => VERDICT_COLOURS[1].0,
            Verdict::OutsideTolerance => VERDICT_COLOURS[2].0,
            Verdict::Ambiguous => VERDICT_COLOURS[3].0,
            Verdict::WrongKind => VERDICT_COLOURS[4].0,
            Verdict::WrongShading => VERDICT_COLOURS[5].0,
        };
        out.put(i as u32 % side, i as u32 / side, pixel);
    }
    out
}

/// The whole factor that shows a `side`-pixel frame at about 300 pixels.
fn enlargement(side: u32) -> u32 {
    (300 / side.max(1)).max(1)
}

/// The grazing view: each method's frame above its verdict map, every panel titled, the
/// verdicts' colours in a legend.
pub fn grazing_png(opts: &BenchOptions, frames: &[JudgedFrame], side: u32) -> anyhow::Result<()> {
    let mut panels = Vec::new();
    for f in frames {
        let colour = Rgba {
            width: side,
            height: side,
            data: f.colour.clone(),
        };
        panels.push((format!("{}: frame", f.method), colour.to_image()));
    }
    for f in frames {
        panels.push((
            format!("{}: verdicts", f.method),
            verdict_picture(f, side).to_image(),
        ));
    }
    let legend: Vec<([u8; 4], String)> = VERDICT_COLOURS
        .iter()
        .map(|&(c, t)| (c, t.to_string()))
        .collect();
    Ok(frames_png(
        &panels,
        frames.len(),
        enlargement(side),
        &legend,
        &opts.out_dir.join(GRAZING_PNG),
    )?)
}

/// Four frames of the camera orbiting the box (pyramid traversal).
pub fn orbit_png(
    opts: &BenchOptions,
    renderer: &DisplacementRenderer,
    side: u32,
) -> anyhow::Result<()> {
    let target = renderer.target(side, side)?;
    let frames = [20.0f32, 110.0, 200.0, 290.0]
        .iter()
        .map(|&azimuth| {
            let camera = Camera::orbit(
                renderer.surface().centre(),
                super::scene::DISTANCE,
                azimuth,
                35.0,
                side,
                side,
            );
            renderer.render(&target, &camera, Method::Pyramid)?;
            let frame = Rgba {
                width: side,
                height: side,
                data: renderer.read(&target)?.colour,
            };
            Ok((format!("azimuth {azimuth} degrees"), frame.to_image()))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    Ok(frames_png(
        &frames,
        4,
        enlargement(side),
        &[],
        &opts.out_dir.join(ORBIT_PNG),
    )?)
}

fn shaded(lighting: &IndirectLighting, terms: Terms) -> anyhow::Result<Rgba> {
    lighting.shade(terms, 1.5)?;
    let fb = &lighting.shade.target;
    Ok(Rgba {
        width: fb.width(),
        height: fb.height(),
        data: fb.read_u8(0, crate::gl::Rect::sized(fb.width(), fb.height()))?,
    })
}

/// Direct + indirect and indirect alone, of the brute-force gather now in `lighting`'s
/// target.
pub fn brute_force_pictures(lighting: &IndirectLighting) -> anyhow::Result<[Rgba; 2]> {
    Ok([
        shaded(lighting, Terms::Both)?,
        shaded(lighting, Terms::Indirect)?,
    ])
}

/// The brute-force pictures ([`brute_force_pictures`]) beside indirect light alone with the
/// coarsest criterion of the plot, the last of [`super::scene::THETAS`]: the gather that
/// [`super::bench::light_run`] leaves in `lighting`'s target (its last timed run).
pub fn light_png(
    opts: &BenchOptions,
    lighting: &IndirectLighting,
    brute_force: [Rgba; 2],
) -> anyhow::Result<()> {
    let coarse = shaded(lighting, Terms::Indirect)?;
    let [both, indirect] = brute_force;
    let frames = [
        ("direct + indirect, brute force", both),
        ("indirect alone, brute force", indirect),
        ("indirect alone, coarsest criterion", coarse),
    ]
    .map(|(title, frame)| (title.to_string(), frame.to_image()));
    let side = frames[0].1.width().max(frames[0].1.height());
    Ok(frames_png(
        &frames,
        3,
        enlargement(side),
        &[],
        &opts.out_dir.join(LIGHT_PNG),
    )?)
}
