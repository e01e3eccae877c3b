//! Framing: the orthographic view that projects the whole body onto the framebuffer
//! [section 3.1, step 1: "render the geometry with an orthographic projection onto the xy
//! plane"], looking down the negative z axis.
//!
//! The integrands are evaluated about the framing centre rather than the world origin:
//! `sgn(n_z) z` then changes sign inside the body and the fp32 sums lose less to
//! cancellation; [`crate::mass::VolumeIntegrals::about`] moves the result back.

use crate::mesh::Mesh;
use glam::camera::rh::proj::opengl;
use glam::{DVec2, DVec3, Mat4, Vec3};
use serde::Serialize;

/// How far outside a triangle (pixels) a pixel centre may lie and still keep it in
/// [`Framing::may_cover_pixel_centre`]: four times llvmpipe's sub-pixel step (1/256).
pub const CULL_MARGIN_PIXELS: f64 = 1.0 / 64.0;

/// Triangles whose bounding box holds more pixel centres than this are kept without testing
/// them one by one (they nearly always hold one).
const MAX_CENTRES_TESTED: f64 = 64.0;

/// A square orthographic window of `resolution` x `resolution` pixels.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Framing {
    /// World point at the centre of the window and of the depth range.
    pub center: DVec3,
    /// Half the side of the square window (world units).
    pub half_width: f64,
    /// Half the depth range (world units).
    pub half_depth: f64,
    pub resolution: u32,
}

impl Framing {
    /// The tightest square window around `mesh`'s bounding box that leaves one empty
    /// pixel on every side, so no fragment is lost at the border. Errors on an empty mesh,
    /// non-finite coordinates, or a mesh that is a single point.
    pub fn fit(mesh: &Mesh, resolution: u32) -> Result<Self, String> {
        let (lo, hi) = bounds(mesh.positions.iter().copied())
            .ok_or_else(|| "the mesh has no vertices".to_string())?;
        Self::fit_box(lo.as_dvec3(), hi.as_dvec3(), resolution)
    }

    /// As [`Framing::fit`] for an axis-aligned box.
    pub fn fit_box(lo: DVec3, hi: DVec3, resolution: u32) -> Result<Self, String> {
        if !(lo.is_finite() && hi.is_finite()) {
            return Err("the mesh has non-finite coordinates".into());
        }
        if resolution < 4 {
            return Err(format!("resolution {resolution} is too small (at least 4)"));
        }
        let size = (hi - lo).max_element();
        if size <= 0.0 {
            return Err("all of the mesh's vertices are at one point".into());
        }
        // A flat body still gets a window and a depth range (a millionth of its size:
        // the floor scales with the body, which may be 10^-20 or 10^38 across).
        let extent = (hi - lo).max(DVec3::splat(1e-6 * size));
        let n = resolution as f64;
        let half_width = 0.5 * extent.x.max(extent.y) * n / (n - 2.0);
        Ok(Self {
            center: (lo + hi) / 2.0,
            half_width,
            // A little slack so the near and far planes never clip a vertex.
            half_depth: 0.5 * extent.z * 1.01 + 1e-6 * half_width,
            resolution,
        })
    }

    /// Side of one pixel; its area is the `dx dy` of eq. 4 and 6.
    pub fn pixel_size(&self) -> f64 {
        2.0 * self.half_width / self.resolution as f64
    }

    /// Centre of pixel (i, j), relative to the framing centre.
    pub fn pixel_center(&self, i: u32, j: u32) -> (f64, f64) {
        let s = self.pixel_size();
        (
            -self.half_width + (i as f64 + 0.5) * s,
            -self.half_width + (j as f64 + 0.5) * s,
        )
    }

    /// Whether a triangle with world corners `corners` can produce a fragment: GL makes one
    /// only where a pixel centre lies inside, so a triangle that holds no pixel centre (most
    /// triangles of a detailed mesh seen at 32 x 32) can be skipped without changing any
    /// sum. See [`covers_pixel_centre`], which takes corners made once per vertex of a mesh
    /// ([`Framing::pixel_vertex`]).
    pub fn may_cover_pixel_centre(&self, corners: [DVec3; 3]) -> bool {
        let [a, b, c] = corners.map(|p| self.pixel_vertex(p));
        covers_pixel_centre(&a, &b, &c)
    }

    /// `p` in pixel units of this window (pixel centre (i, j) at the integer point (i, j)),
    /// with the centres within [`CULL_MARGIN_PIXELS`] of it on each axis.
    pub fn pixel_vertex(&self, p: DVec3) -> PixelVertex {
        let s = self.pixel_size();
        let p = DVec2::new(
            (p.x - self.center.x + self.half_width) / s - 0.5,
            (p.y - self.center.y + self.half_width) / s - 0.5,
        );
        let m = CULL_MARGIN_PIXELS;
        // Far outside the window (or not finite): its triangles are kept untested.
        if !(p.x.abs() < 1e9 && p.y.abs() < 1e9) {
            return PixelVertex {
                p,
                first: [i32::MIN / 2; 2],
                last: [i32::MAX / 2; 2],
            };
        }
        PixelVertex {
            p,
            first: [ceil(p.x - m), ceil(p.y - m)],
            last: [floor(p.x + m), floor(p.y + m)],
        }
    }

    /// Clip-space transform of framing-relative coordinates: x, y onto [-1, 1], and the
    /// depth range so that higher z is nearer (depth 0 at the top, looking down -z).
    pub fn projection(&self) -> Mat4 {
        let w = self.half_width as f32;
        let d = self.half_depth as f32;
        opengl::orthographic(-w, w, -w, w, -d, d)
    }
}

