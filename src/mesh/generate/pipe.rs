//! A thick-walled pipe bent into a U: a closed genus-1 solid.

use std::f32::consts::PI;

use glam::Vec3;

use super::push_quad;
use crate::mesh::Mesh;

/// A pipe with an annular cross-section (radii `outer_radius` > `inner_radius`) swept
/// along a U in the xy plane: a straight leg up the line `x = -bend_radius` from
/// `y = -leg_length` to 0, a half circle of radius `bend_radius` over the top, and a leg
/// back down `x = +bend_radius`. Both ends are closed by flat annular caps, so the
/// surface is closed with genus 1 (a thick tube is a solid torus).
///
/// `around` vertices per circle, `stations` cross-sections spaced evenly by arc length;
/// each station has an outer and an inner circle, so there are
/// `2 * around * stations` vertices and twice as many triangles.
#[derive(Clone, Debug, PartialEq)]
pub struct Pipe {
    pub outer_radius: f32,
    pub inner_radius: f32,
    pub bend_radius: f32,
    pub leg_length: f32,
    pub around: usize,
    pub stations: usize,
}

impl Default for Pipe {
    /// Paper 4's pipe has 4626 vertices and 9252 triangles; 34 x 68 stations gives the
    /// nearest count this construction can: 4624 / 9248.
    fn default() -> Self {
        Self {
            outer_radius: 0.25,
            inner_radius: 0.18,
            bend_radius: 0.6,
            leg_length: 1.0,
            around: 34,
            stations: 68,
        }
    }
}

impl Pipe {
    /// Length of the centre line.
    pub fn path_length(&self) -> f32 {
        2.0 * self.leg_length + PI * self.bend_radius
    }

    /// Point and unit tangent of the centre line at arc length `s`.
    pub fn path(&self, s: f32) -> (Vec3, Vec3) {
        let (l, r) = (self.leg_length, self.bend_radius);
        let bend = PI * r;
        if s <= l {
            (Vec3::new(-r, s - l, 0.0), Vec3::Y)
        } else if s <= l + bend {
            // Angle from pi down to 0: over the top, clockwise seen from +z.
            let alpha = PI - (s - l) / r;
            let (sa, ca) = alpha.sin_cos();
            (Vec3::new(r * ca, r * sa, 0.0), Vec3::new(sa, -ca, 0.0))
        } else {
            (Vec3::new(r, -(s - l - bend), 0.0), -Vec3::Y)
        }
    }
}

/// The mesh of `pipe` (see [`Pipe`]).
pub fn pipe(pipe: &Pipe) -> Mesh {
    let (na, ns) = (pipe.around.max(3), pipe.stations.max(2));
    let mut positions = Vec::with_capacity(2 * na * ns);
    for k in 0..ns {
        let s = pipe.path_length() * k as f32 / (ns - 1) as f32;
        let (centre, tangent) = pipe.path(s);
        // The path is planar, so z is a fixed binormal and N = B x T stays in-plane.
        let binormal = Vec3::Z;
        let normal = binormal.cross(tangent);
        for radius in [pipe.outer_radius, pipe.inner_radius] {
            for j in 0..na {
                let (sn, cs) = (2.0 * PI * j as f32 / na as f32).sin_cos();
                positions.push(centre + radius * (cs * normal + sn * binormal));
            }
        }
    }
    // Vertex j of station k on the outer (wall 0) or inner (wall 1) circle.
    let id = |k: usize, wall: usize, j: usize| ((2 * k + wall) * na + j % na) as u32;
    let mut triangles = Vec::with_capacity(4 * na * ns);
    for k in 0..ns - 1 {
        for j in 0..na {
            // (T, N, B) is right-handed and the angle turns from N to B, so
            // dP/ds x dP/dangle = T x B = -N: the (s, angle) order faces the axis. The
            // outer wall goes the other way round to face out; the inner wall faces
            // the bore, toward the axis.
            push_quad(
                &mut triangles,
                [
                    id(k, 0, j),
                    id(k, 0, j + 1),
                    id(k + 1, 0, j + 1),
                    id(k + 1, 0, j),
                ],
            );
            push_quad(
                &mut triangles,
                [
                    id(k, 1, j),
                    id(k + 1, 1, j),
                    id(k + 1, 1, j + 1),
                    id(k, 1, j + 1),
                ],
            );
        }
    }
    let last = ns - 1;
    for j in 0..na {
        // outer j, outer j+1, inner j+1, inner j runs counter-clockwise about +T: the
        // end cap (facing +T) uses it, the start cap (facing -T) the reverse.
        push_quad(
            &mut triangles,
            [id(0, 0, j), id(0, 1, j), id(0, 1, j + 1), id(0, 0, j + 1)],
        );
        push_quad(
            &mut triangles,
            [
                id(last, 0, j),
                id(last, 0, j + 1),
                id(last, 1, j + 1),
                id(last, 1, j),
            ],
        );
    }
    Mesh::new(positions, triangles)
}
