//! Paper 3 on a real headless context (llvmpipe in CI): the render-pass MLP against the CPU
//! forward pass, on networks and batches the tests make.
//!
//! Tolerance: both sides sum each inner product in fp32, in different orders, so each output
//! may differ from the exact value by at most the bound of `cpu::error_bound` (Higham's
//! gamma_N per layer, carried through |W| and the sigmoid's slope of 1/4, plus 1e-6 for the
//! shader's `exp`); two evaluations therefore agree within twice that bound.

use classic_gpgpu::mlp::cpu::{error_bound, forward, CpuProduct};
use classic_gpgpu::mlp::detect::{classify_cpu, classify_gpu, shipped_detector, THRESHOLD};
use classic_gpgpu::mlp::matmul::RADEON_9700_INPUTS_PER_PASS;
use classic_gpgpu::mlp::{Activation, Formulation, GpuMlp, Layer, Network};
use common::context;
use ndarray::{Array1, Array2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod common;

/// A network of the given layer sizes (sizes[0] inputs), weights uniform in +-1/sqrt(N)*2,
/// sigmoid layers except a random identity here and there.
fn random_network(rng: &mut impl Rng, sizes: &[usize]) -> Network {
    let layers = sizes
        .windows(2)
        .map(|s| {
            let (n, m) = (s[0], s[1]);
            let r = 2.0 / (n as f32).sqrt();
            Layer {
                weights: Array2::from_shape_simple_fn((m, n), || rng.gen_range(-r..r)),
                bias: Array1::from_shape_simple_fn(m, || rng.gen_range(-1.0..1.0)),
                activation: if rng.gen_bool(0.25) {
                    Activation::Identity
                } else {
                    Activation::Sigmoid
                },
            }
        })
        .collect();
    Network::new(layers).unwrap()
}

fn random_batch(rng: &mut impl Rng, l: usize, n: usize) -> Array2<f32> {
    Array2::from_shape_simple_fn((l, n), || rng.gen_range(-1.0..1.0))
}

/// Asserts |a - b| <= 2 bound elementwise, naming the worst element.
fn assert_within(a: &Array2<f32>, b: &Array2<f32>, bound: &Array2<f32>, what: &str) {
    assert_eq!(a.dim(), b.dim(), "{what}: shapes");
    for (((j, i), x), (y, e)) in a.indexed_iter().zip(b.iter().zip(bound.iter())) {
        assert!(
            (x - y).abs() <= 2.0 * e,
            "{what}: output {i} of input vector {j}: {x} vs {y}, allowed {}",
            2.0 * e
        );
    }
}

#[test]
fn gpu_equals_cpu_for_random_networks_of_one_to_four_layers() {
    let ctx = context();
    let gpu = GpuMlp::new(&ctx).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(2004);
    let shapes: [&[usize]; 6] = [
        &[1, 1],
        &[13, 5],
        &[7, 3, 9],
        &[121, 30, 1],
        &[33, 17, 6, 11],
        &[5, 23, 2, 15, 3],
    ];
    for sizes in shapes {
        let net = random_network(&mut rng, sizes);
        let l = rng.gen_range(1..90);
        let x = random_batch(&mut rng, l, sizes[0]);
        let cpu = forward(CpuProduct::Plain, &net, x.view()).outputs;
        let bound = error_bound(&net, x.view());
        for formulation in [Formulation::Faithful, Formulation::Packed] {
            let loaded = gpu.load(&net, formulation).unwrap();
            let out = loaded.forward(x.view(), None).unwrap();
            assert_eq!(out.tiles, 1);
            assert_within(
                &out.outputs,
                &cpu,
                &bound,
                &format!("{formulation:?} {sizes:?}, L = {l}"),
            );
        }
    }
}

#[test]
fn packed_and_faithful_passes_agree() {
    let ctx = context();
    let gpu = GpuMlp::new(&ctx).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let net = random_network(&mut rng, &[50, 19, 7]);
    let x = random_batch(&mut rng, 61, 50);
    let faithful = gpu.load(&net, Formulation::Faithful).unwrap();
    let packed = gpu.load(&net, Formulation::Packed).unwrap();
    let a = faithful.forward(x.view(), None).unwrap().outputs;
    let b = packed.forward(x.view(), None).unwrap().outputs;
    assert_within(&a, &b, &error_bound(&net, x.view()), "packed vs faithful");
    // and they are not trivially equal to something constant
    assert!(a.iter().any(|&v| (v - a[[0, 0]]).abs() > 1e-3));
}

#[test]
fn batches_beyond_a_tile_are_split_and_give_the_same_outputs() {
    let ctx = context();
    let gpu = GpuMlp::new(&ctx).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let net = random_network(&mut rng, &[9, 6, 2]);
    let x = random_batch(&mut rng, 45, 9);
    for formulation in [Formulation::Faithful, Formulation::Packed] {
        let loaded = gpu.load(&net, formulation).unwrap();
        let whole = loaded.forward(x.view(), None).unwrap();
        let tiled = loaded.forward(x.view(), Some(8)).unwrap();
        assert_eq!((whole.tiles, tiled.tiles), (1, 6), "{formulation:?}");
        // the same inputs in the same order give the same fp32 sums
        assert_eq!(whole.outputs, tiled.outputs, "{formulation:?}");
    }
}

/// The paper's pass split, with the per-pass input limit forced small (down to one input per
/// pass). Each pass after the first starts from the running sum of the ones before, read
/// exactly from an R32F texel, and adds its inputs in order, so the split sums the same terms in
/// the same order as one pass: it is held to the same fp32 bound (`error_bound`, twice for two
/// evaluations) against the one-pass outputs and against the CPU.
#[test]
fn products_split_into_passes_equal_one_pass_and_the_cpu() {
    let ctx = context();
    let gpu = GpuMlp::new(&ctx).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(15);
    let shapes: [&[usize]; 3] = [&[13, 5], &[121, 30, 1], &[33, 17, 6, 11]];
    for sizes in shapes {
        let net = random_network(&mut rng, sizes);
        let x = random_batch(&mut rng, 37, sizes[0]);
        let cpu = forward(CpuProduct::Plain, &net, x.view()).outputs;
        let bound = error_bound(&net, x.view());
        let one_pass = gpu.load(&net, Formulation::Faithful).unwrap();
        let whole = one_pass.forward(x.view(), None).unwrap();
        assert_eq!(whole.product_passes, vec![1; sizes.len() - 1]);
        for limit in [1, 3, 7, RADEON_9700_INPUTS_PER_PASS] {
            let split = gpu
                .load(&net, Formulation::Faithful)
                .unwrap()
                .split_products(Some(limit))
                .unwrap();
            // and in tiles, so that the ping-pong targets are remade per tile
            let out = split.forward(x.view(), Some(16)).unwrap();
            let passes: Vec<usize> = sizes.windows(2).map(|s| s[0].div_ceil(limit)).collect();
            assert_eq!(out.product_passes, passes, "{sizes:?}, {limit} per pass");
            assert_eq!(out.tiles, 3);
            let what = format!("{sizes:?}, {limit} inputs per pass");
            assert_within(
                &out.outputs,
                &whole.outputs,
                &bound,
                &format!("{what} vs one pass"),
            );
            assert_within(&out.outputs, &cpu, &bound, &format!("{what} vs CPU"));
        }
    }
}

#[test]
fn a_pass_split_of_zero_or_of_the_packed_passes_is_refused() {
    let ctx = context();
    let gpu = GpuMlp::new(&ctx).unwrap();
    let net = random_network(&mut ChaCha8Rng::seed_from_u64(2), &[6, 3]);
    let zero = gpu
        .load(&net, Formulation::Faithful)
        .unwrap()
        .split_products(Some(0));
    let e = zero.err().expect("refused").to_string();
    assert!(e.contains("at least one input"), "{e}");
    let packed = gpu
        .load(&net, Formulation::Packed)
        .unwrap()
        .split_products(Some(3));
    let e = packed.err().expect("refused").to_string();
    assert!(e.contains("faithful") && e.contains("packed"), "{e}");
}

#[test]
fn layers_wider_than_a_texture_are_refused_clearly() {
    let ctx = context();
    let gpu = GpuMlp::new(&ctx).unwrap();
    let max = ctx.info().limits.max_texture_size as usize;
    for (formulation, n) in [
        (Formulation::Faithful, max + 1),
        (Formulation::Packed, 4 * max + 1),
    ] {
        let net = Network::new(vec![Layer {
            weights: Array2::zeros((2, n)),
            bias: Array1::zeros(2),
            activation: Activation::Sigmoid,
        }])
        .unwrap();
        let err = gpu
            .load(&net, formulation)
            .err()
            .expect("refused")
            .to_string();
        assert!(
            err.contains("layer 0")
                && err.contains(&format!("{n} inputs"))
                && err.contains(&max.to_string()),
            "{err}"
        );
    }
    // the widest faithful layer that fits is accepted
    let net = Network::new(vec![Layer {
        weights: Array2::from_elem((1, max), 1.0 / max as f32),
        bias: Array1::zeros(1),
        activation: Activation::Identity,
    }])
    .unwrap();
    let x = Array2::from_elem((3, max), 1.0f32);
    let out = gpu
        .load(&net, Formulation::Faithful)
        .unwrap()
        .forward(x.view(), None)
        .unwrap();
    assert!(
        out.outputs.iter().all(|&v| (v - 1.0).abs() < 1e-3),
        "{:?}",
        out.outputs
    );
}

#[test]
fn batch_of_the_wrong_width_is_an_error() {
    let ctx = context();
    let gpu = GpuMlp::new(&ctx).unwrap();
    let net = random_network(&mut ChaCha8Rng::seed_from_u64(1), &[4, 2]);
    let loaded = gpu.load(&net, Formulation::Faithful).unwrap();
    let err = loaded
        .forward(Array2::zeros((3, 5)).view(), None)
        .unwrap_err();
    assert!(err.to_string().contains("network takes 4"), "{err}");
}

#[test]
fn text_detector_gpu_mask_equals_cpu_mask() {
    let ctx = context();
    let gpu = GpuMlp::new(&ctx).unwrap();
    let net = shipped_detector().unwrap();
    let photo = image::open(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/mlp/text.png"))
        .unwrap()
        .to_luma8();
    // a 120 x 80 crop with text and ruled lines keeps llvmpipe quick
    let image = image::imageops::crop_imm(&photo, 60, 20, 120, 80).to_image();
    let cpu = classify_cpu(&net, &image, CpuProduct::Optimised, 1 << 16).outputs;
    let windows = classic_gpgpu::mlp::window::window_batch(&image, 0..image.height());
    let bound = error_bound(&net, windows.view());
    for (formulation, inputs_per_pass) in [
        (Formulation::Faithful, None),
        (Formulation::Faithful, Some(RADEON_9700_INPUTS_PER_PASS)),
        (Formulation::Packed, None),
    ] {
        let loaded = gpu
            .load(&net, formulation)
            .unwrap()
            .split_products(inputs_per_pass)
            .unwrap();
        let out = classify_gpu(&loaded, &image, 1 << 16, None)
            .unwrap()
            .outputs;
        let mut undecided = 0;
        for (p, (&g, &c)) in out.iter().zip(&cpu).enumerate() {
            let allowed = 2.0 * bound[[p, 0]];
            assert!(
                (g - c).abs() <= allowed,
                "{formulation:?} {inputs_per_pass:?} pixel {p}: {g} vs {c}"
            );
            // a pixel may flip only when its CPU output is within the tolerance of 1/2
            if (c - THRESHOLD).abs() <= allowed {
                undecided += 1;
            } else {
                assert_eq!(
                    g > THRESHOLD,
                    c > THRESHOLD,
                    "{formulation:?} {inputs_per_pass:?} pixel {p}"
                );
            }
        }
        let text = cpu.iter().filter(|&&c| c > THRESHOLD).count();
        assert!(text > 100 && text < cpu.len() - 100, "{text} text pixels");
        assert!(
            undecided < cpu.len() / 100,
            "{undecided} pixels at the threshold"
        );
    }
}
