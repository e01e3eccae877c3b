//! The uniform grid a distance field is sampled on.

use crate::mesh::Mesh;
use glam::DVec3;
use serde::Serialize;

/// The default margin: this fraction of the box's largest side on every side.
pub const DEFAULT_MARGIN_FRACTION: f64 = 0.1;

/// `n^3` cubic voxels; voxel `(x, y, z)` is centred at `origin + spacing * (x, y, z)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Grid {
    /// The centre of voxel `[0][0][0]`.
    pub origin: DVec3,
    /// The side of a voxel (the same along every axis).
    pub spacing: f64,
    /// Voxels per axis.
    pub n: usize,
    /// How far the grid's cube reaches beyond the model's box on the box's longest axis.
    pub margin: f64,
}

impl Grid {
    /// The cube of `n^3` voxels whose outer faces enclose `mesh`'s bounding box grown by
    /// `margin` on every side, centred on the box (the shorter axes get more room).
    pub fn around(mesh: &Mesh, n: usize, margin: f64) -> anyhow::Result<Grid> {
        let b = mesh.bounds();
        Grid::around_box(b.min.as_dvec3(), b.max.as_dvec3(), n, margin)
    }

    /// [`Grid::around`] for a box.
    pub fn around_box(min: DVec3, max: DVec3, n: usize, margin: f64) -> anyhow::Result<Grid> {
        anyhow::ensure!(n >= 2, "the resolution must be at least 2, not {n}");
        anyhow::ensure!(
            margin.is_finite() && margin >= 0.0,
            "the margin must be finite and not negative, not {margin}"
        );
        let extent = (max - min).max_element();
        let side = extent + 2.0 * margin;
        anyhow::ensure!(
            side.is_finite(),
            "the model's box ({extent:e} across) grown by the margin {margin:e} on each side is \
             beyond the largest number a double holds: give a smaller margin"
        );
        anyhow::ensure!(
            side > 0.0,
            "the model's box is a single point and the margin is zero: give a positive margin"
        );
        let spacing = side / n as f64;
        let centre = (min + max) * 0.5;
        let origin = centre - DVec3::splat(side * 0.5 - spacing * 0.5);
        anyhow::ensure!(
            origin.is_finite() && spacing > 0.0,
            "the grid of {n}^3 voxels over the box {min} .. {max} is not finite"
        );
        Ok(Grid {
            origin,
            spacing,
            n,
            margin,
        })
    }

    /// The default margin for `mesh`: [`DEFAULT_MARGIN_FRACTION`] of its box's longest side.
    pub fn default_margin(mesh: &Mesh) -> f64 {
        mesh.bounds().size().max_element() as f64 * DEFAULT_MARGIN_FRACTION
    }

    /// Voxels in all.
    pub fn len(&self) -> usize {
        self.n * self.n * self.n
    }

    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// The index of voxel `(x, y, z)` in `[z][y][x]` order.
    pub fn index(&self, x: usize, y: usize, z: usize) -> usize {
        (z * self.n + y) * self.n + x
    }

    /// The centre of voxel `(x, y, z)`.
    pub fn point(&self, x: usize, y: usize, z: usize) -> DVec3 {
        self.origin + self.spacing * DVec3::new(x as f64, y as f64, z as f64)
    }

    /// `[n, n, n]`, the shape of the `[z][y][x]` array.
    pub fn shape(&self) -> [usize; 3] {
        [self.n; 3]
    }

    /// Half a voxel's diagonal: a voxel centre farther than this from a surface has no part
    /// of the surface in its voxel.
    pub fn half_diagonal(&self) -> f64 {
        0.5 * 3f64.sqrt() * self.spacing
    }
}
