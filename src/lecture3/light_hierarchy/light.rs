//! The CPU reference of the gathers, in f64: the irradiance a VPL or cluster gives a
//! receiver (the formula of `glsl/lecture3/vpl_common.glsl`), the brute-force sum over every
//! VPL, and the hierarchical search (recursive here, stackless on the GPU).

use super::clusters::{Cluster, ClusterLevel};
use glam::DVec3;
use serde::Serialize;

/// A surface point that receives light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Receiver {
    pub position: DVec3,
    pub normal: DVec3,
}

/// E = flux cos_l cos_r / (pi max(d, d_min)^2), cos_l against the cluster's mean normal.
pub fn irradiance(r: &Receiver, light: &Cluster, min_distance: f64) -> DVec3 {
    let to_light = light.position.as_dvec3() - r.position;
    let d2 = to_light.length_squared();
    if d2 < 1e-12 {
        return DVec3::ZERO;
    }
    let w = to_light / d2.sqrt();
    let cos_r = r.normal.dot(w).max(0.0);
    let cos_l = (-light.normal.as_dvec3().dot(w)).max(0.0);
    light.flux.as_dvec3() * (cos_l * cos_r / (std::f64::consts::PI * d2.max(min_distance.powi(2))))
}

/// The sum over every VPL of level 0.
pub fn brute_force(r: &Receiver, vpls: &ClusterLevel, min_distance: f64) -> DVec3 {
    vpls.nodes
        .iter()
        .filter(|l| l.weight > 0.0)
        .map(|l| irradiance(r, l, min_distance))
        .sum()
}

/// [`brute_force`] at every receiver (`None` where a pixel holds none), on every core of the
/// machine; also returns the number of threads.
pub fn brute_force_all(
    receivers: &[Option<Receiver>],
    vpls: &ClusterLevel,
    min_distance: f64,
) -> (Vec<Option<DVec3>>, usize) {
    crate::lecture3::map_on_all_cores(receivers, |r| {
        r.map(|r| brute_force(&r, vpls, min_distance))
    })
}

/// What a light (a VPL or a cluster) gives a receiver, and how far it is for the criterion:
/// the indirect light's irradiance here, the dipole of [`super::subsurface`] and the
/// directional sky lights of [`super::environment`] on the same traversal.
pub trait Kernel {
    /// The contribution of `light` (one VPL or a cluster taken as one) to `r`.
    fn light(&self, r: &Receiver, light: &Cluster) -> DVec3;
    /// The distance the criterion compares the cluster's radius with.
    fn distance(&self, r: &Receiver, light: &Cluster) -> f64;
}

/// The indirect light of VPLs: [`irradiance`] and the distance between the points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VplKernel {
    pub min_distance: f64,
}

impl Kernel for VplKernel {
    fn light(&self, r: &Receiver, light: &Cluster) -> DVec3 {
        irradiance(r, light, self.min_distance)
    }
    fn distance(&self, r: &Receiver, light: &Cluster) -> f64 {
        light.position.as_dvec3().distance(r.position)
    }
}

/// The sum of `kernel` over every light of level 0.
pub fn brute_force_with(r: &Receiver, lights: &ClusterLevel, kernel: &impl Kernel) -> DVec3 {
    lights
        .nodes
        .iter()
        .filter(|l| l.weight > 0.0)
        .map(|l| kernel.light(r, l))
        .sum()
}

/// When a cluster is taken as one light: radius < theta x distance, and (normal-aware
/// clustering, [`super::normal_cone`]) the length of its mean normal at least `min_coherence`
/// (0: the fixed merge, every cluster passes).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Criterion {
    pub theta: f64,
    pub min_coherence: f64,
}

impl Criterion {
    /// The distance criterion alone.
    pub fn theta(theta: f64) -> Criterion {
        Criterion {
            theta,
            min_coherence: 0.0,
        }
    }
}

/// What the hierarchical search found for one receiver.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TreeGather {
    pub irradiance: DVec3,
    /// Nodes visited (as the GPU counts them).
    pub visited: u32,
    /// Lights (VPLs or clusters) summed.
    pub gathered: u32,
    /// The smallest |radius - theta d| / (theta d) over the decisions taken: near 0, fp32 may
    /// decide the other way.
    pub margin: f64,
}

/// The hierarchical search with criterion radius < theta x distance.
pub fn tree_gather(
    r: &Receiver,
    levels: &[ClusterLevel],
    theta: f64,
    min_distance: f64,
) -> TreeGather {
    tree_gather_with(
        r,
        levels,
        Criterion::theta(theta),
        &VplKernel { min_distance },
    )
}

/// The hierarchical search of `levels` with `criterion` and `kernel`.
pub fn tree_gather_with(
    r: &Receiver,
    levels: &[ClusterLevel],
    criterion: Criterion,
    kernel: &impl Kernel,
) -> TreeGather {
    let mut out = TreeGather {
        irradiance: DVec3::ZERO,
        visited: 0,
        gathered: 0,
        margin: f64::INFINITY,
    };
    let search = Search {
        r,
        levels,
        criterion,
        kernel,
    };
    search.visit(levels.len() - 1, 0, 0, &mut out);
    out
}

struct Search<'a, K> {
    r: &'a Receiver,
    levels: &'a [ClusterLevel],
    criterion: Criterion,
    kernel: &'a K,
}

impl<K: Kernel> Search<'_, K> {
    fn visit(&self, level: usize, x: u32, y: u32, out: &mut TreeGather) {
        out.visited += 1;
        let node = self.levels[level].at(x, y);
        if node.weight <= 0.0 {
            return;
        }
        let theta = self.criterion.theta;
        let d = self.kernel.distance(self.r, node);
        let coherent = node.normal.as_dvec3().length() >= self.criterion.min_coherence;
        if level > 0 && theta > 0.0 && d > 0.0 {
            let margin = (node.radius as f64 - theta * d).abs() / (theta * d);
            out.margin = out.margin.min(margin);
        }
        if level > 0 && self.criterion.min_coherence > 0.0 && (node.radius as f64) < theta * d {
            let length = node.normal.as_dvec3().length();
            let margin =
                (length - self.criterion.min_coherence).abs() / self.criterion.min_coherence;
            out.margin = out.margin.min(margin);
        }
        if level == 0 || ((node.radius as f64) < theta * d && coherent) {
            out.irradiance += self.kernel.light(self.r, node);
            out.gathered += 1;
            return;
        }
        // Children in Morton order, as the GPU visits them.
        for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            self.visit(level - 1, 2 * x + dx, 2 * y + dy, out);
        }
    }
}
