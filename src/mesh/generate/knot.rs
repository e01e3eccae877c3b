//! The (p, q) torus knot as a closed tube.

use std::f32::consts::PI;

use glam::Vec3;

use super::push_quad;
use crate::mesh::Mesh;

/// A tube of radius `tube_radius` around the (p, q) torus knot drawn on the torus of
/// radii `radius` and `radius / 2` around the z axis:
/// `c(t) = ((R + R/2 cos qt) cos pt, (R + R/2 cos qt) sin pt, R/2 sin qt)`.
/// `tubular_segments` rings of `radial_segments` vertices, no seam duplicates:
/// closed, genus 1 (the surface of a knotted solid torus).
#[derive(Clone, Debug, PartialEq)]
pub struct TorusKnot {
    pub p: u32,
    pub q: u32,
    pub radius: f32,
    pub tube_radius: f32,
    pub tubular_segments: usize,
    pub radial_segments: usize,
}

impl Default for TorusKnot {
    /// Paper 4's knot: a trefoil (2, 3) with 120 x 12 = 1440 vertices, 2880 triangles.
    /// The tube is thin enough that the strands never touch (the closest strands of the
    /// centre line are about 0.83 R apart, the tube is 0.4 R across).
    fn default() -> Self {
        Self {
            p: 2,
            q: 3,
            radius: 1.0,
            tube_radius: 0.2,
            tubular_segments: 120,
            radial_segments: 12,
        }
    }
}

impl TorusKnot {
    /// The knot's centre curve at parameter `t` in `[0, 2 pi)`.
    pub fn curve(&self, t: f32) -> Vec3 {
        let (p, q, r) = (self.p as f32, self.q as f32, self.radius);
        let rho = r + 0.5 * r * (q * t).cos();
        Vec3::new(
            rho * (p * t).cos(),
            rho * (p * t).sin(),
            0.5 * r * (q * t).sin(),
        )
    }

    /// `dc/dt`, exact.
    fn tangent(&self, t: f32) -> Vec3 {
        let (p, q, r) = (self.p as f32, self.q as f32, self.radius);
        let rho = r + 0.5 * r * (q * t).cos();
        let drho = -0.5 * r * q * (q * t).sin();
        let (sp, cp) = (p * t).sin_cos();
        Vec3::new(
            drho * cp - rho * p * sp,
            drho * sp + rho * p * cp,
            0.5 * r * q * (q * t).cos(),
        )
    }
}

/// The tube mesh of `knot` (see [`TorusKnot`]).
pub fn torus_knot(knot: &TorusKnot) -> Mesh {
    let (nt, nr) = (knot.tubular_segments.max(3), knot.radial_segments.max(3));
    let mut positions = Vec::with_capacity(nt * nr);
    for i in 0..nt {
        let t = 2.0 * PI * i as f32 / nt as f32;
        let centre = knot.curve(t);
        // A frame that depends on t alone, so the last ring meets the first without a
        // twist: B is perpendicular to the tangent and to the position vector (never
        // parallel to it on a torus knot), N completes the right-handed (T, N, B).
        let tangent = knot.tangent(t).normalize();
        let binormal = tangent.cross(centre).normalize();
        let normal = binormal.cross(tangent);
        for j in 0..nr {
            let (s, c) = (2.0 * PI * j as f32 / nr as f32).sin_cos();
            positions.push(centre + knot.tube_radius * (c * normal + s * binormal));
        }
    }
    let id = |i: usize, j: usize| ((i % nt) * nr + j % nr) as u32;
    let mut triangles = Vec::with_capacity(2 * nt * nr);
    for i in 0..nt {
        for j in 0..nr {
            // dP/dt x dP/dangle = T x B = -N points into the tube, so go the other way.
            push_quad(
                &mut triangles,
                [id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)],
            );
        }
    }
    Mesh::new(positions, triangles)
}
