//! Octrees on the GPU (`crate::lecture3::octree`): the octree of a point set built by
//! reduction passes and its ray cast against the flat voxel walk, both checked pixel by pixel
//! against the CPU, with GPU times and steps per pixel side by side.

use super::timed::gpu_ms;
use crate::lecture3::displacement::Camera;
use crate::lecture3::octree::cast::centre;
use crate::lecture3::octree::grid::{shape_points, VoxelGrid};
use crate::lecture3::octree::levels::cpu_levels;
use crate::lecture3::octree::reference::{CastComparison, CastReference};
use crate::lecture3::octree::{OctreeCaster, Search};
use crate::report::BenchOptions;
use crate::timing::{Runs, Spread};
use serde::Serialize;

/// One grid resolution.
#[derive(Clone, Debug, Serialize)]
pub struct OctreeRow {
    pub resolution: u32,
    pub points: usize,
    pub occupied: usize,
    pub levels: usize,
    /// The GPU levels equal to the CPU's, bit for bit.
    pub levels_equal: bool,
    pub image: u32,
    pub octree_steps: f64,
    pub flat_steps: f64,
    pub octree_ms: f64,
    pub octree_spread: Spread,
    pub flat_ms: f64,
    pub flat_spread: Spread,
    pub octree_vs_cpu: CastComparison,
    pub flat_vs_cpu: CastComparison,
}

/// Points of the report's point set.
pub const POINTS: usize = 20_000;

/// Each resolution: the octree built, both casts judged and timed.
pub fn measure(opts: &BenchOptions, runs: Runs) -> anyhow::Result<Vec<OctreeRow>> {
    let ctx = opts.gl;
    let image = if opts.quick { 64 } else { 128 };
    let resolutions: &[u32] = if opts.quick { &[32] } else { &[32, 64, 128] };
    let points = shape_points(POINTS, 1);
    resolutions
        .iter()
        .map(|&resolution| {
            let voxels = VoxelGrid::from_points(resolution, &points)?;
            let caster = OctreeCaster::new(ctx, &voxels)?;
            let cpu = cpu_levels(&voxels);
            let camera = Camera::orbit(centre(), 3.5, 30.0, 25.0, image, image);
            let reference = CastReference::trace(&cpu, &camera);
            let target = caster.target(image, image)?;
            let mut judged = Vec::new();
            for search in [Search::Octree, Search::Flat] {
                caster.cast(&target, &camera, search)?;
                let frame = caster.read(&target)?;
                frame.check_finished()?;
                let steps =
                    frame.steps().iter().map(|&s| s as f64).sum::<f64>() / (image * image) as f64;
                let time = gpu_ms(ctx, runs, || Ok(caster.cast(&target, &camera, search)?))?;
                judged.push((reference.judge(&frame), steps, time));
            }
            let (flat, octree) = (judged.pop().expect("flat"), judged.pop().expect("octree"));
            Ok(OctreeRow {
                resolution,
                points: POINTS,
                occupied: voxels.count(),
                levels: cpu.len(),
                levels_equal: caster.levels.read()? == cpu,
                image,
                octree_steps: octree.1,
                flat_steps: flat.1,
                octree_ms: octree.2.median,
                octree_spread: octree.2,
                flat_ms: flat.2.median,
                flat_spread: flat.2,
                octree_vs_cpu: octree.0,
                flat_vs_cpu: flat.0,
            })
        })
        .collect()
}
