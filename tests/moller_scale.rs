//! Where Möller's floating-point triangle test stops agreeing with the exact predicate, by
//! coordinate scale: the measurement behind the `--predicate moller` warning
//! (`classic_gpgpu::collide::tri_test::MOLLER_SAFE_SCALES`).
//!
//! The same random triangle pairs (centres in a unit cube, sides about 0.6) are scaled by 10^(k/4) for every quarter decade of f32's range;
//! at each scale Möller's test is compared with the exact predicate on the same f32 input.
//! Run with `--nocapture` for the table. Measured (4000 pairs a scale, 86 of them
//! intersecting): no disagreement while the largest coordinate lies within 1.3e-24..1.3e24;
//! at 2.3e24, 52 false pairs and 5 missed; at 7.3e-25, 14 false and 2 missed; beyond, nearly
//! every non-intersecting pair whose boxes overlap is reported. The test asserts that the
//! warning's band is the measured one.

use classic_gpgpu::collide::tri_test::{Predicate, MOLLER_SAFE_SCALES};
use classic_gpgpu::collide::triangles_intersect;
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const PAIRS: usize = 4000;

/// Random triangle pairs in the unit cube.
fn pairs() -> Vec<([Vec3; 3], [Vec3; 3])> {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let triangle = |rng: &mut ChaCha8Rng| {
        let c = Vec3::new(rng.gen(), rng.gen(), rng.gen());
        [0; 3].map(|_| c + (Vec3::new(rng.gen(), rng.gen(), rng.gen()) - 0.5) * 0.6)
    };
    (0..PAIRS)
        .map(|_| (triangle(&mut rng), triangle(&mut rng)))
        .collect()
}

/// (false pairs, missed pairs, intersecting pairs) of Möller against the exact test at `scale`.
fn disagreements(pairs: &[([Vec3; 3], [Vec3; 3])], scale: f32) -> (usize, usize, usize) {
    let (mut invented, mut missed, mut hits) = (0, 0, 0);
    for (a, b) in pairs {
        let (a, b) = (a.map(|p| p * scale), b.map(|p| p * scale));
        let exact = triangles_intersect(&a, &b, Predicate::Exact);
        let moller = triangles_intersect(&a, &b, Predicate::Moller);
        hits += exact as usize;
        invented += (moller && !exact) as usize;
        missed += (!moller && exact) as usize;
    }
    (invented, missed, hits)
}

#[test]
fn moller_agrees_with_the_exact_test_only_inside_the_measured_scales() {
    let pairs = pairs();
    let quarter_decades = -37 * 4..=38 * 4;
    let mut clean = Vec::new();
    for q in quarter_decades {
        let exponent = q as f32 / 4.0;
        let scale = 10f32.powf(exponent);
        if !scale.is_normal() || scale * 2.0 == f32::INFINITY {
            continue;
        }
        let (invented, missed, hits) = disagreements(&pairs, scale);
        println!(
            "1e{exponent:>6.2}: {hits:>4} intersecting, {invented:>4} false, {missed:>4} missed"
        );
        let largest = pairs
            .iter()
            .flat_map(|(a, b)| a.iter().chain(b))
            .map(|p| (*p * scale).abs().max_element())
            .fold(0.0, f32::max);
        clean.push((largest, invented + missed == 0));
    }
    // The run of clean scales around 1 (by the largest coordinate): where Möller can be
    // trusted.
    let unit = clean
        .iter()
        .position(|&(s, _)| s >= 1.0)
        .expect("1 is in range");
    assert!(
        clean[unit].1,
        "Möller disagrees with the exact test at unit scale"
    );
    let low = (0..unit)
        .rev()
        .find(|&k| !clean[k].1)
        .map(|k| clean[k + 1].0);
    let high = (unit..clean.len())
        .find(|&k| !clean[k].1)
        .map(|k| clean[k - 1].0);
    let (low, high) = (
        low.expect("a failing small scale"),
        high.expect("a failing large scale"),
    );
    println!("clean from {low:.2e} to {high:.2e}");
    // The warning's band is the measured one, to the quarter decade.
    let [safe_low, safe_high] = MOLLER_SAFE_SCALES;
    let within_a_quarter = |a: f32, b: f32| (a.log10() - b.log10()).abs() < 0.2;
    assert!(
        within_a_quarter(safe_low, low) && within_a_quarter(safe_high, high),
        "the warning says {safe_low:e}..{safe_high:e}, the measurement {low:e}..{high:e}"
    );
}
