//! The CPU reference: brute force over time. Every link's capsule against every environment
//! triangle at densely sampled times, each distance from parry3d (an independent library,
//! fp32), with no bounds, culling or advancement.

use super::body::{Body, Keyframes};
use super::environment::Environment;
use parry3d::math::{Pose, Vector};
use parry3d::shape::{Capsule, Triangle};

/// What the samples saw.
#[derive(Clone, Copy, Debug)]
pub struct Sampled {
    /// Time between samples.
    pub step: f64,
    /// The first sample whose smallest gap is within the tolerance, with its link.
    pub first_within_tolerance: Option<(f64, usize)>,
    /// The first sample with an overlap (a gap of at most zero).
    pub first_overlap: Option<f64>,
    /// The smallest gap of all samples.
    pub min_gap: f64,
}

/// The environment's triangles as parry3d shapes.
pub fn shapes(env: &Environment) -> Vec<Triangle> {
    let v = |p: glam::DVec3| Vector::new(p.x as f32, p.y as f32, p.z as f32);
    env.triangles
        .iter()
        .map(|t| Triangle::new(v(t[0]), v(t[1]), v(t[2])))
        .collect()
}

/// The smallest gap (capsule to triangle distance, parry3d) at time `t`, and its link.
pub fn gap_at(body: &Body, keyframes: &Keyframes, triangles: &[Triangle], t: f64) -> (f64, usize) {
    let v = |p: glam::DVec3| Vector::new(p.x as f32, p.y as f32, p.z as f32);
    let identity = Pose::identity();
    let mut best = (f64::INFINITY, 0);
    for (k, c) in body.capsules(&keyframes.pose_at(t)).iter().enumerate() {
        let capsule = Capsule::new(v(c.a), v(c.b), c.radius as f32);
        for tri in triangles {
            let d = parry3d::query::distance(&identity, &capsule, &identity, tri)
                .map(|d| d.distance as f64)
                .unwrap_or(f64::INFINITY);
            if d < best.0 {
                best = (d, k);
            }
        }
    }
    best
}

/// Sample `per_interval` times per keyframe interval (and the last keyframe).
pub fn sample(
    body: &Body,
    keyframes: &Keyframes,
    env: &Environment,
    per_interval: usize,
    tolerance: f64,
) -> Sampled {
    let triangles = shapes(env);
    let step = 1.0 / per_interval.max(1) as f64;
    let count = (keyframes.end() / step).round() as usize;
    let mut out = Sampled {
        step,
        first_within_tolerance: None,
        first_overlap: None,
        min_gap: f64::INFINITY,
    };
    for i in 0..=count {
        let t = (i as f64 * step).min(keyframes.end());
        let (gap, link) = gap_at(body, keyframes, &triangles, t);
        out.min_gap = out.min_gap.min(gap);
        if gap <= tolerance && out.first_within_tolerance.is_none() {
            out.first_within_tolerance = Some((t, link));
        }
        if gap <= 0.0 && out.first_overlap.is_none() {
            out.first_overlap = Some(t);
            break;
        }
    }
    out
}

/// The environment's triangles near the motion, for brute force on a large scene: those
/// whose box comes within `margin` of the box of every link's capsule at `per_interval`
/// sampled times per keyframe interval. Between two samples no link moves more than its
/// speed over the step, so with a margin far above that and above the tolerance a triangle
/// left out is never within the tolerance: the first contact is the same on the subset.
/// The box test is this function's own (no BVH), so the subset does not lean on the
/// query's culling.
pub fn near_the_motion(
    body: &Body,
    keyframes: &Keyframes,
    env: &Environment,
    per_interval: usize,
    margin: f64,
) -> anyhow::Result<Environment> {
    let step = 1.0 / per_interval.max(1) as f64;
    let count = (keyframes.end() / step).round() as usize;
    let (mut lo, mut hi) = (glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY);
    for i in 0..=count {
        let t = (i as f64 * step).min(keyframes.end());
        for c in body.capsules(&keyframes.pose_at(t)) {
            let r = glam::DVec3::splat(c.radius + margin);
            lo = lo.min(c.a.min(c.b) - r);
            hi = hi.max(c.a.max(c.b) + r);
        }
    }
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in &env.triangles {
        let (a, b) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
        if a.cmple(hi).all() && b.cmpge(lo).all() {
            let base = positions.len() as u32;
            positions.extend(t.iter().map(|p| p.as_vec3()));
            triangles.push([base, base + 1, base + 2]);
        }
    }
    Environment::new(&crate::mesh::Mesh::new(positions, triangles))
}
