//! Step 2, "bound each link's swept space" (the source uses interval arithmetic; this bound is
//! ours, of the same kind): within one keyframe interval every joint angle and the root move
//! at constant rates, so a bound on the speed of every point of a link follows from the
//! chain above it. A joint's rotation Rx·Ry·Rz turns at most |ȧx| + |ȧy| + |ȧz| radians per
//! unit time, and a point at distance ρ from a joint moves at most ρ times the joint's rate
//! on its account; ρ is bounded by the link offsets down the chain (rigid lengths), so
//!
//!   speed ≤ |root rate| + Σ over joints j of the chain (rate_j × reach_j).
//!
//! Over a sub-interval [t0, t1] every point of the link's segment then stays within
//! speed · (t1 - t0) / 2 of its place at the midpoint: the capsule at the midpoint, its
//! radius grown by that much, holds the whole sweep (the swept capsule bound).

use super::body::{Body, Capsule, Keyframes};
use glam::DVec3;

/// The largest speed (units per unit time) of any point of each link's segment within
/// keyframe interval `k`.
pub fn link_speeds(body: &Body, keyframes: &Keyframes, k: usize) -> Vec<f64> {
    if keyframes.poses.len() < 2 {
        return vec![0.0; body.links.len()];
    }
    let (a, b) = (&keyframes.poses[k], &keyframes.poses[k + 1]);
    let root_rate = (b.root - a.root).length();
    let joint_rate = joint_rates(keyframes, k);
    (0..body.links.len())
        .map(|link| {
            let chain = body.chain(link);
            let own = &body.links[link];
            let tip = own.segment[0].length().max(own.segment[1].length());
            // reach_j: from joint j down the chain to the farthest point of the segment.
            let mut reach = tip;
            let mut speed = root_rate;
            for (i, &j) in chain.iter().enumerate().rev() {
                speed += joint_rate[j] * reach;
                if i > 0 {
                    reach += body.links[j].joint.length();
                }
            }
            speed
        })
        .collect()
}

/// How fast each link's joint turns within keyframe interval `k`: |ȧx| + |ȧy| + |ȧz|,
/// radians per unit time.
pub fn joint_rates(keyframes: &Keyframes, k: usize) -> Vec<f64> {
    let (a, b) = (&keyframes.poses[k], &keyframes.poses[k + 1]);
    a.angles
        .iter()
        .zip(&b.angles)
        .map(|(x, y)| (*y - *x).abs().element_sum())
        .collect()
}

/// The swept capsule bound of a link over [t0, t1] (inside one keyframe interval): the
/// capsule at the midpoint, grown by `speed · (t1 - t0) / 2`.
pub fn swept_capsule(at_mid: Capsule, speed: f64, t0: f64, t1: f64) -> Capsule {
    Capsule {
        radius: at_mid.radius + speed * (t1 - t0) * 0.5,
        ..at_mid
    }
}

/// The axis-aligned box of a capsule: (min, max).
pub fn capsule_box(c: &Capsule) -> (DVec3, DVec3) {
    let r = DVec3::splat(c.radius);
    (c.a.min(c.b) - r, c.a.max(c.b) + r)
}
