//! Lecture 3, technique 2: pyramidal displacement mapping on the GPU against an exact CPU
//! ray tracer of the same bilinear height field, and relief mapping's artifacts at grazing
//! angles.
//!
//! Tolerance (`displacement::compare`): the GPU's hit must lie between the exact hits of the
//! field raised and lowered by DELTA = 1e-4 (the map spans 0..1; fp32 rounding is ~1e-5
//! here), within SLACK = 1e-4 world units of ray parameter; pixels where that perturbation
//! changes the surface hit are ill-conditioned and counted apart (they must stay few). The
//! written depth must be the hit's depth within 1e-5. The bound pyramid is max-only, so it
//! must equal the CPU's exactly.

use classic_gpgpu::gl::{Texture, TextureFormat};
use classic_gpgpu::lecture3::displacement::bounds::{cpu_bound_pyramid, BoundPyramidBuilder};
use classic_gpgpu::lecture3::displacement::compare::compare;
use classic_gpgpu::lecture3::displacement::{Camera, DisplacementRenderer, Method, Pixel, Surface};
use classic_gpgpu::lecture3::pyramid::Extreme;
use classic_gpgpu::lecture3::HeightMap;
use common::context;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod common;

fn rough_map(w: u32, h: u32, seed: u64) -> HeightMap {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let heights = (0..w * h).map(|_| rng.gen_range(0.0..1.0)).collect();
    HeightMap::new("rough test map", w, h, heights).unwrap()
}

fn view(surface: &Surface, azimuth: f32, elevation: f32, size: u32) -> Camera {
    Camera::orbit(surface.centre(), 3.2, azimuth, elevation, size, size)
}

#[test]
fn the_bound_pyramid_on_the_gpu_equals_the_cpu_one() {
    let ctx = context();
    let builder = BoundPyramidBuilder::new(&ctx).unwrap();
    for map in [
        HeightMap::generated(32),
        rough_map(20, 13, 1),
        rough_map(2, 9, 2),
    ] {
        let heights = Texture::from_f32(
            &ctx,
            map.width(),
            map.height(),
            TextureFormat::R32F,
            map.heights(),
        )
        .unwrap();
        let gpu = builder
            .build(&heights, map.patches(), Extreme::Max)
            .unwrap()
            .read_levels()
            .unwrap();
        assert_eq!(
            gpu,
            cpu_bound_pyramid(&map, Extreme::Max),
            "{}x{}",
            map.width(),
            map.height()
        );
    }
}

/// Renders `camera`'s frame with `method` and compares it with the exact tracer.
fn check_view(
    renderer: &DisplacementRenderer,
    camera: &Camera,
    method: Method,
) -> classic_gpgpu::lecture3::displacement::compare::Comparison {
    let target = renderer.target(camera.width, camera.height).unwrap();
    renderer.render(&target, camera, method).unwrap();
    let frame = renderer.read(&target).unwrap();
    let pixels = frame.pixels();
    // Depth: the hit's window depth.
    for (i, p) in pixels.iter().enumerate() {
        match *p {
            Pixel::Hit { grid, .. } => {
                let world = renderer.surface().grid_to_world(grid);
                let expected = camera.depth_of(world);
                assert!(
                    (frame.depth[i] as f64 - expected).abs() <= 1e-5,
                    "pixel {i}: depth {} vs {expected}",
                    frame.depth[i]
                );
            }
            _ => assert_eq!(frame.depth[i], 1.0, "pixel {i}: no hit, yet a depth"),
        }
    }
    compare(renderer.surface(), camera, &pixels)
}

#[test]
fn pyramid_traversal_finds_the_exact_hit_in_every_view() {
    let ctx = context();
    let maps = [
        (HeightMap::generated(32), 0.25),
        (rough_map(20, 13, 3), 0.4),
        (rough_map(9, 30, 4), 0.15),
    ];
    for (map, depth) in maps {
        let name = format!("{}x{} map", map.width(), map.height());
        let renderer = DisplacementRenderer::new(&ctx, Surface::new(map, depth).unwrap()).unwrap();
        for (azimuth, elevation) in [
            (30.0, 60.0),
            (200.0, 25.0),
            (120.0, 8.0),
            (300.0, 3.0),
            (45.0, 89.0),
        ] {
            let camera = view(renderer.surface(), azimuth, elevation, 48);
            let c = check_view(&renderer, &camera, Method::Pyramid);
            let what = format!("{name}, azimuth {azimuth}, elevation {elevation}: {c:?}");
            assert_eq!(c.unfinished, 0, "{what}");
            assert!(c.compared > 100 && c.exact_hits > 80, "{what}");
            assert_eq!(c.outside_tolerance, 0, "{what}");
            assert_eq!(c.wrong_surface, 0, "{what}");
            assert!(
                c.ambiguous * 50 <= c.compared,
                "too many ill-conditioned pixels: {what}"
            );
        }
    }
}

#[test]
fn relief_mapping_misses_thin_features_at_grazing_angles_and_the_pyramid_does_not() {
    let ctx = context();
    let surface = Surface::new(HeightMap::generated(64), 0.3).unwrap();
    let renderer = DisplacementRenderer::new(&ctx, surface).unwrap();
    // Looking across the thin walls of the bottom-left quadrant, low over the surface.
    let camera = view(renderer.surface(), 225.0, 6.0, 64);
    let pyramid = check_view(&renderer, &camera, Method::Pyramid);
    let relief = check_view(&renderer, &camera, Method::RELIEF);
    assert_eq!(pyramid.wrong_surface, 0, "{pyramid:?}");
    assert!(
        relief.wrong_surface > 10,
        "relief mapping is expected to step over thin walls here: {relief:?}"
    );
    // Seen from straight above, relief mapping's steps are short enough: no artifacts.
    let above = view(renderer.surface(), 0.0, 89.0, 64);
    assert_eq!(
        check_view(&renderer, &above, Method::RELIEF).wrong_surface,
        0
    );
}

#[test]
fn the_bound_pyramid_atlas_holds_every_level() {
    let ctx = context();
    for map in [
        HeightMap::generated(32),
        rough_map(20, 13, 1),
        rough_map(2, 9, 2),
    ] {
        let cpu = cpu_bound_pyramid(&map, Extreme::Max);
        let renderer = DisplacementRenderer::new(&ctx, Surface::new(map, 0.2).unwrap()).unwrap();
        let atlas = renderer.bounds_atlas();
        assert_eq!(atlas.levels() as usize, cpu.len());
        for (level, c) in cpu.iter().enumerate() {
            assert_eq!(atlas.sizes[level], (c.width, c.height));
            assert_eq!(
                atlas.read_level(level as u32).unwrap(),
                c.values,
                "level {level}"
            );
        }
    }
}
