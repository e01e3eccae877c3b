//! Table 8: octrees on the GPU, built by reduction and cast through ([`super::octree`]).

use super::octree::POINTS;
use super::results::Lecture3Results;
use crate::lecture3::octree::reference::CastComparison;
use crate::report::Table;

pub fn table(results: &Lecture3Results) -> Table {
    let image = results.octree.first().map_or(0, |r| r.image);
    Table {
        caption: format!(
            "8. Octrees on the GPU: {POINTS} random points on a sphere, a torus and a cluster \
             voxelized, the occupancy octree built by reduction passes, and {image}x{image} rays \
             cast through it against the flat voxel walk; both judged against the CPU (pixels \
             whose first voxel differs, ill-conditioned pixels apart); on {}",
            results.renderer
        ),
        header: [
            "voxels",
            "occupied",
            "levels (GPU = CPU)",
            "steps per pixel, octree",
            "steps per pixel, flat",
            "octree (ms)",
            "flat (ms)",
            "flat / octree",
            "differing from CPU: octree / flat",
            "ill-conditioned",
        ]
        .map(String::from)
        .to_vec(),
        rows: results
            .octree
            .iter()
            .map(|r| {
                let wrong = |c: &CastComparison| c.wrong_voxel + c.wrong_t + c.unfinished;
                vec![
                    format!("{0}^3", r.resolution),
                    r.occupied.to_string(),
                    format!(
                        "{} ({})",
                        r.levels,
                        if r.levels_equal { "yes" } else { "NO" }
                    ),
                    format!("{:.1}", r.octree_steps),
                    format!("{:.1}", r.flat_steps),
                    format!("{:.3}", r.octree_ms),
                    format!("{:.3}", r.flat_ms),
                    format!("{:.2}", r.flat_ms / r.octree_ms),
                    format!("{} / {}", wrong(&r.octree_vs_cpu), wrong(&r.flat_vs_cpu)),
                    r.octree_vs_cpu.ambiguous.to_string(),
                ]
            })
            .collect(),
    }
}
