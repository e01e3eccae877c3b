//! Primitive-level intersection test [Sec. 5.4]: Möller's triangle/triangle test (the
//! paper's reference 39: Möller 1997, "A fast triangle-triangle intersection test"), on the
//! CPU, for every triangle pair of every colliding AABB pair.
//!
//! Two predicates share one entry point, [`triangles_intersect`]; the exact one is the
//! default (see [`Predicate`]):
//! - [`Predicate::Moller`]: Möller's interval test, written here without the epsilon
//!   snapping of the original code, with its coplanar case (edge/edge tests and
//!   point-in-triangle in the projection plane). Inputs are f32; arithmetic is f64.
//! - [`Predicate::Exact`]: the same plane-side rejections, decided by Shewchuk's exact
//!   orientation predicates (the `robust` crate), and the interval step in the
//!   orientation-only form of Guigue & Devillers (2003), because Möller's interval
//!   endpoints are quotients that no orientation predicate expresses. Touching
//!   configurations (a vertex exactly on a face, shared edges) are decided exactly, and a
//!   zero-area triangle is taken as the segment or point it is. (Möller's test, like its
//!   paper, assumes proper triangles.)
//!
//! Both begin with the triangles' own boxes: a pair whose boxes are disjoint is never
//! reported. Every triangle box lies inside its leaf box, so any pair this predicate reports
//! lies in a colliding AABB pair: that is what makes the streaming pipeline's answer equal
//! the brute-force answer exactly.

use super::aabb::Aabb;
use glam::{DVec3, Vec3};
use robust::{Coord, Coord3D};

/// Which triangle/triangle predicate decides a pair. The default is exact: it decides
/// every pair of the f32 input exactly, touching contacts included, at any scale, for
/// 2-16% more triangle-test time on the six paper scenes. Möller's float test (the paper's)
/// misses or invents contacts where triangles touch (a vertex or an edge on the other
/// triangle), and far from unit scale (10^24, 10^-30) its products of four plane distances
/// overflow or underflow f64 and it reports pairs that do not touch.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub enum Predicate {
    /// Möller 1997 in floating point.
    Moller,
    /// Exact orientation predicates.
    #[default]
    Exact,
}

/// The range of the largest coordinate magnitude within which Möller's test agreed with the
/// exact predicate on every one of 4000 random triangle pairs, measured at every quarter
/// decade of f32's range by `tests/moller_scale.rs` (which asserts that these are the
/// measured ends): clean from a largest coordinate of 1.3e-24 to 1.3e24; at 2.3e24 it
/// invented 52 pairs and missed 5 of 86, at 7.3e-25 it invented 14 and missed 2. Its
/// products of plane distances grow as the 13th power of the scale, so they overflow f64
/// above the band and underflow below it.
pub const MOLLER_SAFE_SCALES: [f32; 2] = [1.3e-24, 1.3e24];

impl Predicate {
    /// Every predicate, as its name parses.
    pub const ALL: [Predicate; 2] = [Predicate::Moller, Predicate::Exact];

    /// The name [`std::str::FromStr`] takes: `moller` or `exact`.
    pub fn name(self) -> &'static str {
        match self {
            Predicate::Moller => "moller",
            Predicate::Exact => "exact",
        }
    }
}

impl std::fmt::Display for Predicate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Predicate {
    type Err = String;

    fn from_str(s: &str) -> Result<Predicate, String> {
        Predicate::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| format!("unknown triangle predicate '{s}' (moller or exact)"))
    }
}

/// Do the closed triangles `a` and `b` share a point?
pub fn triangles_intersect(a: &[Vec3; 3], b: &[Vec3; 3], predicate: Predicate) -> bool {
    let box_a = Aabb::from_points(*a);
    let box_b = Aabb::from_points(*b);
    if !box_a.overlaps(&box_b) {
        return false;
    }
    let a = a.map(|p| p.as_dvec3());
    let b = b.map(|p| p.as_dvec3());
    match predicate {
        Predicate::Moller => moller::tri_tri(&a, &b),
        Predicate::Exact => exact::tri_tri(&a, &b),
    }
}

/// One model as the primitive test sees it: its triangles, its current vertex positions
/// and its AABB stream.
#[derive(Clone, Copy)]
pub struct ModelView<'a> {
    pub triangles: &'a [[u32; 3]],
    pub positions: &'a [Vec3],
    pub stream: &'a super::stream_setup::AabbStream,
}

impl ModelView<'_> {
    pub fn triangle(&self, t: u32) -> [Vec3; 3] {
        self.triangles[t as usize].map(|v| self.positions[v as usize])
    }
}

