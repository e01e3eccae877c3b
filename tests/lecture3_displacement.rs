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
use classic_gpgpu::lecture3::displacement::compare::{compare, Comparison};
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
fn check_view(renderer: &DisplacementRenderer, camera: &Camera, method: Method) -> Comparison {
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
    compare(renderer.surface(), camera, &frame)
}

/// Asserts that every compared pixel of `c` stops at the exact hit and is drawn as it is:
/// surface or wall, normal, colour.
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
            assert!(c.compared > 100 && c.exact_hits > 80, "{what}");
            assert_exact(&c, &what);
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

/// A checkerboard of `block`-sample squares at heights `low` and `high`: flat plateaus whose
/// tops lie exactly on the bound planes of the pyramid's nodes.
fn checkerboard(side: u32, block: u32, low: f32, high: f32) -> HeightMap {
    let heights = (0..side * side)
        .map(|i| {
            let (x, y) = (i % side / block, i / side / block);
            if (x + y) % 2 == 0 {
                high
            } else {
                low
            }
        })
        .collect();
    HeightMap::new("checkerboard", side, side, heights).unwrap()
}

/// A rough map with a flat square plateau in the middle, above everything around it.
fn plateau(side: u32, seed: u64) -> HeightMap {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (lo, hi) = (side / 4, side - side / 4);
    let heights = (0..side * side)
        .map(|i| {
            let (x, y) = (i % side, i / side);
            if (lo..hi).contains(&x) && (lo..hi).contains(&y) {
                0.7
            } else {
                rng.gen_range(0.0..0.5)
            }
        })
        .collect();
    HeightMap::new("plateau", side, side, heights).unwrap()
}

/// Terraces: a smooth hill cut into `steps` flat levels.
fn terraces(side: u32, steps: u32) -> HeightMap {
    let c = (side - 1) as f32 / 2.0;
    let heights = (0..side * side)
        .map(|i| {
            let (x, y) = ((i % side) as f32 - c, (i / side) as f32 - c);
            let hill = (1.0 - (x * x + y * y).sqrt() / (1.5 * c)).clamp(0.0, 1.0);
            (hill * steps as f32).floor() / steps as f32
        })
        .collect();
    HeightMap::new("terraces", side, side, heights).unwrap()
}

#[test]
fn flat_plateau_tops_are_drawn_as_surface_not_as_wall() {
    let ctx = context();
    // The views where plateau tops were drawn as walls: a checkerboard at 60 degrees, a
    // plateau at 20.
    for (map, depth, azimuth, elevation) in [
        (checkerboard(32, 4, 0.2, 0.8), 0.25, 30.0, 60.0),
        (plateau(24, 5), 0.3, 200.0, 20.0),
    ] {
        let name = format!("{}x{} map", map.width(), map.height());
        let renderer = DisplacementRenderer::new(&ctx, Surface::new(map, depth).unwrap()).unwrap();
        let camera = view(renderer.surface(), azimuth, elevation, 48);
        let c = check_view(&renderer, &camera, Method::Pyramid);
        assert_exact(&c, &format!("{name} at {elevation} degrees: {c:?}"));
    }
}

#[test]
fn plateaus_terraces_and_checkerboards_are_drawn_right_from_steep_to_grazing() {
    let ctx = context();
    let maps = [
        (checkerboard(32, 4, 0.2, 0.8), 0.25),
        // Plateaus at the box's top: rays enter through the top onto them. (Not at 0: a floor
        // on the box's bottom is ill-conditioned for the comparison, the field lowered by
        // DELTA lying outside the box.)
        (checkerboard(17, 3, 0.1, 1.0), 0.3),
        (plateau(24, 6), 0.3),
        (terraces(29, 5), 0.35),
    ];
    for (map, depth) in maps {
        let name = format!("{}x{} map", map.width(), map.height());
        let renderer = DisplacementRenderer::new(&ctx, Surface::new(map, depth).unwrap()).unwrap();
        for (azimuth, elevation) in [(30.0, 60.0), (110.0, 35.0), (200.0, 20.0), (300.0, 4.0)] {
            let camera = view(renderer.surface(), azimuth, elevation, 40);
            let c = check_view(&renderer, &camera, Method::Pyramid);
            let what = format!("{name}, azimuth {azimuth}, elevation {elevation}: {c:?}");
            assert!(c.compared > 100, "{what}");
            assert_exact(&c, &what);
        }
    }
}
