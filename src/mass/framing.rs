//! Framing: the orthographic view that projects the whole body onto the framebuffer
//! [section 3.1, step 1: "render the geometry with an orthographic projection onto the xy
//! plane"], looking down the negative z axis.
//!
//! The integrands are evaluated about the framing centre rather than the world origin:
//! `sgn(n_z) z` then changes sign inside the body and the fp32 sums lose less to
//! cancellation; [`crate::mass::VolumeIntegrals::about`] moves the result back.

use crate::mesh::Mesh;
use glam::camera::rh::proj::opengl;
use glam::{DVec3, Mat4, Vec3};
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
    /// sum. Exact up to a margin of [`CULL_MARGIN_PIXELS`]: a centre that close outside an
    /// edge still keeps the triangle (the rasterizer snaps vertices to a sub-pixel grid,
    /// and the GPU receives them in fp32). A triangle whose box holds many centres is kept
    /// untested.
    pub fn may_cover_pixel_centre(&self, corners: [DVec3; 3]) -> bool {
        let s = self.pixel_size();
        // Pixel units: centre (i, j) at the integer point (i, j).
        let to_pixel = |p: DVec3| {
            glam::DVec2::new(
                (p.x - self.center.x + self.half_width) / s - 0.5,
                (p.y - self.center.y + self.half_width) / s - 0.5,
            )
        };
        let [a, b, c] = corners.map(to_pixel);
        let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
        let m = CULL_MARGIN_PIXELS;
        let (first, last) = ((lo - m).ceil(), (hi + m).floor());
        if first.x > last.x || first.y > last.y {
            return false;
        }
        let centres = (last - first + 1.0).element_product();
        let doubled_area = (b - a).perp_dot(c - a);
        if centres > MAX_CENTRES_TESTED || doubled_area.abs() < 1e-9 {
            return true;
        }
        // Each edge as an inward distance function: >= -margin at a centre inside.
        let orient = doubled_area.signum();
        let edges = [(a, b), (b, c), (c, a)].map(|(u, v)| {
            let length = (v - u).length().max(1e-12);
            (u, (v - u) * (orient / length))
        });
        let inside = |p: glam::DVec2| edges.iter().all(|&(u, e)| e.perp_dot(p - u) >= -m);
        (first.y as i64..=last.y as i64).any(|j| {
            (first.x as i64..=last.x as i64).any(|i| inside(glam::DVec2::new(i as f64, j as f64)))
        })
    }

    /// Clip-space transform of framing-relative coordinates: x, y onto [-1, 1], and the
    /// depth range so that higher z is nearer (depth 0 at the top, looking down -z).
    pub fn projection(&self) -> Mat4 {
        let w = self.half_width as f32;
        let d = self.half_depth as f32;
        opengl::orthographic(-w, w, -w, w, -d, d)
    }
}

/// Component-wise bounds of a point set.
pub fn bounds(points: impl IntoIterator<Item = Vec3>) -> Option<(Vec3, Vec3)> {
    points.into_iter().fold(None, |acc, p| match acc {
        None => Some((p, p)),
        Some((lo, hi)) => Some((lo.min(p), hi.max(p))),
    })
}