/// What the primitive-level test found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PrimitiveResult {
    /// Potentially colliding triangle pairs: all triangle pairs of all CAPs.
    pub pctps: u64,
    /// Colliding triangle pairs `(a, b)`, triangle indices of X and Y, sorted, each once.
    pub pairs: Vec<(u32, u32)>,
}

/// Test every triangle pair of every colliding AABB pair `(leaf of X, leaf of Y)`.
/// Each real leaf pair appears once (the stencil guarantees it), and each triangle belongs
/// to one leaf, so each triangle pair is tested at most once.
pub fn test_caps(
    x: ModelView,
    y: ModelView,
    caps: &[(u32, u32)],
    predicate: Predicate,
) -> PrimitiveResult {
    let mut out = PrimitiveResult::default();
    // region: primitive-test
    for &(lx, ly) in caps {
        let tx = &x.stream.leaves[lx as usize].triangles;
        let ty = &y.stream.leaves[ly as usize].triangles;
        out.pctps += (tx.len() * ty.len()) as u64;
        for &a in tx {
            let ta = x.triangle(a);
            for &b in ty {
                if triangles_intersect(&ta, &y.triangle(b), predicate) {
                    out.pairs.push((a, b));
                }
            }
        }
    }
    out.pairs.sort_unstable();
    // endregion
    out
}

mod moller {
    //! Möller's "no division" variant, macro for macro.
    use glam::DVec3;

    pub fn tri_tri(v: &[DVec3; 3], u: &[DVec3; 3]) -> bool {
        // Plane of triangle U: N2.x + d2 = 0; signed distances of V's vertices.
        let n2 = (u[1] - u[0]).cross(u[2] - u[0]);
        let d2 = -n2.dot(u[0]);
        let dv = v.map(|p| n2.dot(p) + d2);
        if same_sign_nonzero(dv) {
            return false;
        }
        // Plane of triangle V; signed distances of U's vertices.
        let n1 = (v[1] - v[0]).cross(v[2] - v[0]);
        let d1 = -n1.dot(v[0]);
        let du = u.map(|p| n1.dot(p) + d1);
        if same_sign_nonzero(du) {
            return false;
        }
        // Direction of the intersection line L; project onto its largest axis.
        let dir = n1.cross(n2);
        let axis = largest_axis(dir);
        let vp = v.map(|p| p[axis]);
        let up = u.map(|p| p[axis]);
        let (Some(iv), Some(iu)) = (interval(vp, dv), interval(up, du)) else {
            return coplanar(n1, v, u);
        };
        // The intervals are [a + b x1 y, a + c x0 y] scaled by the common denominators.
        let (a, b, c, x0, x1) = iv;
        let (d, e, f, y0, y1) = iu;
        let xx = x0 * x1;
        let yy = y0 * y1;
        let xxyy = xx * yy;
        let mut i1 = [a * xxyy + b * x1 * yy, a * xxyy + c * x0 * yy];
        let mut i2 = [d * xxyy + e * xx * y1, d * xxyy + f * xx * y0];
        i1.sort_by(f64::total_cmp);
        i2.sort_by(f64::total_cmp);
        !(i1[1] < i2[0] || i2[1] < i1[0])
    }

    fn same_sign_nonzero(d: [f64; 3]) -> bool {
        d[0] * d[1] > 0.0 && d[0] * d[2] > 0.0
    }

