//! Paper 3's compute formulation (OpenGL 4.3, tiled shared-memory product with bias and
//! sigmoid fused) against the CPU forward pass and the classic render passes. Tolerance as in
//! `mlp_gpu`: each side is within `cpu::error_bound` of the exact value (Higham's gamma_N per
//! layer), so two evaluations agree within twice the bound. Below 4.3 (softpipe): the clear
//! error, and the classic passes still run.

use classic_gpgpu::mlp::compute::ComputeMlp;
use classic_gpgpu::mlp::cpu::{error_bound, forward, CpuProduct};
use classic_gpgpu::mlp::{Activation, Formulation, GpuMlp, Layer, Network};
use common::compute_context;
use ndarray::{Array1, Array2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod common;

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
fn compute_equals_cpu_and_classic_for_random_networks() {
    let (ctx, compute) = compute_context();
    let mut rng = ChaCha8Rng::seed_from_u64(15);
    let classic = GpuMlp::new(&ctx).unwrap();
    if !compute {
        let err = ComputeMlp::new(&ctx).err().unwrap().to_string();
        assert!(
            err.contains("paper 3") && err.contains("needs OpenGL 4.3"),
            "{err}"
        );
        let net = random_network(&mut rng, &[5, 3]);
        let x = Array2::from_shape_simple_fn((4, 5), || rng.gen_range(-1.0..1.0));
        let out = classic
            .load(&net, Formulation::Faithful)
            .unwrap()
            .forward(x.view(), None)
            .unwrap();
        let cpu = forward(CpuProduct::Plain, &net, x.view()).outputs;
        assert_within(&out.outputs, &cpu, &error_bound(&net, x.view()), "classic");
        return;
    }
    let mlp = ComputeMlp::new(&ctx).unwrap();
    // Sizes on and off the 16-wide tiles, one to four layers.
    for (sizes, l) in [
        (vec![1, 1], 1usize),
        (vec![16, 16], 16),
        (vec![121, 30, 1], 77),
        (vec![33, 17, 40, 5], 200),
        (vec![7, 64, 3, 9, 2], 35),
    ] {
        let net = random_network(&mut rng, &sizes);
        let x = Array2::from_shape_simple_fn((l, sizes[0]), || rng.gen_range(-1.0..1.0));
        let bound = error_bound(&net, x.view());
        let now = mlp.load(&net).unwrap().forward(x.view()).unwrap();
        let cpu = forward(CpuProduct::Plain, &net, x.view()).outputs;
        assert_within(
            &now.outputs,
            &cpu,
            &bound,
            &format!("{sizes:?} compute vs CPU"),
        );
        let then = classic
            .load(&net, Formulation::Faithful)
            .unwrap()
            .forward(x.view(), None)
            .unwrap();
        assert_within(
            &now.outputs,
            &then.outputs,
            &bound,
            &format!("{sizes:?} compute vs classic"),
        );
    }
}

#[test]
fn a_batch_of_the_wrong_width_is_an_error() {
    let (ctx, compute) = compute_context();
    if !compute {
        return;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(16);
    let net = random_network(&mut rng, &[4, 2]);
    let mlp = ComputeMlp::new(&ctx).unwrap();
    let loaded = mlp.load(&net).unwrap();
    let err = loaded
        .forward(Array2::zeros((3, 5)).view())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("5 values per input vector") && err.contains("takes 4"),
        "{err}"
    );
    let err = loaded
        .forward(Array2::zeros((0, 4)).view())
        .unwrap_err()
        .to_string();
    assert!(err.contains("no input vectors"), "{err}");
}
