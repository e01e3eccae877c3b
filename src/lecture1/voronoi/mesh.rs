//! Hoff et al.'s distance meshes: each site's distance function over the plane as a
//! polygonal mesh whose height is the distance, drawn with the depth test keeping the
//! nearest. Built from two pieces:
//! - a cone (apex on a point, depth 0; rim of `k` sides, depth = radius) for every point and
//!   every corner of a segment or triangle;
//! - a tent (two rectangles rising at slope 1 from a segment, one per side) for every
//!   segment and every triangle edge: the distance to a line is planar, so the tent is exact;
//! - and, for a triangle, the triangle itself at depth 0.
//!
//! The minimum over a segment's tent and its corners' cones is its distance, and a
//! triangle's is the minimum over its edges' and the flat top, so the depth test needs no
//! clipping of the pieces against each other. Every cone reaches `R`, the farthest distance
//! any pixel needs (the depth range).
//!
//! The tessellation error (what Hoff chooses the number of sides from): the rim's vertices
//! lie on the true cone at radius `R / cos(π/k)`, so its `k` flat facets cover the disk of
//! radius `R`. Each facet is a chord of a convex function, above it: at radius `r` and angle
//! `φ` from a facet's middle the mesh gives `r cos φ / cos(π/k)`, never below the distance
//! and at most `R (1 / cos(π/k) - 1)` above it within the disk. `k` is the smallest with that
//! bound under the asked error `ε`: `k = ⌈π / acos(R / (R + ε))⌉`. A pixel's mesh distance
//! is therefore in `[d, d + ε]`, and the site it keeps is within `ε` of the nearest.
//!
//! Every triangle is cut to the target's square here ([`clip`]), so the rasterizer never
//! clips one. Cut by the renderer, a triangle crossing two sides of the viewport becomes a
//! fan whose inner edge runs from a cone's apex to a corner of the target, and softpipe
//! leaves pixel centres lying on that edge uncovered by both halves (a row of them, won by a
//! farther site); it also sets up the plane of a cut sliver far off. Here a cut polygon is
//! drawn as two overlapping fans, so no pixel centre depends on an inner edge, and without
//! slivers; overlap is harmless, every piece lying above the distance within the bound.

use super::{Domain, Site};
use glam::{DVec2, DVec3};

/// The default tessellation error, pixels.
pub const DEFAULT_ERROR_PIXELS: f64 = 0.5;

/// The fewest cone sides (a triangle already covers its centre's neighbourhood).
const MIN_SIDES: usize = 3;

/// The narrowest cut triangle drawn, pixels (its smallest height).
const SLIVER: f64 = 0.125;

/// The meshes of a set of sites.
#[derive(Clone, Debug)]
pub struct DistanceMeshes {
    /// Triangle vertices, three per triangle: x, y (pixels from the domain's corner),
    /// distance (pixels), site id; sites in id order.
    pub vertices: Vec<[f32; 4]>,
    /// Sides of every cone.
    pub sides: usize,
    /// The radius every cone covers, pixels.
    pub radius: f64,
    /// The rim's distance, the deepest vertex, pixels: `radius / cos(π / sides)`.
    pub rim: f64,
    /// The tessellation error bound, pixels: `radius (1 / cos(π / sides) - 1)`.
    pub error_bound: f64,
}

/// The sides a cone of `radius` needs to stay within `error` of the distance (both pixels).
pub fn cone_sides(radius: f64, error: f64) -> anyhow::Result<usize> {
    anyhow::ensure!(
        error.is_finite() && error > 0.0,
        "the distance meshes' error must be a positive number of pixels, not {error}"
    );
    if radius <= 0.0 {
        return Ok(MIN_SIDES);
    }
    let half_angle = (radius / (radius + error)).acos();
    let sides = (std::f64::consts::PI / half_angle).ceil();
    anyhow::ensure!(
        sides <= 1e6,
        "an error of {error} pixels over a radius of {radius} pixels needs {sides} cone sides: \
         ask for a larger error"
    );
    Ok((sides as usize).max(MIN_SIDES))
}

/// The bound for `sides` sides over `radius` (pixels).
pub fn error_bound(radius: f64, sides: usize) -> f64 {
    radius * (1.0 / (std::f64::consts::PI / sides as f64).cos() - 1.0)
}

/// The distance meshes of `sites` over `domain` at `n x n` pixels, covering `radius` input
/// units from each site, within `error_pixels` of the distance.
pub fn build(
    sites: &[Site],
    domain: Domain,
    n: usize,
    radius: f64,
    error_pixels: f64,
) -> anyhow::Result<DistanceMeshes> {
    let pixel = domain.pixel(n);
    let radius = radius / pixel;
    let sides = cone_sides(radius, error_pixels)?;
    let rim = radius / (std::f64::consts::PI / sides as f64).cos();
    let mut out = DistanceMeshes {
        vertices: Vec::new(),
        sides,
        radius,
        rim,
        error_bound: error_bound(radius, sides),
    };
    let min = DVec2::from(domain.min);
    for (id, site) in sites.iter().enumerate() {
        let corners: Vec<DVec2> = site.corners().iter().map(|&c| (c - min) / pixel).collect();
        let mut piece = Piece {
            out: &mut out.vertices,
            size: n as f64,
            site: id as f32,
        };
        for &c in &corners {
            piece.cone(c, sides, rim);
        }
        match corners.as_slice() {
            [_] => {}
            [a, b] => piece.tent(*a, *b, rim),
            [a, b, c] => {
                for (p, q) in [(a, b), (b, c), (c, a)] {
                    piece.tent(*p, *q, rim);
                }
                if (*b - *a).perp_dot(*c - *a) != 0.0 {
                    piece.triangle([(*a, 0.0), (*b, 0.0), (*c, 0.0)]);
                }
            }
            _ => unreachable!("sites have one to three corners"),
        }
    }
    anyhow::ensure!(
        out.vertices.iter().flatten().all(|v| v.is_finite()),
        "a site's distance mesh is not finite in fp32"
    );
    Ok(out)
}