    pub fn largest_axis(v: DVec3) -> usize {
        let a = v.abs();
        if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        }
    }

    /// NEWCOMPUTE_INTERVALS: pick the vertex alone on its side of the other plane.
    /// `None` means all three distances are zero: the triangles are coplanar.
    fn interval(p: [f64; 3], d: [f64; 3]) -> Option<(f64, f64, f64, f64, f64)> {
        let [p0, p1, p2] = p;
        let [d0, d1, d2] = d;
        Some(if d0 * d1 > 0.0 {
            (p2, (p0 - p2) * d2, (p1 - p2) * d2, d2 - d0, d2 - d1)
        } else if d0 * d2 > 0.0 {
            (p1, (p0 - p1) * d1, (p2 - p1) * d1, d1 - d0, d1 - d2)
        } else if d1 * d2 > 0.0 || d0 != 0.0 {
            (p0, (p1 - p0) * d0, (p2 - p0) * d0, d0 - d1, d0 - d2)
        } else if d1 != 0.0 {
            (p1, (p0 - p1) * d1, (p2 - p1) * d1, d1 - d0, d1 - d2)
        } else if d2 != 0.0 {
            (p2, (p0 - p2) * d2, (p1 - p2) * d2, d2 - d0, d2 - d1)
        } else {
            return None;
        })
    }

    /// coplanar_tri_tri: project onto the axis plane where the triangles are largest, test
    /// every edge pair, then whether one triangle lies inside the other.
    fn coplanar(n: DVec3, v: &[DVec3; 3], u: &[DVec3; 3]) -> bool {
        let (i0, i1) = match largest_axis(n) {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let v2 = v.map(|p| [p[i0], p[i1]]);
        let u2 = u.map(|p| [p[i0], p[i1]]);
        for k in 0..3 {
            if edge_against_tri_edges(v2[k], v2[(k + 1) % 3], &u2) {
                return true;
            }
        }
        point_in_tri(v2[0], &u2) || point_in_tri(u2[0], &v2)
    }

    fn edge_against_tri_edges(v0: [f64; 2], v1: [f64; 2], u: &[[f64; 2]; 3]) -> bool {
        let ax = v1[0] - v0[0];
        let ay = v1[1] - v0[1];
        (0..3).any(|k| edge_edge(v0, ax, ay, u[k], u[(k + 1) % 3]))
    }

    /// EDGE_EDGE_TEST, Franklin Antonio's segment test.
    fn edge_edge(v0: [f64; 2], ax: f64, ay: f64, u0: [f64; 2], u1: [f64; 2]) -> bool {
        let bx = u0[0] - u1[0];
        let by = u0[1] - u1[1];
        let cx = v0[0] - u0[0];
        let cy = v0[1] - u0[1];
        let f = ay * bx - ax * by;
        let d = by * cx - bx * cy;
        if (f > 0.0 && d >= 0.0 && d <= f) || (f < 0.0 && d <= 0.0 && d >= f) {
            let e = ax * cy - ay * cx;
            if f > 0.0 {
                return e >= 0.0 && e <= f;
            }
            return e <= 0.0 && e >= f;
        }
        false
    }

    /// POINT_IN_TRI: `p` strictly on the same side of all three edges.
    fn point_in_tri(p: [f64; 2], u: &[[f64; 2]; 3]) -> bool {
        let side = |a: [f64; 2], b: [f64; 2]| {
            let ea = b[1] - a[1];
            let eb = -(b[0] - a[0]);
            let ec = -ea * a[0] - eb * a[1];
            ea * p[0] + eb * p[1] + ec
        };
        let d0 = side(u[0], u[1]);
        let d1 = side(u[1], u[2]);
        let d2 = side(u[2], u[0]);
        d0 * d1 > 0.0 && d0 * d2 > 0.0
    }
}

mod exact {
    //! Orientation-only decisions (Guigue & Devillers 2003) on Shewchuk's predicates.
    use super::{c2, c3};
    use glam::DVec3;
    use std::cmp::Ordering::{self, Equal, Greater, Less};

