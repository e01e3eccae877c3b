//! Lecture 3, technique 2's minification prefilter: prefiltered GPU frames against the CPU
//! reference of the same rule, pixel by pixel (where each ray stops, surface or wall, normal,
//! colour), and its speed as a property: at a far camera it takes fewer steps, close up it
//! changes nothing.
//!
//! Tolerance (`displacement::compare`): as for the unfiltered traversal, the GPU's hit lies
//! between the CPU's exact hits of the selected field raised and lowered by DELTA = 1e-4 (the
//! prefiltered corners are fp32 means of at most a few hundred samples, ~1e-6 from the CPU's
//! f64 means); pixels whose stop level fp32 rounding could change are not judged.

use classic_gpgpu::lecture3::displacement::compare::{compare_prefiltered, Comparison};
use classic_gpgpu::lecture3::displacement::prefilter::{
    cpu_prefiltered, cpu_supersampled, image_error, may_act, shown_of_rgba8, stop_level, Prefilter,
    Shown,
};
use classic_gpgpu::lecture3::displacement::tracer::supersampled;
use classic_gpgpu::lecture3::displacement::{Camera, DisplacementRenderer, Method, Pixel, Surface};
use classic_gpgpu::lecture3::HeightMap;
use common::context;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod common;

/// Random heights with a smooth swell, `side x side` samples.
fn rough_map(side: u32, seed: u64) -> HeightMap {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let heights = (0..side * side)
        .map(|i| {
            let (x, y) = (
                (i % side) as f32 / side as f32,
                (i / side) as f32 / side as f32,
            );
            let swell = 0.3 + 0.2 * (6.0 * x).sin() * (5.0 * y).cos();
            (swell + rng.gen_range(-0.25..0.25f32)).clamp(0.0, 1.0)
        })
        .collect();
    HeightMap::new("rough test map", side, side, heights).unwrap()
}

fn camera(surface: &Surface, distance: f32, azimuth: f32, elevation: f32, size: u32) -> Camera {
    Camera::orbit(surface.centre(), distance, azimuth, elevation, size, size)
}

fn render(renderer: &DisplacementRenderer, camera: &Camera, method: Method) -> (Shown, f64) {
    let target = renderer.target(camera.width, camera.height).unwrap();
    renderer.render(&target, camera, method).unwrap();
    let frame = renderer.read(&target).unwrap();
    frame.check_finished().unwrap();
    let steps: Vec<f64> = frame
        .pixels()
        .iter()
        .filter_map(|p| match p {
            Pixel::Hit { iterations, .. } => Some(*iterations as f64),
            _ => None,
        })
        .collect();
    let mean_steps = steps.iter().sum::<f64>() / steps.len().max(1) as f64;
    (shown_of_rgba8(&frame.colour), mean_steps)
}

fn assert_exact(c: &Comparison, what: &str) {
    assert_eq!(c.unfinished, 0, "{what}");
    assert_eq!(c.outside_tolerance, 0, "{what}");
    assert_eq!(c.wrong_surface, 0, "{what}");
    assert_eq!(
        c.wrong_kind, 0,
        "surface drawn as wall or the reverse: {what}"
    );
    assert_eq!(c.wrong_normal, 0, "{what}");
    assert_eq!(c.wrong_colour, 0, "{what}");
    assert!(
        c.ambiguous * 50 <= c.compared,
        "too many ill-conditioned pixels: {what}"
    );
}

/// Of the pixels whose stop level is above 0, how many hit on a prefiltered patch (a covered
/// node above level 0) and how many on a finest patch (no node over it covered).
fn hits_by_cut(surface: &Surface, camera: &Camera) -> (usize, usize) {
    let rule = Prefilter::new(surface, camera);
    let eye = camera.eye.as_dvec3();
    let scale = surface.world_to_grid().as_dvec3();
    let (wp, hp) = surface.patches();
    let (mut coarse, mut finest) = (0, 0);
    for (x, y) in (0..camera.height).flat_map(|y| (0..camera.width).map(move |x| (x, y))) {
        let dir = camera.pixel_direction(x, y);
        let Some((t_in, _)) = classic_gpgpu::lecture3::displacement::exact::box_interval(
            eye * scale,
            dir * scale,
            wp as f64,
            hp as f64,
        ) else {
            continue;
        };
        let traced = rule.trace_ray(surface, eye, dir, t_in, 0.0);
        let Some(hit) = traced.hit.filter(|_| traced.level > 0) else {
            continue;
        };
        let cell = (
            (hit.grid.x.floor().max(0.0) as u32).min(wp - 1),
            (hit.grid.y.floor().max(0.0) as u32).min(hp - 1),
        );
        match rule.cut_level(cell, dir.z.abs(), rule.footprint_at(t_in)).0 {
            0 => finest += 1,
            _ => coarse += 1,
        }
    }
    (coarse, finest)
}

