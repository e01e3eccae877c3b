//! The octree as a pyramid of occupancy levels: level 0 the voxel grid (uploaded), level k + 1
//! drawn from level k by one reduction pass, each node occupied when any of its eight children
//! is (a max over 0/1 values, exact in floating point, so the GPU levels equal the CPU's bit for
//! bit). Level k is `(N >> k)^3`, its own texture in the tiled layout of [`super::grid`].

use super::grid::{self, VoxelGrid};
use crate::gl::{Context, Framebuffer, GlError, Program, Texture, TextureFormat};
use crate::shader;
use glam::IVec2;

/// One level on the CPU: an `n^3` grid, voxel (i, j, l) at `(l n + j) n + i`.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    pub n: u32,
    pub occupied: Vec<f32>,
}

impl Level {
    pub fn at(&self, i: u32, j: u32, l: u32) -> bool {
        self.occupied[((l * self.n + j) * self.n + i) as usize] > 0.0
    }

    /// The level in its texture layout.
    pub fn tiled(&self) -> Vec<f32> {
        grid::tile(self.n, |i, j, l| {
            self.occupied[((l * self.n + j) * self.n + i) as usize]
        })
    }
}

/// The CPU octree: every level from the voxel grid up to the one root node.
pub fn cpu_levels(voxels: &VoxelGrid) -> Vec<Level> {
    let mut levels = vec![Level {
        n: voxels.n,
        occupied: voxels.occupied.clone(),
    }];
    while levels.last().expect("level 0").n > 1 {
        let below = levels.last().expect("a level");
        let n = below.n / 2;
        let mut occupied = vec![0.0; (n * n * n) as usize];
        for l in 0..n {
            for j in 0..n {
                for i in 0..n {
                    let any = (0..8).any(|c| {
                        below.at(2 * i + (c & 1), 2 * j + ((c >> 1) & 1), 2 * l + (c >> 2))
                    });
                    occupied[((l * n + j) * n + i) as usize] = any as u32 as f32;
                }
            }
        }
        levels.push(Level { n, occupied });
    }
    levels
}

/// The octree's levels on the GPU, one R32F texture each.
pub struct GpuLevels {
    pub textures: Vec<Texture>,
    /// Level 0's side.
    pub n: u32,
}

impl GpuLevels {
    pub fn count(&self) -> u32 {
        self.textures.len() as u32
    }

    /// Every level read back (untiled).
    pub fn read(&self) -> Result<Vec<Level>, GlError> {
        self.textures
            .iter()
            .enumerate()
            .map(|(k, texture)| {
                let n = self.n >> k;
                let tiled = texture.download_f32()?;
                let (w, _) = grid::texture_size(n);
                let mut occupied = vec![0.0; (n * n * n) as usize];
                for l in 0..n {
                    for j in 0..n {
                        for i in 0..n {
                            let (x, y) = grid::texel(n, i, j, l);
                            occupied[((l * n + j) * n + i) as usize] = tiled[(y * w + x) as usize];
                        }
                    }
                }
                Ok(Level { n, occupied })
            })
            .collect()
    }
}

/// Builds octrees by reduction passes; compile once, build many.
pub struct LevelBuilder {
    ctx: Context,
    program: Program,
}

impl LevelBuilder {
    pub fn new(ctx: &Context) -> Result<LevelBuilder, GlError> {
        Ok(LevelBuilder {
            ctx: ctx.clone(),
            program: Program::rect(ctx, &[shader!("glsl/lecture3/octree_level.frag")])?,
        })
    }

    /// Level 0 uploaded from the voxel grid, then one pass per level above it.
    pub fn build(&self, voxels: &VoxelGrid) -> Result<GpuLevels, GlError> {
        let (w, h) = grid::texture_size(voxels.n);
        let leaf = Texture::from_f32(&self.ctx, w, h, TextureFormat::R32F, &voxels.tiled())?;
        let mut textures = vec![leaf];
        let mut n = voxels.n;
        while n > 1 {
            n /= 2;
            let (w, h) = grid::texture_size(n);
            let level = Texture::new_2d(&self.ctx, w, h, TextureFormat::R32F)?;
            let below = textures.last().expect("the level below");
            Framebuffer::new(&self.ctx, "octree level", &[&level], None)?
                .pass(&self.program, "octree level from the one below")?
                .texture("u_below", below)
                .uniform("u_n", n as i32)
                .uniform("u_tiles", tiles(n))
                .uniform("u_below_tiles", tiles(2 * n))
                .draw_full()?;
            textures.push(level);
        }
        Ok(GpuLevels {
            textures,
            n: voxels.n,
        })
    }
}

fn tiles(n: u32) -> IVec2 {
    let (tx, ty) = grid::tiles(n);
    IVec2::new(tx as i32, ty as i32)
}