    /// Sign of `((b - a) x (c - a)) . (d - a)`: positive when `d` is on the side the
    /// right-hand normal of `abc` points to. Shewchuk's orient3d has the opposite sign.
    fn o3(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Ordering {
        0.0.partial_cmp(&robust::orient3d(c3(a), c3(b), c3(c), c3(d)))
            .unwrap_or(Equal)
    }

    /// Exact test of two closed triangles; a degenerate one (collinear corners) is taken
    /// as the segment or point it is, so zero-area triangles are decided exactly too.
    pub fn tri_tri(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> bool {
        match (Shape::of(t1), Shape::of(t2)) {
            (Shape::Triangle, Shape::Triangle) => proper_tri_tri(t1, t2),
            (Shape::Triangle, other) => other.meets_triangle(t1),
            (other, Shape::Triangle) => other.meets_triangle(t2),
            (a, b) => a.meets_lower(&b),
        }
    }

    /// What three corners span.
    #[derive(Clone, Copy, Debug)]
    enum Shape {
        Triangle,
        Segment(DVec3, DVec3),
        Point(DVec3),
    }

    /// The three axis-plane projections (index pairs).
    const PLANES: [(usize, usize); 3] = [(0, 1), (1, 2), (2, 0)];

    fn project(p: DVec3, (i, j): (usize, usize)) -> [f64; 2] {
        [p[i], p[j]]
    }

    /// Three points are collinear iff their projections on all three axis planes are: the
    /// projections' orientations are the components of the cross product.
    fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
        PLANES
            .iter()
            .all(|&pl| o2(project(a, pl), project(b, pl), project(c, pl)) == Equal)
    }

    /// The axis plane to decide coplanar (or collinear) figures in: one where the points
    /// do not all fall on a line, else one that keeps the axis of largest spread.
    fn working_plane(points: &[DVec3]) -> (usize, usize) {
        for &pl in &PLANES {
            for i in 0..points.len() {
                for j in i + 1..points.len() {
                    for k in j + 1..points.len() {
                        let (a, b, c) = (points[i], points[j], points[k]);
                        if o2(project(a, pl), project(b, pl), project(c, pl)) != Equal {
                            return pl;
                        }
                    }
                }
            }
        }
        let spread = |axis: usize| {
            let lo = points.iter().map(|p| p[axis]).fold(f64::INFINITY, f64::min);
            let hi = points
                .iter()
                .map(|p| p[axis])
                .fold(f64::NEG_INFINITY, f64::max);
            hi - lo
        };
        let axis = (0..3)
            .max_by(|&a, &b| spread(a).total_cmp(&spread(b)))
            .unwrap_or(0);
        PLANES[axis] // the plane (axis, axis + 1) keeps `axis`
    }

    impl Shape {
        fn of(t: &[DVec3; 3]) -> Shape {
            if !collinear(t[0], t[1], t[2]) {
                return Shape::Triangle;
            }
            // The extreme corners along the axis of largest spread bound the others.
            let spread = |axis: usize| {
                let v: Vec<f64> = t.iter().map(|p| p[axis]).collect();
                v.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
                    - v.iter().cloned().fold(f64::INFINITY, f64::min)
            };
            let axis = (0..3)
                .max_by(|&a, &b| spread(a).total_cmp(&spread(b)))
                .unwrap_or(0);
            let lo = *t.iter().min_by(|a, b| a[axis].total_cmp(&b[axis])).unwrap();
            let hi = *t.iter().max_by(|a, b| a[axis].total_cmp(&b[axis])).unwrap();
            if lo == hi {
                Shape::Point(lo)
            } else {
                Shape::Segment(lo, hi)
            }
        }

        /// This segment or point against the proper triangle `t`.
        fn meets_triangle(&self, t: &[DVec3; 3]) -> bool {
            let [a, b, c] = *t;
            match *self {
                Shape::Point(p) => o3(a, b, c, p) == Equal && point_in_coplanar_triangle(p, t),
                Shape::Segment(p, q) => {
                    let (sp, sq) = (o3(a, b, c, p), o3(a, b, c, q));
                    if sp == sq && sp != Equal {
                        return false;
                    }
                    if sp == Equal && sq == Equal {
                        let pl = working_plane(&[a, b, c]);
                        let tri = t.map(|v| project(v, pl));
                        let (p2, q2) = (project(p, pl), project(q, pl));
                        return point_in_triangle(p2, &tri)
                            || (0..3).any(|k| segments_meet(p2, q2, tri[k], tri[(k + 1) % 3]));
                    }
                    if sp == Equal {
                        return point_in_coplanar_triangle(p, t);
                    }
                    if sq == Equal {
                        return point_in_coplanar_triangle(q, t);
                    }
                    // pq crosses the plane: the crossing is inside iff pq passes on the
                    // same side of (or through) all three edges.
                    let s = [o3(p, q, a, b), o3(p, q, b, c), o3(p, q, c, a)];
                    !(s.contains(&Greater) && s.contains(&Less))
                }
                Shape::Triangle => unreachable!("proper triangles go to proper_tri_tri"),
            }
        }

        /// Two segments or points.
        fn meets_lower(&self, other: &Shape) -> bool {
            let ends = |s: &Shape| match *s {
                Shape::Segment(p, q) => (p, q),
                Shape::Point(p) => (p, p),
                Shape::Triangle => unreachable!(),
            };
            let ((p, q), (r, t)) = (ends(self), ends(other));
            if o3(p, q, r, t) != Equal {
                return false;
            }
            let pl = working_plane(&[p, q, r, t]);
            let [p2, q2, r2, t2] = [p, q, r, t].map(|v| project(v, pl));
            if p == q && r == t {
                return p == r;
            }
            if p == q {
                return o2(r2, t2, p2) == Equal && on_segment(r2, t2, p2) && collinear(r, t, p);
            }
            if r == t {
                return o2(p2, q2, r2) == Equal && on_segment(p2, q2, r2) && collinear(p, q, r);
            }
            segments_meet(p2, q2, r2, t2)
        }
    }

    /// A second exact test for proper triangles, by a different route (tests only): closed
    /// triangles meet iff an edge of one meets the other, since the boundary of their
    /// intersection (a segment, a point or a polygon) lies on their edges.
    #[cfg(test)]
    pub fn by_edges(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> bool {
        let edges_meet = |a: &[DVec3; 3], b: &[DVec3; 3]| {
            (0..3).any(|k| Shape::Segment(a[k], a[(k + 1) % 3]).meets_triangle(b))
        };
        edges_meet(t1, t2) || edges_meet(t2, t1)
    }

    /// `p`, known to lie in the plane of the proper triangle `t`, inside or on it.
    fn point_in_coplanar_triangle(p: DVec3, t: &[DVec3; 3]) -> bool {
        let pl = working_plane(t);
        point_in_triangle(project(p, pl), &t.map(|v| project(v, pl)))
    }

    /// Guigue & Devillers on two proper triangles.
    fn proper_tri_tri(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> bool {
        let [p1, q1, r1] = *t1;
        let [p2, q2, r2] = *t2;
        // Sides of T1's vertices with respect to the plane of T2, and vice versa.
        let (dp1, dq1, dr1) = (o3(p2, q2, r2, p1), o3(p2, q2, r2, q1), o3(p2, q2, r2, r1));
        if dp1 == dq1 && dp1 == dr1 && dp1 != Equal {
            return false;
        }
        let (dp2, dq2, dr2) = (o3(p1, q1, r1, p2), o3(p1, q1, r1, q2), o3(p1, q1, r1, r2));
        if dp2 == dq2 && dp2 == dr2 && dp2 != Equal {
            return false;
        }
        // Permute T1 so that p1 is alone on its side, swapping T2's orientation to match.
        let t1_ = |a, b, c| [a, b, c];
        let (t1p, t2_flip) = match (dp1, dq1, dr1) {
            (Greater, Greater, _) => (t1_(r1, p1, q1), true),
            (Greater, _, Greater) => (t1_(q1, r1, p1), true),
            (Greater, _, _) => (t1_(p1, q1, r1), false),
            (Less, Less, _) => (t1_(r1, p1, q1), false),
            (Less, _, Less) => (t1_(q1, r1, p1), false),
            (Less, _, _) => (t1_(p1, q1, r1), true),
            (Equal, Less, Equal | Greater) => (t1_(q1, r1, p1), true),
            (Equal, Less, Less) => (t1_(p1, q1, r1), false),
            (Equal, Greater, Greater) => (t1_(p1, q1, r1), true),
            (Equal, Greater, _) => (t1_(q1, r1, p1), false),
            (Equal, Equal, Greater) => (t1_(r1, p1, q1), false),
            (Equal, Equal, Less) => (t1_(r1, p1, q1), true),
            (Equal, Equal, Equal) => return coplanar(t1, t2),
        };
        let (t2p, d2) = if t2_flip {
            ([p2, r2, q2], (dp2, dr2, dq2))
        } else {
            ([p2, q2, r2], (dp2, dq2, dr2))
        };
        tri_tri_3d(t1p, t2p, d2, t1, t2)
    }

    /// TRI_TRI_3D: permute T2 so that p2 is alone on its side, then CHECK_MIN_MAX.
    fn tri_tri_3d(
        t1: [DVec3; 3],
        t2: [DVec3; 3],
        d: (Ordering, Ordering, Ordering),
        orig1: &[DVec3; 3],
        orig2: &[DVec3; 3],
    ) -> bool {
        let [p1, q1, r1] = t1;
        let [p2, q2, r2] = t2;
        let check = |a: [DVec3; 3], b: [DVec3; 3]| check_min_max(a, b);
        let keep = [p1, q1, r1];
        let flip = [p1, r1, q1];
        match d {
            (Greater, Greater, _) => check(flip, [r2, p2, q2]),
            (Greater, _, Greater) => check(flip, [q2, r2, p2]),
            (Greater, _, _) => check(keep, [p2, q2, r2]),
            (Less, Less, _) => check(keep, [r2, p2, q2]),
            (Less, _, Less) => check(keep, [q2, r2, p2]),
            (Less, _, _) => check(flip, [p2, q2, r2]),
            (Equal, Less, Equal | Greater) => check(flip, [q2, r2, p2]),
            (Equal, Less, Less) => check(keep, [p2, q2, r2]),
            (Equal, Greater, Greater) => check(flip, [p2, q2, r2]),
            (Equal, Greater, _) => check(keep, [q2, r2, p2]),
            (Equal, Equal, Greater) => check(keep, [r2, p2, q2]),
            (Equal, Equal, Less) => check(flip, [r2, p2, q2]),
            (Equal, Equal, Equal) => coplanar(orig1, orig2),
        }
    }

    /// CHECK_MIN_MAX: the segments T1 and T2 cut from L overlap iff two orientations agree.
    fn check_min_max(t1: [DVec3; 3], t2: [DVec3; 3]) -> bool {
        let [p1, q1, r1] = t1;
        let [p2, q2, r2] = t2;
        o3(q1, p2, p1, q2) != Greater && o3(p1, p2, r1, r2) != Greater
    }

    /// Coplanar proper triangles, decided in an axis plane onto which they project without
    /// collapsing (chosen exactly): closed triangles meet iff an edge pair meets or a vertex
    /// lies in the other triangle.
    fn coplanar(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> bool {
        let (i0, i1) = working_plane(t1);
        let a = t1.map(|p| [p[i0], p[i1]]);
        let b = t2.map(|p| [p[i0], p[i1]]);
        for i in 0..3 {
            for j in 0..3 {
                if segments_meet(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]) {
                    return true;
                }
            }
        }
        point_in_triangle(a[0], &b) || point_in_triangle(b[0], &a)
    }

    fn o2(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Ordering {
        robust::orient2d(c2(a), c2(b), c2(c))
            .partial_cmp(&0.0)
            .unwrap_or(Equal)
    }

    fn on_segment(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
        p[0] >= a[0].min(b[0])
            && p[0] <= a[0].max(b[0])
            && p[1] >= a[1].min(b[1])
            && p[1] <= a[1].max(b[1])
    }

    /// Closed segments `ab` and `cd` share a point (collinear overlaps included).
    fn segments_meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
        let (d1, d2) = (o2(c, d, a), o2(c, d, b));
        let (d3, d4) = (o2(a, b, c), o2(a, b, d));
        if d1 != d2 && d1 != Equal && d2 != Equal && d3 != d4 && d3 != Equal && d4 != Equal {
            return true;
        }
        (d1 == Equal && on_segment(c, d, a))
            || (d2 == Equal && on_segment(c, d, b))
            || (d3 == Equal && on_segment(a, b, c))
            || (d4 == Equal && on_segment(a, b, d))
    }

    /// `p` inside or on the closed triangle `t` (either orientation).
    fn point_in_triangle(p: [f64; 2], t: &[[f64; 2]; 3]) -> bool {
        let s = [o2(t[0], t[1], p), o2(t[1], t[2], p), o2(t[2], t[0], p)];
        !(s.contains(&Greater) && s.contains(&Less))
    }
}

fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

fn c2(p: [f64; 2]) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn tri(a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> [Vec3; 3] {
        [Vec3::from(a), Vec3::from(b), Vec3::from(c)]
    }

    fn both(a: &[Vec3; 3], b: &[Vec3; 3]) -> (bool, bool) {
        (
            triangles_intersect(a, b, Predicate::Moller),
            triangles_intersect(a, b, Predicate::Exact),
        )
    }

    #[test]
    fn orientation_sign_convention() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let above = c3(DVec3::Z);
        // Shewchuk: positive when d lies below the plane of counter-clockwise abc.
        assert!(robust::orient3d(c3(a), c3(b), c3(c), above) < 0.0);
    }

    #[test]
    fn crossing_triangles_intersect_and_separated_do_not() {
        let a = tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        let piercing = tri([0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [1.5, 2.5, 1.0]);
        let above = tri([0.5, 0.5, 0.1], [1.5, 0.5, 1.0], [0.5, 1.5, 1.0]);
        let beside = tri([1.5, 1.5, -1.0], [1.5, 1.5, 1.0], [3.0, 3.0, 0.0]);
        assert_eq!(both(&a, &piercing), (true, true));
        assert_eq!(both(&a, &above), (false, false));
        assert_eq!(both(&a, &beside), (false, false));
    }

    #[test]
    fn coplanar_cases() {
        let a = tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        let overlapping = tri([1.0, 1.0, 0.0], [-1.0, 1.0, 0.0], [1.0, -1.0, 0.0]);
        let inside = tri([0.2, 0.2, 0.0], [0.5, 0.2, 0.0], [0.2, 0.5, 0.0]);
        let apart = tri([3.0, 3.0, 0.0], [4.0, 3.0, 0.0], [3.0, 4.0, 0.0]);
        assert_eq!(both(&a, &overlapping), (true, true));
        assert_eq!(both(&a, &inside), (true, true));
        assert_eq!(both(&inside, &a), (true, true));
        assert_eq!(both(&a, &apart), (false, false));
    }

    #[test]
    fn exact_predicates_decide_touching_configurations() {
        let a = tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        // A vertex exactly on the face, the rest above it.
        let vertex_on_face = tri([0.5, 0.5, 0.0], [0.5, 0.5, 1.0], [1.0, 0.7, 1.0]);
        // Sharing an edge, folded up.
        let shared_edge = tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, -1.0, 1.0]);
        // Touching at a single vertex in the same plane.
        let corner = tri([2.0, 0.0, 0.0], [3.0, 0.0, 0.0], [3.0, 1.0, 0.0]);
        // One ulp of 1.0 above the face: never touches.
        let ulp = 1.0f32 + f32::EPSILON;
        let hovering = tri([0.5, 0.5, ulp - 1.0], [0.5, 0.5, 1.0], [1.0, 0.7, 1.0]);
        assert!(triangles_intersect(&a, &vertex_on_face, Predicate::Exact));
        assert!(triangles_intersect(&a, &shared_edge, Predicate::Exact));
        assert!(triangles_intersect(&a, &corner, Predicate::Exact));
        assert!(!triangles_intersect(&a, &hovering, Predicate::Exact));
    }

    #[test]
    fn exact_predicates_take_degenerate_triangles_as_segments_and_points() {
        let exact = |a: &[Vec3; 3], b: &[Vec3; 3]| triangles_intersect(a, b, Predicate::Exact);
        // A tilted proper triangle in the plane z = y.
        let t = tri([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 2.0]);
        let seg = |p: [f32; 3], q: [f32; 3]| {
            let m = [
                (p[0] + q[0]) / 2.0,
                (p[1] + q[1]) / 2.0,
                (p[2] + q[2]) / 2.0,
            ];
            tri(p, m, q)
        };
        // Above the plane all along, though its shadow on the plane falls inside t.
        assert!(!exact(&seg([0.5, 0.2, 0.9], [0.5, 0.2, 1.9]), &t));
        // Piercing it at (0.5, 0.2, 0.2).
        assert!(exact(&seg([0.5, 0.2, -0.5], [0.5, 0.2, 0.9]), &t));
        assert!(exact(&t, &seg([0.5, 0.2, -0.5], [0.5, 0.2, 0.9])));
        // Lying in the plane, crossing an edge; lying in the plane outside.
        assert!(exact(&seg([-0.5, 0.5, 0.5], [0.5, 0.5, 0.5]), &t));
        assert!(!exact(&seg([1.5, 1.5, 1.5], [2.5, 1.5, 1.5]), &t));
        // Points on and off the face.
        let point = |p: [f32; 3]| tri(p, p, p);
        assert!(exact(&point([0.5, 0.25, 0.25]), &t));
        assert!(!exact(&point([0.5, 0.25, 0.5]), &t));
        // Segment against segment: crossing, and skew.
        let s1 = seg([0.0, 0.0, 0.0], [2.0, 2.0, 0.0]);
        assert!(exact(&s1, &seg([0.0, 2.0, 0.0], [2.0, 0.0, 0.0])));
        assert!(!exact(&s1, &seg([0.0, 2.0, 0.0], [2.0, 0.0, 1.0])));
        // Collinear overlapping and collinear apart; a point on a segment.
        assert!(exact(&s1, &seg([1.0, 1.0, 0.0], [3.0, 3.0, 0.0])));
        assert!(!exact(
            &seg([0.0, 0.0, 1.0], [1.0, 1.0, 1.0]),
            &seg([1.5, 1.5, 1.0], [3.0, 3.0, 1.0])
        ));
        assert!(exact(&s1, &point([0.5, 0.5, 0.0])));
        assert!(!exact(&s1, &point([0.5, 0.5, 1e-7])));
    }

    #[test]
    fn exact_test_agrees_with_the_edge_route_on_adversarial_triangles() {
        // Corners on a coarse grid, so that shared vertices, vertices on faces, shared
        // edges and coplanar pairs all happen often.
        let mut rng = ChaCha8Rng::seed_from_u64(17);
        let (mut hits, mut tested) = (0, 0);
        for _ in 0..40_000 {
            let mut p = || {
                DVec3::new(
                    rng.gen_range(0..4) as f64,
                    rng.gen_range(0..4) as f64,
                    rng.gen_range(0..3) as f64,
                )
            };
            let (a, b) = ([p(), p(), p()], [p(), p(), p()]);
            let proper = |t: &[DVec3; 3]| (t[1] - t[0]).cross(t[2] - t[0]) != DVec3::ZERO;
            if !proper(&a) || !proper(&b) {
                continue;
            }
            let e = exact::tri_tri(&a, &b);
            assert_eq!(e, exact::by_edges(&a, &b), "{a:?} {b:?}");
            hits += e as u32;
            tested += 1;
        }
        assert!(hits > 1000 && hits < tested, "{hits} of {tested}");
    }

    #[test]
    fn moller_and_exact_agree_on_random_triangles() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut hits = 0;
        for _ in 0..20_000 {
            let mut r = || {
                tri(
                    rng.gen::<[f32; 3]>(),
                    rng.gen::<[f32; 3]>(),
                    rng.gen::<[f32; 3]>(),
                )
            };
            let (a, b) = (r(), r());
            let (m, e) = both(&a, &b);
            assert_eq!(m, e, "{a:?} {b:?}");
            hits += m as u32;
        }
        assert!(
            hits > 1000,
            "the sample must contain intersecting pairs ({hits})"
        );
    }

