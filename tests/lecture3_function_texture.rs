//! Lecture 3, technique 4: a function in a 1D texture against the exact function, and the
//! shader's own evaluation against the CPU's.
//!
//! Tolerances. Computed in the shader: the sigmoid within 2e-6 (fp32 `exp` and a division
//! on values below 1); the square wave within 2e-5 (16 fp32 sines of a phase kept exact by
//! `fract`, each within ~1e-6). Looked up: the texture unit interpolates between two texels
//! with weights that hardware may round to 8 fractional bits, so the GPU lookup may differ
//! from exact linear interpolation by the step between neighbouring texels / 256, plus 2e-6.
//! Sums of K values: K times the per-value tolerance.

use classic_gpgpu::lecture3::function_texture::{
    error_against_exact, sample_x, Evaluation, Function, FunctionPasses, FunctionTable,
};
use common::context;

mod common;

fn per_value_tolerance(f: Function) -> f64 {
    match f {
        Function::Sigmoid => 2e-6,
        Function::SquareWave => 2e-5,
    }
}

#[test]
fn the_shader_computes_each_function_as_the_cpu_does() {
    let ctx = context();
    let passes = FunctionPasses::new(&ctx, 64, 32).unwrap();
    for f in Function::ALL {
        for per_pixel in [1, 16] {
            passes.run(Evaluation::Exact(f), per_pixel).unwrap();
            let gpu = passes.read().unwrap();
            let total = passes.total(per_pixel);
            for (p, &sum) in gpu.iter().enumerate() {
                let samples = p as u64 * per_pixel as u64..(p as u64 + 1) * per_pixel as u64;
                let cpu: f64 = samples.map(|s| f.exact(sample_x(f, s, total))).sum();
                let tol = per_pixel as f64 * per_value_tolerance(f);
                assert!(
                    (sum as f64 - cpu).abs() <= tol,
                    "{} K = {per_pixel}, pixel {p}: GPU {sum} vs CPU {cpu}",
                    f.name()
                );
            }
        }
    }
}

#[test]
fn lookups_interpolate_the_table_linearly_and_err_within_the_bound() {
    let ctx = context();
    let passes = FunctionPasses::new(&ctx, 64, 64).unwrap();
    let total = passes.total(1);
    for f in Function::ALL {
        let mut previous_error = f64::INFINITY;
        for texels in [16, 64, 256, 1024] {
            let table = FunctionTable::new(&ctx, f, texels).unwrap();
            passes.run(Evaluation::Lookup(&table), 1).unwrap();
            let gpu = passes.read().unwrap();
            let weight_tolerance = table.max_step() / 256.0 + 2e-6;
            for (s, &v) in gpu.iter().enumerate() {
                let cpu = table.interpolate(sample_x(f, s as u64, total));
                assert!(
                    (v as f64 - cpu).abs() <= weight_tolerance,
                    "{} with {texels} texels, sample {s}: GPU {v} vs interpolation {cpu}",
                    f.name()
                );
            }
            let (cpu_max, _) =
                error_against_exact(f, |s| table.interpolate(sample_x(f, s, total)), total);
            assert!(
                cpu_max <= table.error_bound(),
                "{} {texels}: {cpu_max} above the bound {}",
                f.name(),
                table.error_bound()
            );
            let (gpu_max, _) = error_against_exact(f, |s| gpu[s as usize] as f64, total);
            assert!(gpu_max <= table.error_bound() + weight_tolerance);
            // Linear interpolation's error falls with the square of the spacing, once the
            // table resolves the function.
            assert!(cpu_max < previous_error, "{} {texels}", f.name());
            previous_error = cpu_max;
        }
    }
}

#[test]
fn bad_sizes_are_named() {
    let ctx = context();
    let err = FunctionTable::new(&ctx, Function::Sigmoid, 1)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("--texels") && err.contains("1 texels"),
        "{err}"
    );
    let passes = FunctionPasses::new(&ctx, 8, 8).unwrap();
    let err = passes
        .run(Evaluation::Exact(Function::Sigmoid), 3)
        .unwrap_err()
        .to_string();
    assert!(err.contains("--per-pixel"), "{err}");
    assert!(FunctionPasses::new(&ctx, 12, 8).is_err());
}
