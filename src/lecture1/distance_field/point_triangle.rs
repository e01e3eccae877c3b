//! The exact distance from a point to a triangle, the per-fragment work of the rasterized
//! distance field (the same steps as `glsl/lecture1/point_triangle.glsl`, here in f64).
//!
//! If the point's projection onto the triangle's plane falls inside the triangle, the distance
//! is the distance to the plane; otherwise it is the distance to the nearest of the three
//! edges. A triangle of zero area has no plane and is its edges (a segment or a point).

use glam::DVec3;

/// Distance from `p` to the segment `a b` (a point when `a == b`).
pub fn point_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + t * ab)).length()
}

/// Distance from `p` to the triangle `a b c` (any area, zero included).
pub fn point_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let n = (b - a).cross(c - a);
    let n2 = n.length_squared();
    // The projection is inside when p is on the inner side of each edge's plane.
    let inside = n2 > 0.0
        && (b - a).cross(p - a).dot(n) >= 0.0
        && (c - b).cross(p - b).dot(n) >= 0.0
        && (a - c).cross(p - c).dot(n) >= 0.0;
    if inside {
        return (p - a).dot(n).abs() / n2.sqrt();
    }
    point_segment(p, a, b)
        .min(point_segment(p, b, c))
        .min(point_segment(p, c, a))
}
