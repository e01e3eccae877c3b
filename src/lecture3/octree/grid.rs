//! The voxel grid the octree is built over: a point set (random points on shapes, or points
//! sampled on a mesh's triangles) binned into `N^3` voxels of the unit cube, and the 2D layout
//! of a 3D grid in a texture: slice z of an `n^3` level is the tile `(z % tx, z / tx)` of
//! `tx x ty` tiles of `n x n` texels.

use crate::lecture3::error::Error;
use crate::mesh::Mesh;
use glam::Vec3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The largest grid side (the traversal shader holds 8 levels).
pub const MAX_RESOLUTION: u32 = 128;

/// Tiles per row and rows of tiles of an `n^3` level: about square.
pub fn tiles(n: u32) -> (u32, u32) {
    let tx = 1u32 << n.trailing_zeros().div_ceil(2);
    (tx, n.div_ceil(tx))
}

/// The texture size of an `n^3` level.
pub fn texture_size(n: u32) -> (u32, u32) {
    let (tx, ty) = tiles(n);
    (n * tx, n * ty)
}

/// Where voxel (i, j, l) of an `n^3` level lies in its texture.
pub fn texel(n: u32, i: u32, j: u32, l: u32) -> (u32, u32) {
    let (tx, _) = tiles(n);
    (i + (l % tx) * n, j + (l / tx) * n)
}

/// An `n^3` grid of occupancy (0 or 1), voxel (i, j, l) at `(l n + j) n + i`.
#[derive(Clone, Debug, PartialEq)]
pub struct VoxelGrid {
    pub n: u32,
    pub occupied: Vec<f32>,
}

impl VoxelGrid {
    /// Points in the unit cube binned into `n^3` voxels (`n` a power of two, 2 to 128).
    pub fn from_points(n: u32, points: &[Vec3]) -> Result<VoxelGrid, Error> {
        if !n.is_power_of_two() || !(2..=MAX_RESOLUTION).contains(&n) {
            return Err(Error::input(
                "--resolution",
                format!("{n}: a power of two from 2 to {MAX_RESOLUTION} is needed"),
            ));
        }
        let mut occupied = vec![0.0; (n * n * n) as usize];
        for (k, p) in points.iter().enumerate() {
            if !p.is_finite() || p.min_element() < 0.0 || p.max_element() > 1.0 {
                return Err(Error::input(
                    "the points",
                    format!("point {k} ({p}) is not in the unit cube"),
                ));
            }
            let v = (*p * n as f32).as_uvec3().min(glam::UVec3::splat(n - 1));
            occupied[((v.z * n + v.y) * n + v.x) as usize] = 1.0;
        }
        Ok(VoxelGrid { n, occupied })
    }

    pub fn at(&self, i: u32, j: u32, l: u32) -> bool {
        self.occupied[((l * self.n + j) * self.n + i) as usize] > 0.0
    }

    /// Occupied voxels.
    pub fn count(&self) -> usize {
        self.occupied.iter().filter(|&&v| v > 0.0).count()
    }

    /// The grid in its texture layout (row by row from the bottom), 0 in unused tiles.
    pub fn tiled(&self) -> Vec<f32> {
        tile(self.n, |i, j, l| {
            self.occupied[((l * self.n + j) * self.n + i) as usize]
        })
    }
}

/// An `n^3` level in its texture layout, `value(i, j, l)` per voxel.
pub fn tile(n: u32, value: impl Fn(u32, u32, u32) -> f32) -> Vec<f32> {
    let (w, h) = texture_size(n);
    let mut out = vec![0.0; (w * h) as usize];
    for l in 0..n {
        for j in 0..n {
            for i in 0..n {
                let (x, y) = texel(n, i, j, l);
                out[(y * w + x) as usize] = value(i, j, l);
            }
        }
    }
    out
}

/// `count` random points (fixed `seed`) on three shapes in the unit cube: a sphere's shell, a
/// torus and a small dense cluster, so that most of the cube is empty space.
pub fn shape_points(count: usize, seed: u64) -> Vec<Vec3> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|k| {
            let (u, v): (f32, f32) = (rng.gen(), rng.gen());
            let (a, b) = (std::f32::consts::TAU * u, std::f32::consts::TAU * v);
            match k % 3 {
                0 => {
                    // Sphere shell about (0.35, 0.4, 0.45), radius 0.25.
                    let z = 2.0 * v - 1.0;
                    let r = (1.0 - z * z).sqrt();
                    Vec3::new(0.35, 0.4, 0.45) + 0.25 * Vec3::new(r * a.cos(), r * a.sin(), z)
                }
                1 => {
                    // Torus about (0.65, 0.6, 0.6), radii 0.2 and 0.06, lying in xz.
                    let ring = Vec3::new(a.cos(), 0.0, a.sin());
                    let tube = 0.06 * (b.cos() * ring + b.sin() * Vec3::Y);
                    Vec3::new(0.65, 0.6, 0.6) + 0.2 * ring + tube
                }
                _ => Vec3::new(0.8, 0.2, 0.25) + 0.05 * (Vec3::new(u, v, rng.gen()) - 0.5),
            }
        })
        .collect()
}

/// `count` points sampled on `mesh`'s triangles (area-weighted, fixed `seed`), the mesh scaled
/// uniformly into the unit cube with a margin of 2%.
pub fn mesh_points(mesh: &Mesh, count: usize, seed: u64) -> Result<Vec<Vec3>, Error> {
    let areas = mesh.face_areas();
    let total: f64 = areas.iter().map(|&a| a as f64).sum();
    if mesh.triangle_count() == 0 || total.is_nan() || total <= 0.0 {
        return Err(Error::input(
            "the model",
            "has no triangle of positive area",
        ));
    }
    let bounds = mesh.bounds();
    let scale = 0.96 / bounds.size().max_element().max(f32::MIN_POSITIVE);
    let centre = bounds.center();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut cumulative = Vec::with_capacity(areas.len());
    let mut sum = 0.0;
    for &a in &areas {
        sum += a as f64 / total;
        cumulative.push(sum);
    }
    Ok((0..count)
        .map(|_| {
            let pick: f64 = rng.gen();
            let t = cumulative
                .partition_point(|&c| c < pick)
                .min(areas.len() - 1);
            let [a, b, c] = mesh.triangle(t);
            let (mut u, mut v): (f32, f32) = (rng.gen(), rng.gen());
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            let p = a + u * (b - a) + v * (c - a);
            ((p - centre) * scale + Vec3::splat(0.5)).clamp(Vec3::ZERO, Vec3::ONE)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_voxel_has_its_own_texel() {
        for n in [2, 4, 8, 16, 32, 64] {
            let (w, h) = texture_size(n);
            let mut seen = vec![false; (w * h) as usize];
            for l in 0..n {
                for j in 0..n {
                    for i in 0..n {
                        let (x, y) = texel(n, i, j, l);
                        assert!(x < w && y < h);
                        assert!(!std::mem::replace(&mut seen[(y * w + x) as usize], true));
                    }
                }
            }
        }
    }
}
