//! The displaced surface: a height map laid on the top of a box in the world, and the grid
//! space the tracers work in.
//!
//! World: the box `[0, Lx] x [0, Ly] x [0, Lz]`, its longer side 2, texels square, the
//! height map's value h at height `h Lz`. Grid space: x and y in patch units (patch (i, j)
//! spans `[i, i + 1] x [j, j + 1]`), z the height in [0, 1]. World to grid is a diagonal
//! scale, so a ray keeps its parameter (distance along the unit world direction).

use super::patch::Corners;
use crate::lecture3::error::{check_range, Error};
use crate::lecture3::HeightMap;
use glam::{DVec3, Vec3};

/// A height map on a box.
#[derive(Clone, Debug)]
pub struct Surface {
    pub map: HeightMap,
    /// (Lx, Ly, Lz): the box in world units.
    pub size: Vec3,
}

impl Surface {
    /// `depth` is Lz, the height of a white sample, in world units (the box's longer side is
    /// 2); `--depth` on the command line.
    pub fn new(map: HeightMap, depth: f32) -> Result<Surface, Error> {
        check_range("--depth", depth as f64, 1e-3, 2.0)?;
        let (wp, hp) = map.patches();
        let longer = wp.max(hp) as f32;
        let size = Vec3::new(2.0 * wp as f32 / longer, 2.0 * hp as f32 / longer, depth);
        Ok(Surface { map, size })
    }

    /// Patches along x and y.
    pub fn patches(&self) -> (u32, u32) {
        self.map.patches()
    }

    /// World to grid: multiply each coordinate by this.
    pub fn world_to_grid(&self) -> Vec3 {
        let (wp, hp) = self.patches();
        Vec3::new(
            wp as f32 / self.size.x,
            hp as f32 / self.size.y,
            1.0 / self.size.z,
        )
    }

    /// The centre of the box (where the camera looks).
    pub fn centre(&self) -> Vec3 {
        0.5 * self.size
    }

    /// Corner heights of patch (i, j), raised by `offset`.
    pub fn corners(&self, i: u32, j: u32, offset: f64) -> Corners {
        let h = |x, y| self.map.at(x, y) as f64 + offset;
        [h(i, j), h(i + 1, j), h(i, j + 1), h(i + 1, j + 1)]
    }

    /// A grid point in the world.
    pub fn grid_to_world(&self, p: DVec3) -> DVec3 {
        p / self.world_to_grid().as_dvec3()
    }
}
