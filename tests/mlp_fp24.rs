//! Paper 3 at its board's precision: the shaders' 24-bit rounding (`glsl/mlp/fp24.glsl`)
//! against the CPU model (`mlp::fp24`), value by value, and the whole network at fp24 on the
//! GPU against the CPU forward pass that rounds at the same steps.
//!
//! Tolerances: rounding is exact integer work on the fp32 bits, so the pass must give the CPU
//! model's bits. Products and sums are correctly rounded fp32 operations on both sides, so a
//! network of identity layers must agree bit for bit. Only the sigmoid differs: the shader's
//! `exp` and division are not the CPU's, so a step may land one 24-bit unit away, and after
//! that the two runs are two fp24 evaluations of the same network, each within
//! `fp24::error_bound_fp24` of the exact value: they agree within twice that bound.

use classic_gpgpu::mlp::cpu::{forward, CpuProduct};
use classic_gpgpu::mlp::detect::shipped_detector;
use classic_gpgpu::mlp::fp24::{
    error_bound_fp24, forward_fp24, fp24, is_fp24, round_on_gpu, Precision, MAX, MIN_POSITIVE,
};
use classic_gpgpu::mlp::matmul::RADEON_9700_INPUTS_PER_PASS;
use classic_gpgpu::mlp::window::window_batch;
use classic_gpgpu::mlp::{Activation, Formulation, GpuMlp, Layer, Network};
use common::context;
use image::GrayImage;
use ndarray::{Array1, Array2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod common;

/// Values at the format's edges, ties both ways, and random fp32 bit patterns over the whole
/// exponent range of the format and a little beyond (no fp32 denormals: a renderer may flush
/// them as it reads the texture, which is not the rounding under test).
fn test_values() -> Vec<f32> {
    let step_at_one = 2f32.powi(-16);
    let mut values = vec![
        0.0,
        -0.0,
        1.0,
        1.0 + step_at_one / 2.0,
        1.0 + 1.5 * step_at_one,
        131_073.0,
        131_075.0,
        2.0 - f32::EPSILON,
        0.1,
        MAX,
        -MAX,
        MAX + 2f32.powi(63 - 16) / 2.0,
        MAX + 2f32.powi(63 - 16) / 4.0,
        2f32.powi(64),
        f32::MAX,
        -f32::MAX,
        MIN_POSITIVE,
        f32::from_bits(MIN_POSITIVE.to_bits() - 1),
        f32::from_bits(MIN_POSITIVE.to_bits() - 0x80),
        -f32::from_bits(MIN_POSITIVE.to_bits() - 0x80),
        2f32.powi(-63),
        f32::MIN_POSITIVE,
        f32::INFINITY,
        f32::NEG_INFINITY,
    ];
    let mut rng = ChaCha8Rng::seed_from_u64(24);
    for _ in 0..6000 {
        // exponents -66 .. 66 around the format's -62 .. 63, any mantissa, either sign
        let exponent: u32 = rng.gen_range(61..=193);
        let bits = (rng.gen::<u32>() & 0x8000_0000) | (exponent << 23) | rng.gen_range(0..1 << 23);
        values.push(f32::from_bits(bits));
    }
    // exact ties of every kind: the dropped 7 bits 0x40, the kept part odd or even
    for _ in 0..1000 {
        let exponent: u32 = rng.gen_range(65..=190);
        let kept: u32 = rng.gen_range(0..1 << 16);
        values.push(f32::from_bits((exponent << 23) | (kept << 7) | 0x40));
    }
    values
}

#[test]
fn shader_rounding_equals_the_cpu_model_bit_for_bit() {
    let ctx = context();
    ctx.set_checks(true);
    let values = test_values();
    let gpu = round_on_gpu(&ctx, &values).unwrap();
    let mismatches: Vec<String> = values
        .iter()
        .zip(&gpu)
        .filter(|(v, g)| g.to_bits() != fp24(**v).to_bits())
        .take(10)
        .map(|(v, g)| {
            format!(
                "{v:e} ({:#010x}): GPU {g:e}, CPU {:e}",
                v.to_bits(),
                fp24(*v)
            )
        })
        .collect();
    assert!(
        mismatches.is_empty(),
        "{} values:\n{}",
        mismatches.len(),
        mismatches.join("\n")
    );
    // the test values do reach every case: ties, overflow, underflow, unchanged
    assert!(gpu.contains(&f32::INFINITY) && gpu.iter().any(|g| g.to_bits() == 0x8000_0000));
    assert!(values.iter().zip(&gpu).filter(|(v, g)| v != g).count() > 6000);
}

/// A network of the given layer sizes, weights +-2/sqrt(N), activations as given.
fn network(rng: &mut impl Rng, sizes: &[usize], activation: Activation) -> Network {
    let layers = sizes
        .windows(2)
        .map(|s| {
            let (n, m) = (s[0], s[1]);
            let r = 2.0 / (n as f32).sqrt();
            Layer {
                weights: Array2::from_shape_simple_fn((m, n), || rng.gen_range(-r..r)),
                bias: Array1::from_shape_simple_fn(m, || rng.gen_range(-1.0..1.0)),
                activation,
            }
        })
        .collect();
    Network::new(layers).unwrap()
}

fn batch(rng: &mut impl Rng, l: usize, n: usize) -> Array2<f32> {
    Array2::from_shape_simple_fn((l, n), || rng.gen_range(-1.0..1.0))
}

/// The GPU at fp24, in one pass per product and in the R300's passes of 15 inputs.
fn gpu_fp24(gpu: &GpuMlp, net: &Network, x: &Array2<f32>) -> Vec<Array2<f32>> {
    [None, Some(RADEON_9700_INPUTS_PER_PASS)]
        .into_iter()
        .map(|per_pass| {
            gpu.load(net, Formulation::Faithful)
                .unwrap()
                .split_products(per_pass)
                .unwrap()
                .forward(x.view(), None)
                .unwrap()
                .outputs
        })
        .collect()
}

#[test]
fn identity_layers_at_fp24_equal_the_cpu_model_bit_for_bit() {
    let ctx = context();
    ctx.set_checks(true);
    let gpu = GpuMlp::with_precision(&ctx, Precision::Fp24).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(9700);
    for sizes in [&[1usize, 1][..], &[40, 7], &[33, 9, 5]] {
        let net = network(&mut rng, sizes, Activation::Identity);
        let x = batch(&mut rng, 37, sizes[0]);
        let cpu = forward_fp24(&net, x.view());
        let fp32 = forward(CpuProduct::Plain, &net, x.view()).outputs;
        assert_ne!(cpu, fp32, "{sizes:?}: the rounding changed nothing");
        for out in gpu_fp24(&gpu, &net, &x) {
            for ((j, i), g) in out.indexed_iter() {
                assert_eq!(
                    g.to_bits(),
                    cpu[[j, i]].to_bits(),
                    "{sizes:?}: output {i} of vector {j}: GPU {g}, CPU model {}",
                    cpu[[j, i]]
                );
            }
        }
    }
}

#[test]
fn sigmoid_networks_at_fp24_agree_with_the_cpu_model_within_the_bound() {
    let ctx = context();
    ctx.set_checks(true);
    let gpu = GpuMlp::with_precision(&ctx, Precision::Fp24).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(300);
    let photo = GrayImage::from_fn(19, 5, |x, y| image::Luma([((x * 53 + y * 97) % 256) as u8]));
    let mut cases = vec![(shipped_detector().unwrap(), window_batch(&photo, 0..5))];
    for sizes in [&[13usize, 5][..], &[21, 16, 3], &[7, 30, 1]] {
        let net = network(&mut rng, sizes, Activation::Sigmoid);
        let x = batch(&mut rng, 29, sizes[0]);
        cases.push((net, x));
    }
    let (mut exact, mut total) = (0, 0);
    for (net, x) in &cases {
        let cpu = forward_fp24(net, x.view());
        let bound = error_bound_fp24(net, x.view());
        for out in gpu_fp24(&gpu, net, x) {
            for (((j, i), g), (c, e)) in out.indexed_iter().zip(cpu.iter().zip(&bound)) {
                assert!(
                    is_fp24(*g),
                    "output {i} of vector {j}: {g} is not a 24-bit value"
                );
                assert!(
                    (g - c).abs() <= 2.0 * e,
                    "output {i} of vector {j}: GPU {g}, CPU model {c}, allowed {}",
                    2.0 * e
                );
                exact += usize::from(g == c);
                total += 1;
            }
        }
    }
    eprintln!("{exact} of {total} outputs equal the CPU model's exactly");
}

#[test]
fn only_the_fp24_programs_round_and_fp24_refuses_the_packed_formulation() {
    let ctx = context();
    ctx.set_checks(true);
    let fp32 = GpuMlp::new(&ctx).unwrap();
    let fp24_gpu = GpuMlp::with_precision(&ctx, Precision::Fp24).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let net = network(&mut rng, &[17, 6, 2], Activation::Sigmoid);
    let x = batch(&mut rng, 11, 17);
    let at_fp32 = fp32
        .load(&net, Formulation::Faithful)
        .unwrap()
        .forward(x.view(), None)
        .unwrap()
        .outputs;
    // fp32 outputs are (almost all) not 24-bit values; the fp24 run's all are
    assert!(at_fp32.iter().any(|v| !is_fp24(*v)));
    let at_fp24 = &gpu_fp24(&fp24_gpu, &net, &x)[0];
    assert!(at_fp24.iter().all(|v| is_fp24(*v)));
    let e = fp24_gpu
        .load(&net, Formulation::Packed)
        .err()
        .expect("packed at fp24 is refused")
        .to_string();
    assert!(e.contains("faithful") && e.contains("packed"), "{e}");
}

/// A scratch directory for this test binary.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("mlp_fp24_{}_{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &std::path::Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// `mlp run --period`: the outputs are the fp24 model's within its bound (identity layers: its
/// very bits), the products are split into the board's passes, and the JSON names the board.
#[test]
fn mlp_run_period_runs_the_r300_profile() {
    let dir = scratch("run");
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    let net = network(&mut rng, &[20, 6, 2], Activation::Identity);
    let x = batch(&mut rng, 9, 20);
    let net_file = write(&dir, "net.json", &net.to_json());
    let rows: Vec<Vec<f32>> = x.outer_iter().map(|r| r.to_vec()).collect();
    let x_file = write(&dir, "x.json", &serde_json::to_string(&rows).unwrap());
    let base = [
        "mlp",
        "run",
        "--network",
        &net_file,
        "--input",
        &x_file,
        "--json",
    ];
    let v = common::json_of(&[&base[..], &["--period"]].concat());
    assert_eq!(v["period"]["gpu"], "ATI RADEON 9700 PRO");
    assert_eq!(v["product_passes"], serde_json::json!([2, 1])); // 20 inputs: 15 + 5; 6: 6
    let model = forward_fp24(&net, x.view());
    let outputs = v["outputs"].as_array().unwrap();
    for (j, row) in outputs.iter().enumerate() {
        for (i, value) in row.as_array().unwrap().iter().enumerate() {
            let got = value.as_f64().unwrap() as f32;
            assert_eq!(got.to_bits(), model[[j, i]].to_bits(), "output {i} of {j}");
        }
    }
    // without --period: fp32, one pass per product, no board named
    let plain = common::json_of(&base);
    assert!(plain["period"].is_null());
    assert_eq!(plain["product_passes"], serde_json::json!([1, 1]));
}

/// What the R300 could not do is refused with the limit named: a compute pass, a layer wider
/// than its 2048-texel textures; the packed formulation has no fp24 emulation.
#[test]
fn mlp_run_period_refuses_what_the_board_could_not_do() {
    let dir = scratch("refuse");
    let wide = Network::new(vec![Layer {
        weights: Array2::zeros((1, 2049)),
        bias: Array1::zeros(1),
        activation: Activation::Sigmoid,
    }])
    .unwrap();
    let wide_file = write(&dir, "wide.json", &wide.to_json());
    let wide_x = write(&dir, "wide_x.json", &format!("[{:?}]", vec![0.5f32; 2049]));
    let small = write(&dir, "net.json", &wide_small().to_json());
    let small_x = write(&dir, "x.json", "[[1, 2]]");
    let cases: [(&[&str], &[&str]); 3] = [
        (
            &["--network", &wide_file, "--input", &wide_x],
            &["ATI RADEON 9700 PRO", "max_texture_size", "2048"],
        ),
        (
            &[
                "--network",
                &small,
                "--input",
                &small_x,
                "--formulation",
                "compute",
            ],
            &["ATI RADEON 9700 PRO", "compute_shaders"],
        ),
        (
            &[
                "--network",
                &small,
                "--input",
                &small_x,
                "--formulation",
                "packed",
            ],
            &["24-bit", "faithful"],
        ),
    ];
    for (args, words) in cases {
        let out = common::classic_gpgpu(&[&["mlp", "run", "--period"][..], args].concat());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} should fail: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        for word in words {
            assert!(stderr.contains(word), "{args:?}: '{word}' not in {stderr}");
        }
    }
    // the same wide layer runs at today's limits
    let out = common::classic_gpgpu(&["mlp", "run", "--network", &wide_file, "--input", &wide_x]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn wide_small() -> Network {
    Network::new(vec![Layer {
        weights: Array2::from_elem((1, 2), 0.25),
        bias: Array1::zeros(1),
        activation: Activation::Sigmoid,
    }])
    .unwrap()
}

/// `mlp detect --period` classifies an image as the board would and says so.
#[test]
fn mlp_detect_period_names_the_board() {
    let dir = scratch("detect");
    let image = GrayImage::from_fn(23, 7, |x, y| image::Luma([((x * 41 + y * 89) % 256) as u8]));
    let path = dir.join("page.png");
    image.save(&path).unwrap();
    let path = path.display().to_string();
    let v = common::json_of(&["mlp", "detect", &path, "--period", "--json"]);
    assert_eq!(v["period"]["gpu"], "ATI RADEON 9700 PRO");
    assert_eq!(v["product_passes"], serde_json::json!([9, 2])); // 121 = 8 x 15 + 1; 30 = 15 + 15
    assert!(v["text_pixels"].as_u64().unwrap() <= 23 * 7);
}
