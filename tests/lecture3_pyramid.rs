//! Lecture 3, technique 1: the max/min image pyramid drawn by render passes against the CPU
//! pyramid, on images the tests make and on the shipped height map. Max and min are exact in
//! fp32, so the tolerance is zero: every level must be equal bit for bit.

use classic_gpgpu::lecture3::height_map::{HeightMap, SHIPPED_PATH, SHIPPED_SIZE};
use classic_gpgpu::lecture3::pyramid::{cpu_pyramid, level_count, Extreme, PyramidBuilder};
use common::context;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::Path;

mod common;

fn random_image(rng: &mut impl Rng, w: u32, h: u32) -> Vec<f32> {
    (0..w * h).map(|_| rng.gen_range(-100.0..100.0)).collect()
}

#[test]
fn gpu_pyramid_equals_cpu_pyramid_exactly() {
    let ctx = context();
    let builder = PyramidBuilder::new(&ctx).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(2006);
    for (w, h) in [
        (1, 1),
        (2, 2),
        (5, 3),
        (16, 16),
        (37, 64),
        (100, 7),
        (1, 9),
        (64, 33),
    ] {
        let image = random_image(&mut rng, w, h);
        for extreme in [Extreme::Max, Extreme::Min] {
            let cpu = cpu_pyramid(w, h, &image, extreme);
            assert_eq!(cpu.len() as u32, level_count(w, h));
            let gpu = builder
                .from_image(w, h, &image, extreme)
                .unwrap()
                .read_levels()
                .unwrap();
            assert_eq!(gpu.len(), cpu.len(), "{w}x{h} {extreme:?}: levels");
            for (level, (g, c)) in gpu.iter().zip(&cpu).enumerate() {
                assert_eq!(
                    (g.width, g.height),
                    (c.width, c.height),
                    "{w}x{h} {extreme:?} level {level}: size"
                );
                let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&g.values),
                    bits(&c.values),
                    "{w}x{h} {extreme:?} level {level}"
                );
            }
        }
    }
}

#[test]
fn the_root_is_the_extreme_of_the_image_and_every_node_bounds_its_children() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (w, h) = (23, 11);
    let image = random_image(&mut rng, w, h);
    let max = cpu_pyramid(w, h, &image, Extreme::Max);
    let min = cpu_pyramid(w, h, &image, Extreme::Min);
    let top = |levels: &[classic_gpgpu::lecture3::pyramid::Level]| {
        let root = levels.last().unwrap();
        assert_eq!((root.width, root.height), (1, 1));
        root.values[0]
    };
    assert_eq!(top(&max), image.iter().cloned().fold(f32::MIN, f32::max));
    assert_eq!(top(&min), image.iter().cloned().fold(f32::MAX, f32::min));
    // Every pixel of the image lies under the max and over the min of each of its ancestors.
    for (i, &v) in image.iter().enumerate() {
        let (x, y) = (i as u32 % w, i as u32 / w);
        for k in 0..max.len() as u32 {
            let (lx, ly) = (
                (x >> k).min(max[k as usize].width - 1),
                (y >> k).min(max[k as usize].height - 1),
            );
            assert!(max[k as usize].at(lx, ly) >= v);
            assert!(min[k as usize].at(lx, ly) <= v);
        }
    }
}

#[test]
fn the_shipped_height_map_is_the_generated_one() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(SHIPPED_PATH);
    let loaded = HeightMap::load(&path, 16384).unwrap();
    assert_eq!(loaded, HeightMap::generated(SHIPPED_SIZE));
    // And its pyramid on the GPU is the CPU's.
    let ctx = context();
    let builder = PyramidBuilder::new(&ctx).unwrap();
    let (w, h) = (loaded.width(), loaded.height());
    let gpu = builder
        .from_image(w, h, loaded.heights(), Extreme::Max)
        .unwrap()
        .read_levels()
        .unwrap();
    assert_eq!(gpu, cpu_pyramid(w, h, loaded.heights(), Extreme::Max));
}

/// The mean of the image pixels under node (x, y) of level `level`, from the image alone.
fn direct_mean(image: &[f32], w: u32, h: u32, level: u32, x: u32, y: u32) -> Option<f64> {
    let (pw, ph) = (w.next_power_of_two(), h.next_power_of_two());
    let (lw, lh) = ((pw >> level).max(1), (ph >> level).max(1));
    let (sx, sy) = (pw / lw, ph / lh);
    let pixels: Vec<f64> = (y * sy..((y + 1) * sy).min(h))
        .flat_map(|py| (x * sx..((x + 1) * sx).min(w)).map(move |px| (px, py)))
        .map(|(px, py)| image[(py * w + px) as usize] as f64)
        .collect();
    (!pixels.is_empty()).then(|| pixels.iter().sum::<f64>() / pixels.len() as f64)
}

/// The mean pyramid: every node the mean of the image pixels it covers, odd sizes included
/// (a node on the edge of an odd level averages only the pixels it has), on the CPU from the
/// image directly and on the GPU level from level. Tolerance: each GPU level rounds one
/// weighted mean of four fp32 values (a few units in the last place of the largest |value|),
/// so after L levels 4 L eps max|v|.
#[test]
fn the_mean_pyramid_averages_the_pixels_each_node_covers() {
    let ctx = context();
    let builder = PyramidBuilder::new(&ctx).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(1987);
    for (w, h) in [
        (1, 1),
        (2, 2),
        (5, 3),
        (7, 7),
        (16, 16),
        (37, 64),
        (100, 7),
        (1, 9),
    ] {
        let image = random_image(&mut rng, w, h);
        let cpu = cpu_pyramid(w, h, &image, Extreme::Mean);
        let biggest = image.iter().fold(0f32, |m, v| m.max(v.abs())) as f64;
        let tol = 4.0 * cpu.len() as f64 * f32::EPSILON as f64 * biggest;
        let gpu = builder
            .from_image(w, h, &image, Extreme::Mean)
            .unwrap()
            .read_levels()
            .unwrap();
        assert_eq!(gpu.len(), cpu.len(), "{w}x{h}: levels");
        for (level, (g, c)) in gpu.iter().zip(&cpu).enumerate() {
            assert_eq!(
                (g.width, g.height),
                (c.width, c.height),
                "{w}x{h} level {level}"
            );
            for y in 0..c.height {
                for x in 0..c.width {
                    let what = format!("{w}x{h} level {level} node ({x}, {y})");
                    let direct = direct_mean(&image, w, h, level as u32, x, y);
                    // The CPU pyramid is the direct mean (0 where a node covers nothing).
                    assert!(
                        (c.at(x, y) as f64 - direct.unwrap_or(0.0)).abs()
                            <= f32::EPSILON as f64 * biggest,
                        "{what}: CPU {} vs {direct:?}",
                        c.at(x, y)
                    );
                    assert!(
                        (g.at(x, y) as f64 - c.at(x, y) as f64).abs() <= tol,
                        "{what}: GPU {} vs CPU {} (tolerance {tol:.1e})",
                        g.at(x, y),
                        c.at(x, y)
                    );
                }
            }
        }
        // The root is the image's mean.
        let mean = image.iter().map(|&v| v as f64).sum::<f64>() / image.len() as f64;
        let root = gpu.last().unwrap().values[0] as f64;
        assert!(
            (root - mean).abs() <= tol,
            "{w}x{h}: root {root} vs mean {mean}"
        );
    }
}