/// The triangles of one site.
struct Piece<'a> {
    out: &'a mut Vec<[f32; 4]>,
    /// The target's side, pixels.
    size: f64,
    site: f32,
}

impl Piece<'_> {
    /// The triangle's part inside the target, as a fan; its depth is planar, so the cut
    /// points' depths are interpolated along the cut edges.
    fn triangle(&mut self, corners: [(DVec2, f64); 3]) {
        let polygon = clip(
            corners.map(|(p, d)| DVec3::new(p.x, p.y, d)).to_vec(),
            self.size,
        );
        // A fan from the first corner; a cut polygon also a second fan from the next corner,
        // so a pixel centre on an inner edge of one fan lies inside a triangle of the other.
        // There a sliver (narrower than `SLIVER` pixels, cut off by a side near a corner or
        // a vertex) is left out: the other fan covers it, and the plane softpipe sets up
        // from three nearly collinear corners is off by far more than fp32 rounding.
        let m = polygon.len();
        let fans = if m > 3 { 2 } else { 1 };
        for first in 0..fans {
            for k in 1..m.saturating_sub(1) {
                let t = [first, first + k, first + k + 1].map(|i| polygon[i % m]);
                if fans == 2 && narrowest(t) < SLIVER {
                    continue;
                }
                for p in t {
                    self.out
                        .push([p.x as f32, p.y as f32, p.z as f32, self.site]);
                }
            }
        }
    }

    /// A cone of `sides` facets, apex at `apex`, rim vertices at `rim` pixels (their depth).
    fn cone(&mut self, apex: DVec2, sides: usize, rim: f64) {
        let at = |k: usize| {
            let a = std::f64::consts::TAU * (k % sides) as f64 / sides as f64;
            apex + rim * DVec2::new(a.cos(), a.sin())
        };
        for k in 0..sides {
            self.triangle([(apex, 0.0), (at(k), rim), (at(k + 1), rim)]);
        }
    }

    /// The two rectangles rising from the segment `a b` at slope 1 to depth `rim`; nothing
    /// for a segment of zero length (its cones cover it).
    fn tent(&mut self, a: DVec2, b: DVec2, rim: f64) {
        let along = b - a;
        if along.length_squared() == 0.0 {
            return;
        }
        let normal = along.perp().normalize();
        for side in [normal, -normal] {
            let (a2, b2) = (a + rim * side, b + rim * side);
            self.triangle([(a, 0.0), (b, 0.0), (b2, rim)]);
            self.triangle([(a, 0.0), (b2, rim), (a2, rim)]);
        }
    }
}

/// The part of the polygon (x, y in pixels, depth) inside the square `[0, size]^2`
/// (Sutherland and Hodgman, one side at a time). A cut point is interpolated from the cut
/// edge's endpoints taken in a fixed order, so the polygons on either side of a shared edge
/// get the same point, bit for bit.
pub fn clip(mut polygon: Vec<DVec3>, size: f64) -> Vec<DVec3> {
    // Each side as (axis, bound, keep below the bound).
    for (axis, bound, below) in [
        (0, 0.0, false),
        (0, size, true),
        (1, 0.0, false),
        (1, size, true),
    ] {
        let inside = |p: DVec3| {
            if below {
                p[axis] <= bound
            } else {
                p[axis] >= bound
            }
        };
        let mut kept = Vec::with_capacity(polygon.len() + 1);
        for (i, &p) in polygon.iter().enumerate() {
            let q = polygon[(i + 1) % polygon.len()];
            if inside(p) {
                kept.push(p);
            }
            if inside(p) != inside(q) {
                let (a, b) = if (p.x, p.y, p.z) < (q.x, q.y, q.z) {
                    (p, q)
                } else {
                    (q, p)
                };
                let t = (bound - a[axis]) / (b[axis] - a[axis]);
                let mut cut = a + (b - a) * t;
                cut[axis] = bound;
                kept.push(cut);
            }
        }
        polygon = kept;
        if polygon.len() < 3 {
            return Vec::new();
        }
    }
    polygon
}

/// A triangle's smallest height (x, y only).
fn narrowest([a, b, c]: [DVec3; 3]) -> f64 {
    let (a, b, c) = (a.truncate(), b.truncate(), c.truncate());
    let twice_area = (b - a).perp_dot(c - a).abs();
    let longest = (b - a).length().max((c - b).length()).max((a - c).length());
    if longest == 0.0 {
        0.0
    } else {
        twice_area / longest
    }
}
