//! Cube, box and UV sphere.

use std::f32::consts::PI;

use glam::Vec3;

use super::push_quad;
use crate::mesh::Mesh;

/// An axis-aligned cube of edge `edge` centred on the origin: 8 vertices, 12 triangles.
pub fn cube(edge: f32) -> Mesh {
    cuboid(Vec3::splat(0.5 * edge))
}

/// An axis-aligned box with the given half extents, centred on the origin: 8 vertices,
/// 12 triangles. Vertex `i` has the sign pattern of its bits (bit 0: +x, 1: +y, 2: +z).
pub fn cuboid(half: Vec3) -> Mesh {
    let positions = (0..8)
        .map(|i| {
            let sign = |bit: u32| if i & (1 << bit) != 0 { 1.0 } else { -1.0 };
            half * Vec3::new(sign(0), sign(1), sign(2))
        })
        .collect();
    // Each face's corners counter-clockwise seen from outside.
    let faces = [
        [0, 4, 6, 2], // -x
        [1, 3, 7, 5], // +x
        [0, 1, 5, 4], // -y
        [2, 6, 7, 3], // +y
        [0, 2, 3, 1], // -z
        [4, 5, 7, 6], // +z
    ];
    let mut triangles = Vec::with_capacity(12);
    faces.into_iter().for_each(|f| push_quad(&mut triangles, f));
    Mesh::new(positions, triangles)
}

/// A UV sphere: `segments` meridians (at least 3) and `rings` bands from pole to pole (at
/// least 2), poles on the z axis. One vertex per pole, no seam duplicates:
/// `2 + (rings - 1) * segments` vertices and `2 * segments * (rings - 1)` triangles.
/// Paper 4's sphere (422 / 840) is `uv_sphere(r, 30, 15)`.
pub fn uv_sphere(radius: f32, segments: usize, rings: usize) -> Mesh {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let mut positions = vec![Vec3::new(0.0, 0.0, radius)];
    for k in 1..rings {
        let theta = PI * k as f32 / rings as f32;
        for j in 0..segments {
            let phi = 2.0 * PI * j as f32 / segments as f32;
            let (st, ct) = theta.sin_cos();
            let (sp, cp) = phi.sin_cos();
            positions.push(radius * Vec3::new(st * cp, st * sp, ct));
        }
    }
    positions.push(Vec3::new(0.0, 0.0, -radius));
    let north = 0u32;
    let south = positions.len() as u32 - 1;
    let ring = |k: usize, j: usize| (1 + (k - 1) * segments + j % segments) as u32;

    let mut triangles = Vec::with_capacity(2 * segments * (rings - 1));
    for j in 0..segments {
        triangles.push([north, ring(1, j), ring(1, j + 1)]);
    }
    for k in 1..rings - 1 {
        for j in 0..segments {
            push_quad(
                &mut triangles,
                [
                    ring(k, j),
                    ring(k + 1, j),
                    ring(k + 1, j + 1),
                    ring(k, j + 1),
                ],
            );
        }
    }
    for j in 0..segments {
        triangles.push([ring(rings - 1, j), south, ring(rings - 1, j + 1)]);
    }
    Mesh::new(positions, triangles)
}
