//! A scene that folds onto itself: a tube around a trefoil knot whose radius swells and
//! shrinks, so that the strands of the knot press through each other where they pass close. The knot is the (2, 3) torus knot
//! `((2 + cos 3s) cos 2s, (2 + cos 3s) sin 2s, sin 3s)`; the tube's cross-section is a ring of
//! `sides` vertices in the plane normal to the curve. Every frame is a closed-form function
//! of the time, reproducible bit for bit.

use crate::mesh::Mesh;
use glam::Vec3;
use std::f32::consts::TAU;

/// The smallest radius and the largest. The strands of the knot pass 1.66 apart at their
/// closest and its tightest bend has a radius of 1.43, so the thinnest tube touches nowhere
/// and the thickest (radius 1.1) presses its strands into each other.
pub const RADIUS_RANGE: (f32, f32) = (0.2, 1.1);

/// Angular frequency of the swelling (rad/s): one full swell every `TAU / 1.5` seconds.
pub const SWELL_OMEGA: f32 = 1.5;

/// The tube: the curve sampled at `segments` points, each with two unit vectors spanning its
/// normal plane.
#[derive(Clone, Debug)]
pub struct KnottedTube {
    centres: Vec<Vec3>,
    normals: Vec<(Vec3, Vec3)>,
    sides: usize,
    /// The triangles (and a rest pose at the smallest radius).
    pub mesh: Mesh,
}

impl KnottedTube {
    /// About `triangles` triangles (at least 8 x 3 rings of 6 sides x 2), three rings along
    /// the curve for every side around it.
    pub fn with_triangles(triangles: usize) -> KnottedTube {
        let sides = (((triangles / 6) as f64).sqrt() as usize).max(6);
        let segments = (triangles / (2 * sides)).max(24);
        Self::new(segments, sides)
    }

    pub fn new(segments: usize, sides: usize) -> KnottedTube {
        let centres: Vec<Vec3> = (0..segments)
            .map(|i| trefoil(TAU * i as f32 / segments as f32))
            .collect();
        // The knot winds around z at a non-zero rate (d/ds of the angle is 2), so its tangent
        // is never parallel to z: tangent x z is a normal that never vanishes and closes up.
        let normals = (0..segments)
            .map(|i| {
                let next = centres[(i + 1) % segments];
                let prev = centres[(i + segments - 1) % segments];
                let tangent = (next - prev).normalize();
                let e1 = tangent.cross(Vec3::Z).normalize();
                (e1, tangent.cross(e1))
            })
            .collect();
        let ring = |i: usize, k: usize| ((i % segments) * sides + k % sides) as u32;
        let mut triangles = Vec::with_capacity(2 * segments * sides);
        for i in 0..segments {
            for k in 0..sides {
                let (a, b, c, d) = (
                    ring(i, k),
                    ring(i + 1, k),
                    ring(i + 1, k + 1),
                    ring(i, k + 1),
                );
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
        let mut tube = KnottedTube {
            centres,
            normals,
            sides,
            mesh: Mesh::new(Vec::new(), triangles),
        };
        tube.mesh.positions = tube.positions_at_radius(RADIUS_RANGE.0);
        tube
    }

    /// The vertices with the tube's radius `radius`.
    pub fn positions_at_radius(&self, radius: f32) -> Vec<Vec3> {
        let mut positions = Vec::with_capacity(self.centres.len() * self.sides);
        for (c, (e1, e2)) in self.centres.iter().zip(&self.normals) {
            for k in 0..self.sides {
                let angle = TAU * k as f32 / self.sides as f32;
                positions.push(*c + radius * (angle.cos() * *e1 + angle.sin() * *e2));
            }
        }
        positions
    }

    /// The radius at time `t`: from the smallest up to the largest and back.
    pub fn radius(t: f32) -> f32 {
        let (lo, hi) = RADIUS_RANGE;
        lo + (hi - lo) * 0.5 * (1.0 - (SWELL_OMEGA * t).cos())
    }

    /// The vertices at time `t` (seconds).
    pub fn positions(&self, t: f32) -> Vec<Vec3> {
        self.positions_at_radius(Self::radius(t))
    }
}

fn trefoil(s: f32) -> Vec3 {
    let r = 2.0 + (3.0 * s).cos();
    Vec3::new(r * (2.0 * s).cos(), r * (2.0 * s).sin(), (3.0 * s).sin())
}