    #[test]
    fn moller_and_exact_agree_on_random_coplanar_triangles() {
        // In a plane where f32 coordinates are exactly coplanar: z = 0, then x + y + z = 1
        // with x, y on a grid so that z is exact.
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (mut hits, mut overlapping) = (0, 0);
        for plane in 0..2 {
            for _ in 0..5_000 {
                let mut p = || {
                    let (x, y) = (
                        rng.gen_range(0..64) as f32 / 64.0,
                        rng.gen_range(0..64) as f32 / 64.0,
                    );
                    if plane == 0 {
                        Vec3::new(x, y, 0.0)
                    } else {
                        Vec3::new(x, y, 1.0 - x - y)
                    }
                };
                let (a, b) = ([p(), p(), p()], [p(), p(), p()]);
                let area = |t: &[Vec3; 3]| (t[1] - t[0]).cross(t[2] - t[0]).length();
                if area(&a) == 0.0 || area(&b) == 0.0 {
                    continue;
                }
                let e = triangles_intersect(&a, &b, Predicate::Exact);
                let m = triangles_intersect(&a, &b, Predicate::Moller);
                // On a grid, exact touching happens; Möller's float test may then go either
                // way. Apart, both say no; overlapping with positive area, both say yes.
                if !e {
                    assert!(
                        !m,
                        "Möller reports disjoint coplanar triangles: {a:?} {b:?}"
                    );
                }
                if overlap_with_area(&a, &b) {
                    assert!(
                        e,
                        "exact misses overlapping coplanar triangles: {a:?} {b:?}"
                    );
                    assert!(
                        m,
                        "Möller misses overlapping coplanar triangles: {a:?} {b:?}"
                    );
                    overlapping += 1;
                }
                hits += e as u32;
            }
        }
        assert!(hits > 1000, "{hits}");
        assert!(overlapping > 500, "{overlapping}");
    }