/// A vertex in a window's pixel units and the pixel-centre columns and rows its margin
/// reaches: a triangle's box of centres is then integer minima and maxima.
#[derive(Clone, Copy, Debug)]
pub struct PixelVertex {
    p: DVec2,
    /// Lowest centre column and row at or above `p - margin`.
    first: [i32; 2],
    /// Highest centre column and row at or below `p + margin`.
    last: [i32; 2],
}

/// Whether the triangle with corners `a`, `b`, `c` ([`Framing::pixel_vertex`]) holds a
/// pixel centre. Exact up to a margin of [`CULL_MARGIN_PIXELS`]: a centre that close outside
/// an edge still keeps the triangle (the rasterizer snaps vertices to a sub-pixel grid, and
/// the GPU receives them in fp32). A triangle whose box holds many centres is kept untested.
pub fn covers_pixel_centre(a: &PixelVertex, b: &PixelVertex, c: &PixelVertex) -> bool {
    let x0 = a.first[0].min(b.first[0]).min(c.first[0]);
    let x1 = a.last[0].max(b.last[0]).max(c.last[0]);
    let y0 = a.first[1].min(b.first[1]).min(c.first[1]);
    let y1 = a.last[1].max(b.last[1]).max(c.last[1]);
    if x0 > x1 || y0 > y1 {
        return false;
    }
    // In f64: a far corner's range spans all of i32.
    let centres = (x1 as f64 - x0 as f64 + 1.0) * (y1 as f64 - y0 as f64 + 1.0);
    let (a, b, c) = (a.p, b.p, c.p);
    let doubled_area = (b - a).perp_dot(c - a);
    if centres > MAX_CENTRES_TESTED || doubled_area.abs() < 1e-9 {
        return true;
    }
    // Each edge's inward distance at a centre inside is >= -margin: with the edge
    // function f = e x (p - u) (oriented inward), f >= 0 or f^2 <= margin^2 |e|^2.
    let m = CULL_MARGIN_PIXELS;
    let orient = doubled_area.signum();
    let edges = [(a, b), (b, c), (c, a)].map(|(u, v)| (u, (v - u) * orient));
    let inside = |p: DVec2| {
        edges.iter().all(|&(u, e)| {
            let f = e.perp_dot(p - u);
            f >= 0.0 || f * f <= m * m * e.length_squared()
        })
    };
    (y0..=y1).any(|j| (x0..=x1).any(|i| inside(DVec2::new(i as f64, j as f64))))
}

/// The least integer >= `x` (|x| < 2^30), without a libm call.
fn ceil(x: f64) -> i32 {
    let t = x as i32;
    t + ((t as f64) < x) as i32
}

/// The greatest integer <= `x` (|x| < 2^30), without a libm call.
fn floor(x: f64) -> i32 {
    let t = x as i32;
    t - ((t as f64) > x) as i32
}

/// Component-wise bounds of a point set.
pub fn bounds(points: impl IntoIterator<Item = Vec3>) -> Option<(Vec3, Vec3)> {
    points.into_iter().fold(None, |acc, p| match acc {
        None => Some((p, p)),
        Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small triangle whose nearest edge passes `d` pixels from pixel centre (10, 10) and
    /// holds no other centre.
    fn triangle_beside_centre(framing: &Framing, d: f64) -> [DVec3; 3] {
        let s = framing.pixel_size();
        let world = |px: f64, py: f64| {
            DVec3::new(
                (px + 0.5) * s - framing.half_width + framing.center.x,
                (py + 0.5) * s - framing.half_width + framing.center.y,
                0.0,
            )
        };
        [
            world(9.6, 10.0 + d),
            world(10.4, 10.0 + d),
            world(10.0, 10.8),
        ]
    }

    #[test]
    fn the_cull_keeps_a_centre_within_the_margin_and_drops_one_beyond_it() {
        let framing = Framing::fit_box(DVec3::splat(-1.0), DVec3::splat(1.0), 32).unwrap();
        let m = CULL_MARGIN_PIXELS;
        for (d, kept) in [
            (-0.1, true),
            (0.5 * m, true),
            (0.9 * m, true),
            (1.5 * m, false),
        ] {
            let mut corners = triangle_beside_centre(&framing, d);
            assert_eq!(framing.may_cover_pixel_centre(corners), kept, "d = {d}");
            // Either winding.
            corners.swap(0, 1);
            assert_eq!(
                framing.may_cover_pixel_centre(corners),
                kept,
                "d = {d}, turned"
            );
        }
    }

    #[test]
    fn a_triangle_with_a_far_or_not_finite_corner_is_kept() {
        let framing = Framing::fit_box(DVec3::splat(-1.0), DVec3::splat(1.0), 32).unwrap();
        let near = triangle_beside_centre(&framing, 0.5);
        for far in [
            DVec3::new(1e12, 0.0, 0.0),
            DVec3::new(-3e9, 5e9, 0.0),
            DVec3::NAN,
        ] {
            assert!(
                framing.may_cover_pixel_centre([near[0], near[1], far]),
                "{far}"
            );
        }
    }

    #[test]
    fn integer_ceil_and_floor_match_the_float_ones() {
        for x in [
            -2.5,
            -2.0,
            -1e-9,
            0.0,
            1e-9,
            0.5,
            3.0,
            3.25,
            -1e6 - 0.5,
            1e6 + 0.5,
        ] {
            assert_eq!(ceil(x) as f64, x.ceil(), "{x}");
            assert_eq!(floor(x) as f64, x.floor(), "{x}");
        }
    }
}
