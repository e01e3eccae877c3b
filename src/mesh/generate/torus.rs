//! Tori: paper 4's (a 32 x 32 vertex grid with its seams duplicated) and closed ones of
//! a requested size for paper 1.

use std::f32::consts::PI;

use glam::Vec3;

use super::push_quad;
use crate::mesh::Mesh;

/// The point at angle `phi` around the z axis and `theta` around the tube.
fn torus_point(major: f32, minor: f32, phi: f32, theta: f32) -> Vec3 {
    let (sp, cp) = phi.sin_cos();
    let (st, ct) = theta.sin_cos();
    Vec3::new(
        (major + minor * ct) * cp,
        (major + minor * ct) * sp,
        minor * st,
    )
}

/// A torus around the z axis as a modelling package builds it: a grid of
/// `(major_segments + 1) x (minor_segments + 1)` vertices whose last row and column
/// repeat the first (the texture seams), and `2 * major_segments * minor_segments`
/// triangles. Closed once the seams are welded ([`Mesh::is_closed`] welds). Paper 4's
/// torus (1024 / 1922) is `torus(R, r, 31, 31)`.
pub fn torus(major: f32, minor: f32, major_segments: usize, minor_segments: usize) -> Mesh {
    let (nu, nv) = (major_segments.max(3), minor_segments.max(3));
    let mut positions = Vec::with_capacity((nu + 1) * (nv + 1));
    for i in 0..=nu {
        for j in 0..=nv {
            // Use exactly the first row's angles on the seam, so the duplicates coincide.
            let phi = 2.0 * PI * (i % nu) as f32 / nu as f32;
            let theta = 2.0 * PI * (j % nv) as f32 / nv as f32;
            positions.push(torus_point(major, minor, phi, theta));
        }
    }
    let id = |i: usize, j: usize| (i * (nv + 1) + j) as u32;
    Mesh::new(positions, torus_triangles(nu, nv, id))
}

/// A torus without duplicated vertices: `major_segments * minor_segments` vertices,
/// twice as many triangles, closed, genus 1.
pub fn torus_closed(major: f32, minor: f32, major_segments: usize, minor_segments: usize) -> Mesh {
    let (nu, nv) = (major_segments.max(3), minor_segments.max(3));
    let mut positions = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let phi = 2.0 * PI * i as f32 / nu as f32;
            let theta = 2.0 * PI * j as f32 / nv as f32;
            positions.push(torus_point(major, minor, phi, theta));
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + j % nv) as u32;
    Mesh::new(positions, torus_triangles(nu, nv, id))
}

/// A closed torus with about `triangles` triangles (paper 1's tori have 15K): the grid
/// `nu x nv` with `2 nu nv` nearest to the request whose cells are closest to square
/// (`nu / nv` near `major / minor`), preferring an exact count. Exact whenever
/// `triangles / 2` has such a factorisation (15 000 = 2 x 150 x 50 for `R / r = 3`).
pub fn torus_with_triangles(major: f32, minor: f32, triangles: usize) -> Mesh {
    let (nu, nv) = torus_grid_for(triangles, major / minor);
    torus_closed(major, minor, nu, nv)
}

/// Grid size for [`torus_with_triangles`]: minimise the count error first (to within
/// 0.5 %, counted as equal), then the aspect mismatch |ln(nu / nv / aspect)|.
fn torus_grid_for(triangles: usize, aspect: f32) -> (usize, usize) {
    let quads = (triangles as f64 / 2.0).max(9.0);
    let mut best = (3usize, 3usize);
    let mut best_score = (f64::INFINITY, f64::INFINITY);
    let max_nv = quads.sqrt().ceil() as usize * 4;
    for nv in 3..=max_nv.max(3) {
        let nu = ((quads / nv as f64).round() as usize).max(3);
        let count_error = ((2 * nu * nv) as f64 - triangles as f64).abs() / triangles as f64;
        let bucket = if count_error == 0.0 {
            0.0
        } else {
            (count_error / 0.005).ceil()
        };
        let aspect_error = ((nu as f64 / nv as f64) / aspect as f64).ln().abs();
        let score = (bucket, aspect_error);
        if score < best_score {
            best_score = score;
            best = (nu, nv);
        }
    }
    best
}

/// Quads `(i, j) (i+1, j) (i+1, j+1) (i, j+1)`: counter-clockwise about
/// `dP/dphi x dP/dtheta`, which points out of the tube.
fn torus_triangles(nu: usize, nv: usize, id: impl Fn(usize, usize) -> u32) -> Vec<[u32; 3]> {
    let mut triangles = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            push_quad(
                &mut triangles,
                [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
            );
        }
    }
    triangles
}