/// How many compared pixels the rule sends above level 0.
fn prefiltered_pixels(surface: &Surface, camera: &Camera) -> usize {
    let rule = Prefilter::new(surface, camera);
    let eye = camera.eye.as_dvec3();
    let scale = surface.world_to_grid().as_dvec3();
    let (wp, hp) = surface.patches();
    (0..camera.height)
        .flat_map(|y| (0..camera.width).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let d = camera.pixel_direction(x, y) * scale;
            classic_gpgpu::lecture3::displacement::exact::box_interval(
                eye * scale,
                d,
                wp as f64,
                hp as f64,
            )
            .is_some_and(|(t0, _)| stop_level(rule.footprint_at(t0), rule.top) > 0)
        })
        .count()
}

#[test]
fn prefiltered_frames_equal_the_cpu_reference_of_the_same_rule() {
    let ctx = context();
    for (map, depth) in [
        (rough_map(65, 1), 0.3),
        (rough_map(40, 2), 0.2),
        (HeightMap::generated(64), 0.3),
    ] {
        let name = format!("{}x{} map", map.width(), map.height());
        let renderer = DisplacementRenderer::new(&ctx, Surface::new(map, depth).unwrap()).unwrap();
        let (mut compared, mut prefiltered) = (0, 0);
        let (mut coarse, mut finest) = (0, 0);
        for (distance, azimuth, elevation) in [
            (5.0, 30.0, 60.0),
            (8.0, 200.0, 35.0),
            (10.0, 120.0, 12.0),
            (14.0, 300.0, 80.0),
        ] {
            let camera = camera(renderer.surface(), distance, azimuth, elevation, 48);
            let target = renderer.target(48, 48).unwrap();
            renderer
                .render(&target, &camera, Method::Prefiltered)
                .unwrap();
            let frame = renderer.read(&target).unwrap();
            let c = compare_prefiltered(renderer.surface(), &camera, &frame);
            let what = format!("{name}, distance {distance}, elevation {elevation}: {c:?}");
            assert!(c.compared > 40 && c.exact_hits > 30, "{what}");
            assert_exact(&c, &what);
            compared += c.compared;
            prefiltered += prefiltered_pixels(renderer.surface(), &camera);
            let (c, f) = hits_by_cut(renderer.surface(), &camera);
            (coarse, finest) = (coarse + c, finest + f);
        }
        // The rule sent a good share of the pixels above level 0 (else this compared little that is new).
        assert!(
            prefiltered * 4 > compared,
            "{name}: {prefiltered} of {compared}"
        );
        // Both kinds of hit of such pixels were judged: on prefiltered patches and on the
        // finest patches where no node is covered.
        assert!(
            coarse > 50 && finest > 50,
            "{name}: {coarse} hits on prefiltered patches, {finest} on finest ones"
        );
    }
}

