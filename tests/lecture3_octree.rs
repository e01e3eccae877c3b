//! Lecture 3, octrees on the GPU: the occupancy octree built by reduction passes against the
//! CPU's (bit for bit: a max of 0/1 values is exact), and its ray cast against a flat search
//! and the CPU, pixel by pixel.
//!
//! Tolerance (`octree::reference`): pixels whose ray passes within EDGE = 1e-4 voxel of a voxel
//! edge where it changes voxels are ill-conditioned (fp32 may walk either side) and not judged;
//! they must stay few. Every other pixel's first voxel (or miss) must be the CPU's exactly, and
//! its entry parameter within T_TOL = 1e-4 world units.

use classic_gpgpu::lecture3::displacement::Camera;
use classic_gpgpu::lecture3::octree::cast::{centre, CastPixel};
use classic_gpgpu::lecture3::octree::grid::{shape_points, VoxelGrid};
use classic_gpgpu::lecture3::octree::levels::cpu_levels;
use classic_gpgpu::lecture3::octree::reference::CastReference;
use classic_gpgpu::lecture3::octree::{OctreeCaster, Search};
use common::context;
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod common;

/// A sparse random grid: `count` random points.
fn scattered(n: u32, count: usize, seed: u64) -> VoxelGrid {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let points: Vec<Vec3> = (0..count)
        .map(|_| Vec3::new(rng.gen(), rng.gen(), rng.gen()))
        .collect();
    VoxelGrid::from_points(n, &points).unwrap()
}

#[test]
fn the_octree_levels_on_the_gpu_equal_the_cpu_ones() {
    let ctx = context();
    for grid in [
        VoxelGrid::from_points(32, &shape_points(3000, 1)).unwrap(),
        scattered(16, 40, 2),
        scattered(8, 1, 3),
        scattered(2, 3, 4),
    ] {
        let caster = OctreeCaster::new(&ctx, &grid).unwrap();
        let gpu = caster.levels.read().unwrap();
        let cpu = cpu_levels(&grid);
        assert_eq!(gpu.len(), cpu.len());
        assert_eq!(gpu, cpu, "{}^3 grid", grid.n);
        assert_eq!(
            cpu.last().unwrap().occupied,
            vec![(grid.count() > 0) as u32 as f32]
        );
    }
}

#[test]
fn octree_and_flat_casts_find_the_cpus_first_voxel() {
    let ctx = context();
    for (grid, views) in [
        (
            VoxelGrid::from_points(32, &shape_points(4000, 5)).unwrap(),
            vec![(3.5, 30.0, 20.0), (5.0, 200.0, -35.0), (2.2, 120.0, 70.0)],
        ),
        (
            scattered(16, 60, 6),
            vec![(4.0, 45.0, 30.0), (1.0, 10.0, 5.0)],
        ),
        (scattered(64, 300, 7), vec![(3.5, 60.0, 20.0)]),
    ] {
        let caster = OctreeCaster::new(&ctx, &grid).unwrap();
        let cpu = cpu_levels(&grid);
        for (distance, azimuth, elevation) in views {
            let camera = Camera::orbit(centre(), distance, azimuth, elevation, 40, 40);
            let reference = CastReference::trace(&cpu, &camera);
            let target = caster.target(40, 40).unwrap();
            let mut steps = Vec::new();
            for search in [Search::Octree, Search::Flat] {
                caster.cast(&target, &camera, search).unwrap();
                let frame = caster.read(&target).unwrap();
                let c = reference.judge(&frame);
                let what = format!(
                    "{}^3, {search:?}, view {distance} {azimuth} {elevation}: {c:?}",
                    grid.n
                );
                assert_eq!(c.unfinished, 0, "{what}");
                assert_eq!(c.wrong_voxel, 0, "{what}");
                assert_eq!(c.wrong_t, 0, "{what}");
                assert_eq!(c.cpu_octree_vs_flat, 0, "{what}");
                assert!(c.ambiguous * 50 <= c.pixels, "{what}");
                assert!(c.cpu_hits > 20 || grid.n == 64, "{what}");
                let hits: Vec<f64> = frame
                    .pixels()
                    .iter()
                    .map(|p| match p {
                        CastPixel::Hit { steps, .. } => *steps as f64,
                        _ => 0.0,
                    })
                    .collect();
                steps
                    .push(frame.steps().iter().map(|&s| s as f64).sum::<f64>() / hits.len() as f64);
                if search == Search::Octree {
                    // The shader's step count is the CPU traversal's (same rule).
                    assert!(
                        (steps[0] - c.cpu_octree_steps).abs() < 0.05 * c.cpu_octree_steps + 0.5,
                        "{what}: {steps:?}"
                    );
                }
            }
            eprintln!(
                "{}^3, view {distance} {azimuth} {elevation}: steps {steps:?}",
                grid.n
            );
            // Where rays cross much empty space (300 points in 64^3 voxels), the octree takes
            // fewer steps than the flat walk.
            if grid.n == 64 {
                assert!(
                    steps[0] < steps[1],
                    "octree {steps:?} vs flat steps per pixel"
                );
            }
        }
    }
}
