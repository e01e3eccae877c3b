//! Global AABB overlap test [Sec. 5.1]: trivial rejection on the CPU before any streaming.

use super::aabb::Aabb;
use glam::Vec3;

/// `true` when the global boxes of the two models overlap, so the streaming test must run.
pub fn global_boxes_overlap(positions_x: &[Vec3], positions_y: &[Vec3]) -> bool {
    let gx = Aabb::from_points(positions_x.iter().copied());
    let gy = Aabb::from_points(positions_y.iter().copied());
    gx.overlaps(&gy)
}