/// The prefilter's speed as a property: far away it stops the descent early, so a hit pixel
/// takes fewer traversal steps; close up (every footprint under 2 patches) it changes nothing.
#[test]
fn far_away_the_prefilter_takes_fewer_steps_and_close_up_it_changes_nothing() {
    let ctx = context();
    let surface = Surface::new(rough_map(129, 3), 0.3).unwrap();
    let renderer = DisplacementRenderer::new(&ctx, surface).unwrap();
    let camera = camera(renderer.surface(), 7.0, 225.0, 40.0, 48);
    assert!(prefiltered_pixels(renderer.surface(), &camera) > 200);
    let (plain, plain_steps) = render(&renderer, &camera, Method::Pyramid);
    let (filtered, filtered_steps) = render(&renderer, &camera, Method::Prefiltered);
    assert_ne!(plain, filtered);
    assert!(
        filtered_steps < plain_steps,
        "steps per hit pixel: prefiltered {filtered_steps}, unfiltered {plain_steps}"
    );
    // The supersampled reference and the error are finite and the reference is not the
    // 1-ray image (its pixels average 64 rays).
    let reference = supersampled(&renderer, &camera, 8).unwrap();
    let error = image_error(&plain, &reference);
    assert!(error.is_finite() && error > 0.0);
    assert!(image_error(&plain, &supersampled(&renderer, &camera, 1).unwrap()) < 1e-6);
    // Close up (every footprint under 2 patches) the two traversals draw the same image.
    let near = camera_near(renderer.surface());
    assert_eq!(prefiltered_pixels(renderer.surface(), &near), 0);
    // The renderer skips drawing the shading pyramid there, and only there.
    assert!(!may_act(&near, renderer.surface()) && may_act(&camera, renderer.surface()));
    assert_eq!(
        render(&renderer, &near, Method::Pyramid).0,
        render(&renderer, &near, Method::Prefiltered).0
    );
}

fn camera_near(surface: &Surface) -> Camera {
    camera(surface, 1.2, 225.0, 50.0, 96)
}

/// Quality, the abstract's claim: seen at 35 and 70 degrees, from a middle and a far distance, where each pixel covers many patches, the prefiltered frame (shaded as
/// the facets facing the eye) is closer to the supersampled unfiltered image (8x8 rays per
/// pixel) than the unfiltered frame (one ray per pixel) is, by at least `MARGIN` of the
/// unfiltered error; on the GPU and by the CPU reference of the same rule (exact f64 traces of
/// every sub-pixel ray and of the rule, shaded alike), which agree to `AGREE` (8-bit colours,
/// and the few pixels whose hit fp32 moves across a checker edge).
///
/// The report's own map and views are judged in the two tests after this one.
#[test]
fn from_far_away_the_prefiltered_frame_is_closer_to_the_supersampled_image() {
    const MARGIN: f64 = 0.3;
    const AGREE: f64 = 0.01;
    let ctx = context();
    for (map, distance) in [(rough_map(129, 3), 7.0), (rough_map(129, 4), 12.0)] {
        let surface = Surface::new(map, 0.3).unwrap();
        let renderer = DisplacementRenderer::new(&ctx, surface).unwrap();
        for elevation in [35.0, 70.0] {
            let camera = camera(renderer.surface(), distance, 225.0, elevation, 64);
            let acting = prefiltered_pixels(renderer.surface(), &camera);
            assert!(
                acting > 100,
                "elevation {elevation}: {acting} pixels stop above level 0"
            );
            let reference = supersampled(&renderer, &camera, 8).unwrap();
            let plain = image_error(&render(&renderer, &camera, Method::Pyramid).0, &reference);
            let filtered = image_error(
                &render(&renderer, &camera, Method::Prefiltered).0,
                &reference,
            );
            let surface = renderer.surface();
            let cpu_reference = cpu_supersampled(surface, &camera, 8);
            let cpu_plain = image_error(&cpu_supersampled(surface, &camera, 1), &cpu_reference);
            let cpu_filtered = image_error(&cpu_prefiltered(surface, &camera), &cpu_reference);
            let what = format!(
                "distance {distance}, elevation {elevation}: GPU unfiltered {plain:.4} \
                 prefiltered {filtered:.4}; CPU unfiltered {cpu_plain:.4} prefiltered \
                 {cpu_filtered:.4}"
            );
            eprintln!("{what}");
            assert!(filtered <= (1.0 - MARGIN) * plain, "{what}");
            assert!(cpu_filtered <= (1.0 - MARGIN) * cpu_plain, "{what}");
            assert!(
                (plain - cpu_plain).abs() <= AGREE && (filtered - cpu_filtered).abs() <= AGREE,
                "{what}"
            );
        }
    }
}

