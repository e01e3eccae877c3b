//! Lecture 3, technique 6: an `if` removed with the depth buffer. The occlusion query must
//! count exactly the active pixels (the CPU counts the mask); both versions must draw the
//! CPU's picture: the expensive sum of 64 sines within 2e-5 (fp32 sines of phases kept exact,
//! each within ~1e-6, weighted by 1/k: at most 1e-6 (1 + ln 64) < 6e-6, with room for the sum's
//! rounding), 0 exactly where the mask is off; and the two versions must agree within 1e-6.
//! The expensive shader's runs, counted (pipeline statistics or an atomic counter), must fit
//! the mask at quad granularity behind it (at least the active pixels, nothing outside the
//! quads that hold one: `runs_fit_mask`) and cover every pixel without it; where the context
//! cannot count them, the reason must name what is missing.

use classic_gpgpu::lecture3::depth_mask::{
    active_quads, cpu_picture, mask, runs_fit_mask, DepthMask, MaskShape, RunCounter,
};
use common::context;

mod common;

#[test]
fn masked_and_branching_versions_draw_the_cpu_picture_and_the_query_counts_active_pixels() {
    let ctx = context();
    let (w, h, iterations) = (32, 16, 64);
    for shape in [MaskShape::Blobs, MaskShape::Scattered] {
        let values = mask(shape, w, h, 5);
        let passes = DepthMask::new(&ctx, &values, w, h).unwrap();
        for fraction in [0.0, 0.1, 0.5, 0.9, 1.0] {
            let (cpu, active) = cpu_picture(&values, w, h, fraction, iterations);
            assert_eq!(active, (fraction as f64 * (w * h) as f64).ceil() as u64);
            let ran = passes.run_branching(fraction, iterations).unwrap();
            assert_eq!(ran, (w * h) as u64, "the branching shader runs everywhere");
            let branching = passes.read().unwrap();
            let ran = passes.run_masked(fraction, iterations).unwrap();
            assert_eq!(
                ran, active,
                "{shape:?} {fraction}: fragments behind the depth test"
            );
            let masked = passes.read().unwrap();
            for i in 0..cpu.len() {
                let what = format!("{shape:?} {fraction}, pixel {i}");
                if cpu[i] == 0.0 && values[i] >= fraction {
                    assert_eq!((branching[i], masked[i]), (0.0, 0.0), "{what}");
                    continue;
                }
                assert!(
                    (branching[i] as f64 - cpu[i]).abs() <= 2e-5,
                    "{what}: {} vs {}",
                    branching[i],
                    cpu[i]
                );
                assert!(
                    (masked[i] as f64 - cpu[i]).abs() <= 2e-5,
                    "{what}: {} vs {}",
                    masked[i],
                    cpu[i]
                );
                assert!((masked[i] - branching[i]).abs() <= 1e-6, "{what}");
            }
        }
    }
}

#[test]
fn runs_fit_the_mask_only_at_quad_granularity() {
    // 4x2 pixels: one active pixel in the left quad.
    let values = [0.0, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9, 0.9];
    assert_eq!(active_quads(&values, 4, 2, 0.5), 1);
    assert_eq!(active_quads(&values, 4, 2, 1.0), 2);
    assert_eq!(active_quads(&values, 4, 2, 0.0), 0);
    assert!(runs_fit_mask(1, 1, 1) && runs_fit_mask(8, 1, 1));
    // Every pixel ran (no early test): more than the active quads allow.
    assert!(!runs_fit_mask(9, 1, 1) && !runs_fit_mask(0, 1, 1));
    assert!(runs_fit_mask(0, 0, 0) && !runs_fit_mask(1, 0, 0));
    // Odd sizes: the last quads are partial.
    assert_eq!(active_quads(&[0.0; 9], 3, 3, 0.5), 4);
}

#[test]
fn masks_select_the_fraction_asked_for() {
    for shape in [MaskShape::Blobs, MaskShape::Scattered] {
        let values = mask(shape, 64, 32, 1);
        let mut sorted = values.clone();
        sorted.sort_by(f32::total_cmp);
        sorted.dedup();
        assert_eq!(sorted.len(), values.len(), "{shape:?}: distinct values");
        assert!(sorted[0] == 0.0 && *sorted.last().unwrap() < 1.0);
    }
    // Blobs are coherent: most neighbours agree at 50%; scattered pixels do not.
    let agree = |shape| {
        let v = mask(shape, 64, 64, 1);
        (0..64 * 63)
            .filter(|&i| (v[i] < 0.5) == (v[i + 64] < 0.5))
            .count() as f64
            / (64.0 * 63.0)
    };
    assert!(agree(MaskShape::Blobs) > 0.9);
    assert!(agree(MaskShape::Scattered) < 0.6);
}

