//! The exact distance from a point to a triangle, the per-fragment work of the rasterized
//! distance field (the same steps as `glsl/lecture1/point_triangle.glsl`, here in f64).
//!
//! If the point's projection onto the triangle's plane falls inside the triangle, the distance
//! is the distance to the plane; otherwise it is the distance to the nearest of the three
//! edges. A triangle of zero area has no plane and is its edges (a segment or a point).

use glam::DVec3;

/// The closest point to `p` on the segment `a b` (a point when `a == b`).
pub fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    a + t * ab
}

/// Distance from `p` to the segment `a b` (a point when `a == b`).
pub fn point_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    (p - closest_on_segment(p, a, b)).length()
}

/// Whether `p` projects into the triangle `a b c` along its normal `n` (`n2` its squared
/// length; never for a triangle of zero area): `p` is on the inner side of each edge's plane.
fn projects_inside(p: DVec3, [a, b, c]: [DVec3; 3], n: DVec3, n2: f64) -> bool {
    n2 > 0.0
        && (b - a).cross(p - a).dot(n) >= 0.0
        && (c - b).cross(p - b).dot(n) >= 0.0
        && (a - c).cross(p - c).dot(n) >= 0.0
}

/// Distance from `p` to the triangle `a b c` (any area, zero included).
pub fn point_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let n = (b - a).cross(c - a);
    let n2 = n.length_squared();
    if projects_inside(p, [a, b, c], n, n2) {
        return (p - a).dot(n).abs() / n2.sqrt();
    }
    point_segment(p, a, b)
        .min(point_segment(p, b, c))
        .min(point_segment(p, c, a))
}

/// The closest point to `p` on the triangle `a b c` (any area, zero included): its projection
/// where that falls inside, else the nearest point of the three edges.
pub fn closest_on_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> DVec3 {
    let n = (b - a).cross(c - a);
    let n2 = n.length_squared();
    if projects_inside(p, [a, b, c], n, n2) {
        return p - n * ((p - a).dot(n) / n2);
    }
    [(a, b), (b, c), (c, a)]
        .iter()
        .map(|&(u, v)| closest_on_segment(p, u, v))
        .min_by(|x, y| {
            (*x - p)
                .length_squared()
                .total_cmp(&(*y - p).length_squared())
        })
        .unwrap_or(a)
}