/// The report's views of its generated map (thin tall walls, bumps, rings), where the rule
/// without the covered-node test made frames worse than no prefilter: at each of the report's
/// elevations, grazing included, the prefiltered frame is closer to the supersampled image
/// (4x4 rays per pixel, as the report's) than the unfiltered one; from the farthest distance
/// (stop levels up to 2 and 3) by at least `FAR_MARGIN` of the unfiltered error.
fn report_views() -> Vec<(f32, f32, bool)> {
    [15.0, 35.0, 70.0]
        .into_iter()
        .flat_map(|elevation| {
            [(12.8, false), (25.6, true)]
                .into_iter()
                .map(move |(distance, far)| (elevation, distance, far))
        })
        .collect()
}

const FAR_MARGIN: f64 = 0.15;

fn assert_better(unfiltered: f64, prefiltered: f64, far: bool, what: &str) {
    assert!(unfiltered.is_finite() && prefiltered.is_finite(), "{what}");
    assert!(prefiltered < unfiltered, "worse with the prefilter: {what}");
    if far {
        assert!(
            prefiltered <= (1.0 - FAR_MARGIN) * unfiltered,
            "not better by {FAR_MARGIN} from far away: {what}"
        );
    }
}

/// On the GPU at the report's quick size (64x64), and by the CPU reference, which agree to
/// `AGREE` (8-bit colours, and pixels whose hit fp32 moves across a checker edge).
#[test]
fn on_the_report_map_the_prefilter_is_better_at_every_elevation() {
    const AGREE: f64 = 0.01;
    let ctx = context();
    let surface = Surface::new(HeightMap::generated(64), 0.3).unwrap();
    let renderer = DisplacementRenderer::new(&ctx, surface).unwrap();
    for (elevation, distance, far) in report_views() {
        let camera = camera(renderer.surface(), distance, 225.0, elevation, 64);
        assert!(prefiltered_pixels(renderer.surface(), &camera) > 20);
        let reference = supersampled(&renderer, &camera, 4).unwrap();
        let plain = image_error(&render(&renderer, &camera, Method::Pyramid).0, &reference);
        let filtered = image_error(
            &render(&renderer, &camera, Method::Prefiltered).0,
            &reference,
        );
        let surface = renderer.surface();
        let cpu_reference = cpu_supersampled(surface, &camera, 4);
        let cpu_plain = image_error(&cpu_supersampled(surface, &camera, 1), &cpu_reference);
        let cpu_filtered = image_error(&cpu_prefiltered(surface, &camera), &cpu_reference);
        let what = format!(
            "64x64, distance {distance}, elevation {elevation}: GPU unfiltered {plain:.4} \
             prefiltered {filtered:.4}; CPU unfiltered {cpu_plain:.4} prefiltered \
             {cpu_filtered:.4}"
        );
        eprintln!("{what}");
        assert_better(plain, filtered, far, &what);
        assert_better(cpu_plain, cpu_filtered, far, &what);
        assert!(
            (plain - cpu_plain).abs() <= AGREE && (filtered - cpu_filtered).abs() <= AGREE,
            "{what}"
        );
    }
}

/// The same at the report's full size (128x128), by the CPU reference alone (exact f64 traces
/// of every ray; the GPU frames are judged against it pixel by pixel above).
#[test]
fn at_the_full_report_size_the_cpu_reference_of_the_prefilter_is_better_at_every_elevation() {
    let surface = Surface::new(HeightMap::generated(64), 0.3).unwrap();
    for (elevation, distance, far) in report_views() {
        let camera = camera(&surface, distance, 225.0, elevation, 128);
        assert!(prefiltered_pixels(&surface, &camera) > 50);
        let reference = cpu_supersampled(&surface, &camera, 4);
        let plain = image_error(&cpu_supersampled(&surface, &camera, 1), &reference);
        let filtered = image_error(&cpu_prefiltered(&surface, &camera), &reference);
        let what = format!(
            "128x128, distance {distance}, elevation {elevation}: unfiltered {plain:.4} \
             prefiltered {filtered:.4}"
        );
        eprintln!("{what}");
        assert_better(plain, filtered, far, &what);
    }
}
