//! Normal-aware clustering: the fixed 2x2 merge joins VPLs of different surfaces (a wall and
//! the floor at a corner) into one cluster with one mean normal, and such a cluster lights a
//! receiver as if all its VPLs faced one way. Here a cluster is taken as one light only when
//! its normals also agree; otherwise its children are gathered.
//!
//! The rule (a reconstruction: the abstract speaks only of "a simple, fast clustering"): a
//! cluster is one light when radius < theta x distance **and** |n̄| >= `min_coherence`, where
//! n̄ is the flux-weighted mean of its VPLs' unit normals (the cluster's stored normal; |n̄| = 1
//! when they all agree). Normals inside a cone of half-angle a around any axis give |n̄| >=
//! cos a, so every cluster whose normals fit in no cone of half-angle acos(`min_coherence`) is
//! refined (0.9: about 26 degrees; a few dim outliers may still pass). The hierarchy is built as
//! before; only the traversal reads the mean normal's length (`vpl_gather_tree.frag`,
//! [`super::light::Criterion`]).

use super::gather::Gather;
use super::light::{tree_gather_with, VplKernel};
use super::pipeline::IndirectLighting;
use crate::lecture3::error::Error;
use serde::Serialize;

/// The coherence used by default: mean normals at least 0.9 long (cones of about 26 degrees).
pub const MIN_COHERENCE: f32 = 0.9;

/// One criterion gathered with the fixed merge and with normal-aware clustering.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClusteringRow {
    pub theta: f32,
    pub min_coherence: f32,
    /// Relative RMS error of the GPU tree search against the GPU brute force, fixed merge.
    pub fixed_error: f64,
    /// The same with normal-aware clustering.
    pub normal_aware_error: f64,
    /// Lights (VPLs or clusters) summed per receiver, on the CPU's traversal of the same
    /// hierarchy: fixed merge, normal-aware.
    pub fixed_lights: f64,
    pub normal_aware_lights: f64,
    /// Nodes visited per receiver on the GPU: fixed merge, normal-aware.
    pub fixed_nodes: f64,
    pub normal_aware_nodes: f64,
}

/// The relative RMS difference of `values` (rgb of each texel) from `reference`, over the
/// texels where `covered`.
pub fn relative_rms(values: &[[f32; 4]], reference: &[[f32; 4]], covered: &[bool]) -> f64 {
    let (mut err, mut norm) = (0.0f64, 0.0f64);
    for ((v, r), _) in values
        .iter()
        .zip(reference)
        .zip(covered)
        .filter(|(_, &c)| c)
    {
        for c in 0..3 {
            err += (v[c] as f64 - r[c] as f64).powi(2);
            norm += (r[c] as f64).powi(2);
        }
    }
    (err / norm.max(f64::MIN_POSITIVE)).sqrt()
}

/// For each theta, the fixed merge against normal-aware clustering with `min_coherence`, both
/// against the brute-force sum, on `lighting` (lights built, receivers drawn). Leaves the last
/// normal-aware gather in the target.
pub fn compare_clustering(
    lighting: &IndirectLighting,
    thetas: &[f32],
    min_coherence: f32,
) -> Result<Vec<ClusteringRow>, Error> {
    lighting.gather(Gather::BruteForce)?;
    let brute = lighting.gathers.read()?;
    let receivers = lighting.gbuffer.receivers()?;
    let covered: Vec<bool> = receivers.iter().map(Option::is_some).collect();
    let levels = lighting.clusters.read_atlas_levels()?;
    let count = covered.iter().filter(|&&c| c).count().max(1) as f64;
    let kernel = VplKernel {
        min_distance: super::gather::MIN_DISTANCE as f64,
    };
    let mut rows = Vec::with_capacity(thetas.len());
    for &theta in thetas {
        let measure = |gather: Gather| -> Result<(f64, f64, f64), Error> {
            lighting.gather(gather)?;
            let gpu = lighting.gathers.read()?;
            let criterion = gather
                .criterion()
                .ok_or_else(|| Error::Result("a tree gather has a criterion".into()))?;
            let (gathered, _) = crate::lecture3::map_on_all_cores(&receivers, |r| {
                r.map_or(0, |r| {
                    tree_gather_with(&r, &levels, criterion, &kernel).gathered as u64
                })
            });
            let lights: u64 = gathered.iter().sum();
            let nodes: f64 = gpu
                .iter()
                .zip(&covered)
                .filter(|(_, &c)| c)
                .map(|(g, _)| g[3] as f64)
                .sum();
            Ok((
                relative_rms(&gpu, &brute, &covered),
                lights as f64 / count,
                nodes / count,
            ))
        };
        let fixed = measure(Gather::tree(theta)?)?;
        let aware = measure(Gather::normal_aware(theta, min_coherence)?)?;
        rows.push(ClusteringRow {
            theta,
            min_coherence,
            fixed_error: fixed.0,
            normal_aware_error: aware.0,
            fixed_lights: fixed.1,
            normal_aware_lights: aware.1,
            fixed_nodes: fixed.2,
            normal_aware_nodes: aware.2,
        });
    }
    Ok(rows)
}