#[test]
fn bad_parameters_are_named() {
    let ctx = context();
    let passes = DepthMask::new(&ctx, &mask(MaskShape::Blobs, 8, 8, 1), 8, 8).unwrap();
    let err = passes.run_masked(f32::NAN, 16).unwrap_err().to_string();
    assert!(err.contains("--fraction") && err.contains("NaN"), "{err}");
    let err = passes.run_branching(0.5, 0).unwrap_err().to_string();
    assert!(err.contains("--iterations"), "{err}");
    assert!(DepthMask::new(&ctx, &[0.0; 12], 4, 3).is_err());
}

#[test]
fn the_report_row_checks_and_leaves_the_depth_masked_picture() {
    // The section's depth-mask row checks the pictures of its last timed runs and its
    // picture is what the row leaves in the target: the depth-masked one.
    use classic_gpgpu::report::lecture3::depth_mask_row;
    use classic_gpgpu::timing::Runs;
    let ctx = context();
    let (w, iterations, fraction) = (32, 64, 0.25);
    let values = mask(MaskShape::Scattered, w, w, 1);
    let passes = DepthMask::new(&ctx, &values, w, w).unwrap();
    let (cpu, active) = cpu_picture(&values, w, w, fraction, iterations);
    let row = depth_mask_row(
        &ctx,
        &passes,
        &values,
        MaskShape::Scattered,
        w,
        fraction,
        iterations,
        None,
        Runs::exactly(2),
    )
    .unwrap();
    assert_eq!(row.active, active);
    assert_eq!(row.masked_fragments, active);
    assert_eq!(row.branching_fragments, (w * w) as u64);
    assert!(row.max_error <= 2e-5, "{}", row.max_error);
    let left = passes.read().unwrap();
    for (i, (&g, &c)) in left.iter().zip(&cpu).enumerate() {
        if values[i] >= fraction {
            assert_eq!(g, 0.0, "pixel {i} is masked off");
        } else {
            assert!((g as f64 - c).abs() <= 2e-5, "pixel {i}: {g} vs {c}");
        }
    }
}

#[test]
fn the_expensive_shader_runs_only_on_active_pixels_by_its_own_count() {
    let ctx = context();
    let (w, h, iterations) = (32, 16, 16);
    for shape in [MaskShape::Blobs, MaskShape::Scattered] {
        let values = mask(shape, w, h, 7);
        let passes = DepthMask::new(&ctx, &values, w, h).unwrap();
        let counter = passes.run_counter();
        if let RunCounter::Unavailable(why) = &counter {
            // Only a context with neither means may say so, and it must say what is missing.
            assert!(!ctx.has_compute(), "{why}");
            assert!(
                why.contains("pipeline statistics") && why.contains("atomic"),
                "{why}"
            );
            assert_eq!(passes.count_runs(0.5, iterations, true).unwrap(), None);
            eprintln!("not counted on this context: {why}");
            return;
        }
        for fraction in [0.0, 0.1, 0.5, 1.0] {
            let (cpu, active) = cpu_picture(&values, w, h, fraction, iterations);
            let what = format!("{shape:?} {fraction}, counted by {counter:?}");
            let quads = active_quads(&values, w, h, fraction);
            let all = passes
                .count_runs(fraction, iterations, false)
                .unwrap()
                .unwrap();
            let pixels = (w * h) as u64;
            assert!(
                runs_fit_mask(all, pixels, pixels / 4),
                "without the mask, {all} runs: {what}"
            );
            let masked = passes
                .count_runs(fraction, iterations, true)
                .unwrap()
                .unwrap();
            assert!(
                runs_fit_mask(masked, active, quads),
                "behind the mask, {masked} runs for {active} active pixels in {quads} quads: {what}"
            );
            if counter == RunCounter::AtomicCounter {
                // No helper invocation touches the counter: exactly the active pixels.
                assert_eq!(masked, active, "{what}");
            }
            let picture = passes.read().unwrap();
            for (i, (&g, &c)) in picture.iter().zip(&cpu).enumerate() {
                assert!(
                    (g as f64 - c).abs() <= 2e-5,
                    "{what}, pixel {i}: {g} vs {c}"
                );
            }
        }
    }
}
