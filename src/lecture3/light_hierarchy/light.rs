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

/// What the hierarchical search found for one receiver.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TreeGather {
    pub irradiance: DVec3,
    /// Nodes visited (as the GPU counts them).
    pub visited: u32,
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
    let mut out = TreeGather {
        irradiance: DVec3::ZERO,
        visited: 0,
        margin: f64::INFINITY,
    };
    visit(
        r,
        levels,
        levels.len() - 1,
        0,
        0,
        theta,
        min_distance,
        &mut out,
    );
    out
}

#[allow(clippy::too_many_arguments)]
fn visit(
    r: &Receiver,
    levels: &[ClusterLevel],
    level: usize,
    x: u32,
    y: u32,
    theta: f64,
    min_distance: f64,
    out: &mut TreeGather,
) {
    out.visited += 1;
    let node = levels[level].at(x, y);
    if node.weight <= 0.0 {
        return;
    }
    let d = node.position.as_dvec3().distance(r.position);
    if level > 0 && theta > 0.0 && d > 0.0 {
        let margin = (node.radius as f64 - theta * d).abs() / (theta * d);
        out.margin = out.margin.min(margin);
    }
    if level == 0 || (node.radius as f64) < theta * d {
        out.irradiance += irradiance(r, node, min_distance);
        return;
    }
    // Children in Morton order, as the GPU visits them.
    for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        visit(
            r,
            levels,
            level - 1,
            2 * x + dx,
            2 * y + dy,
            theta,
            min_distance,
            out,
        );
    }
}
