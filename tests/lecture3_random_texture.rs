//! Lecture 3, technique 5: random numbers into a texture. The GPU generators must equal the
//! CPU generator bit for bit (integer arithmetic: no tolerance), and their numbers must pass
//! a chi-square test of uniformity (64 bins) and tests of serial correlation (each texel's
//! successive numbers) and spatial correlation (neighbouring texels at the same step), all at
//! the 0.1% level (normal quantile 3.29 two-sided, 3.09 one-sided for chi-square). The seeds
//! are fixed, so the outcome is too; a deliberately bad generator shows the tests can fail.

use classic_gpgpu::lecture3::random_texture::statistics::{
    chi_square, chi_square_critical, correlation, correlation_bound,
};
use classic_gpgpu::lecture3::random_texture::{HybridTaus, RandomTexture};
use common::context;

mod common;

const SEED: u64 = 2007;

#[test]
fn gpu_generators_equal_the_cpu_generator_bit_for_bit() {
    let ctx = context();
    let (w, h) = (13, 7);
    let gpu = RandomTexture::new(&ctx, w, h, SEED).unwrap();
    let mut cpu: Vec<HybridTaus> = (0..(w * h) as u64)
        .map(|i| HybridTaus::seeded(SEED, i))
        .collect();
    let seeds: Vec<u32> = cpu.iter().flat_map(|g| g.z).collect();
    assert_eq!(gpu.states().unwrap(), seeds);
    for step in 1..=20 {
        gpu.step().unwrap();
        let values: Vec<u32> = cpu.iter_mut().map(|g| g.next_f32().to_bits()).collect();
        let gpu_values: Vec<u32> = gpu.values().unwrap().iter().map(|v| v.to_bits()).collect();
        assert_eq!(gpu_values, values, "step {step}: numbers");
        let states: Vec<u32> = cpu.iter().flat_map(|g| g.z).collect();
        assert_eq!(gpu.states().unwrap(), states, "step {step}: states");
    }
}

/// Every test at the 0.1% level on `streams[texel][step]` laid out `width` texels a row.
fn assert_random(streams: &[Vec<f32>], width: usize, what: &str) {
    let all: Vec<f32> = streams.iter().flatten().copied().collect();
    let bins = 64;
    let chi2 = chi_square(&all, bins);
    let critical = chi_square_critical((bins - 1) as f64, 3.09);
    assert!(chi2 < critical, "{what}: chi-square {chi2} >= {critical}");
    let serial: Vec<(f32, f32)> = streams
        .iter()
        .flat_map(|s| s.windows(2).map(|p| (p[0], p[1])))
        .collect();
    let r = correlation(&serial);
    let bound = correlation_bound(serial.len(), 3.29);
    assert!(
        r.abs() < bound,
        "{what}: serial correlation {r} (bound {bound})"
    );
    let steps = streams[0].len();
    let spatial: Vec<(f32, f32)> = (0..streams.len())
        .filter(|i| (i + 1) % width != 0)
        .flat_map(|i| (0..steps).map(move |t| (i, t)))
        .map(|(i, t)| (streams[i][t], streams[i + 1][t]))
        .collect();
    let r = correlation(&spatial);
    let bound = correlation_bound(spatial.len(), 3.29);
    assert!(
        r.abs() < bound,
        "{what}: neighbour correlation {r} (bound {bound})"
    );
}

#[test]
fn the_numbers_are_uniform_and_independent() {
    let ctx = context();
    let (w, h, steps) = (64, 64, 12);
    let gpu = RandomTexture::new(&ctx, w, h, SEED).unwrap();
    let mut streams = vec![Vec::with_capacity(steps); (w * h) as usize];
    for _ in 0..steps {
        gpu.step().unwrap();
        for (s, v) in streams.iter_mut().zip(gpu.values().unwrap()) {
            s.push(v);
        }
    }
    assert_random(&streams, w as usize, "GPU hybrid Tausworthe");
}

#[test]
#[should_panic(expected = "neighbour correlation")]
fn the_tests_catch_a_generator_seeded_with_consecutive_integers() {
    // A plain LCG per texel seeded with the texel index: each stream alone looks uniform, but
    // neighbouring texels run in lockstep.
    let (w, h, steps) = (64, 64, 12);
    let streams: Vec<Vec<f32>> = (0..w * h)
        .map(|i: u32| {
            let mut z = i;
            (0..steps)
                .map(|_| {
                    z = z.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                    (z >> 8) as f32 / 16_777_216.0
                })
                .collect()
        })
        .collect();
    assert_random(&streams, w as usize, "consecutive LCG seeds");
}

#[test]
fn a_texture_beyond_the_limit_is_refused() {
    let ctx = context();
    let max = ctx.info().limits.max_texture_size;
    let err = RandomTexture::new(&ctx, max + 1, 1, SEED)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("--size") && err.contains(&max.to_string()),
        "{err}"
    );
}