    /// Do coplanar triangles on the 1/64 grid share more than boundary points? Decided
    /// exactly in integers on their projections onto z = 0 (both planes of the test project
    /// one to one): convex interiors meet unless an edge's line separates the triangles,
    /// touching allowed.
    fn overlap_with_area(a: &[Vec3; 3], b: &[Vec3; 3]) -> bool {
        let grid = |t: &[Vec3; 3]| t.map(|p| [(p.x * 64.0) as i64, (p.y * 64.0) as i64]);
        let (a, b) = (grid(a), grid(b));
        let separates = |t: &[[i64; 2]; 3], other: &[[i64; 2]; 3]| {
            (0..3).any(|i| {
                let (p, q) = (t[i], t[(i + 1) % 3]);
                let side =
                    |r: [i64; 2]| (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
                let own = side(t[(i + 2) % 3]);
                other.iter().all(|&r| side(r) * own.signum() <= 0)
            })
        };
        !separates(&a, &b) && !separates(&b, &a)
    }

    #[test]
    fn the_test_is_symmetric_and_independent_of_vertex_order() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for _ in 0..2_000 {
            let mut r = || {
                tri(
                    rng.gen::<[f32; 3]>(),
                    rng.gen::<[f32; 3]>(),
                    rng.gen::<[f32; 3]>(),
                )
            };
            let (a, b) = (r(), r());
            for p in [Predicate::Moller, Predicate::Exact] {
                let base = triangles_intersect(&a, &b, p);
                assert_eq!(triangles_intersect(&b, &a, p), base);
                let rot = [a[1], a[2], a[0]];
                let rev = [b[0], b[2], b[1]];
                assert_eq!(triangles_intersect(&rot, &rev, p), base);
            }
        }
    }
}
