//! Step 5, "exact tests on the survivors": the distance between a link's segment and a
//! triangle (f64), with the closest points; the capsule touches the triangle when that
//! distance is at most its radius. The nearest pair of a segment and a triangle that do not
//! cross lies at a segment end against the triangle, or on an edge against the segment
//! (a closest pair inside both would make them parallel, and then an end does as well).

use glam::DVec3;

pub use crate::lecture1::distance_field::point_triangle::closest_on_triangle;

/// The distance and the closest points (on the segment, on the triangle).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nearest {
    pub distance: f64,
    pub on_segment: DVec3,
    pub on_triangle: DVec3,
}

/// The closest points of segments `p0 p1` and `q0 q1` (Ericson, Real-Time Collision
/// Detection, 5.1.9).
fn closest_segments(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> (DVec3, DVec3) {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.length_squared(), d2.length_squared(), d2.dot(r));
    let tiny = 1e-300;
    let (s, t) = if a <= tiny && e <= tiny {
        (0.0, 0.0)
    } else if a <= tiny {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(r);
        if e <= tiny {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let mut s = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
            (s, t)
        }
    };
    (p0 + d1 * s, q0 + d2 * t)
}

/// Where segment `a b` crosses the triangle, if it does.
fn crossing(a: DVec3, b: DVec3, [p, q, r]: [DVec3; 3]) -> Option<DVec3> {
    let n = (q - p).cross(r - p);
    let (da, db) = ((a - p).dot(n), (b - p).dot(n));
    if n.length_squared() == 0.0 || (da > 0.0 && db > 0.0) || (da < 0.0 && db < 0.0) || da == db {
        return None;
    }
    let x = a + (b - a) * (da / (da - db));
    let inside = (q - p).cross(x - p).dot(n) >= 0.0
        && (r - q).cross(x - q).dot(n) >= 0.0
        && (p - r).cross(x - r).dot(n) >= 0.0;
    inside.then_some(x)
}

/// The distance between segment `a b` and `triangle`, with the closest points.
pub fn segment_triangle(a: DVec3, b: DVec3, triangle: [DVec3; 3]) -> Nearest {
    if let Some(x) = crossing(a, b, triangle) {
        return Nearest {
            distance: 0.0,
            on_segment: x,
            on_triangle: x,
        };
    }
    let mut pairs = vec![
        (a, closest_on_triangle(a, triangle)),
        (b, closest_on_triangle(b, triangle)),
    ];
    for k in 0..3 {
        pairs.push(closest_segments(a, b, triangle[k], triangle[(k + 1) % 3]));
    }
    let (on_segment, on_triangle) = pairs
        .into_iter()
        .min_by(|x, y| (x.0 - x.1).length().total_cmp(&(y.0 - y.1).length()))
        .unwrap_or((a, a));
    Nearest {
        distance: (on_segment - on_triangle).length(),
        on_segment,
        on_triangle,
    }
}
