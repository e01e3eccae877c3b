//! The GPU ray casts: a full-screen pass in which each fragment casts its pixel's ray into the
//! voxel grid, through the octree ([`Search::Octree`], `octree_cast.frag`) or voxel by voxel
//! ([`Search::Flat`], `octree_flat.frag`), and writes the first occupied voxel.
//!
//! World: the cube `[0, 2]^3` (centre (1, 1, 1)); grid space: `[0, N]^3`, one unit per voxel.

use super::grid::{self, VoxelGrid};
use super::levels::{GpuLevels, LevelBuilder};
use crate::gl::{Context, Framebuffer, GlError, Program, Rect, Texture, TextureFormat};
use crate::lecture3::displacement::Camera;
use crate::lecture3::error::Error;
use crate::shader;
use glam::{IVec3, Vec3};
use serde::Serialize;

/// How the fragment shader searches the grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Search {
    /// Top-down through the occupancy octree, empty nodes crossed whole.
    Octree,
    /// Every voxel along the ray (3D DDA over the full grid).
    Flat,
}

/// The cube's side in world units.
pub const WORLD_SIDE: f32 = 2.0;

/// The cube's centre (where cameras look).
pub fn centre() -> Vec3 {
    Vec3::splat(0.5 * WORLD_SIDE)
}

/// A voxel grid's octree on the GPU, ready to be cast into.
pub struct OctreeCaster {
    ctx: Context,
    pub levels: GpuLevels,
    octree_program: Program,
    flat_program: Program,
}

/// What one pixel's ray found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CastPixel {
    Miss,
    Hit {
        voxel: IVec3,
        /// Where the ray enters the voxel (world units along the unit direction).
        t: f64,
        steps: u32,
    },
    Unfinished,
}

/// A cast read back.
pub struct CastFrame {
    pub width: u32,
    pub height: u32,
    hit: Vec<f32>,
    stats: Vec<f32>,
}

impl CastFrame {
    pub fn pixel(&self, px: u32, py: u32) -> CastPixel {
        let i = (py * self.width + px) as usize;
        let (hit, stats) = (&self.hit[4 * i..4 * i + 4], &self.stats[4 * i..4 * i + 4]);
        match stats[1] {
            s if s < 0.0 => CastPixel::Unfinished,
            0.0 => CastPixel::Miss,
            _ => CastPixel::Hit {
                voxel: IVec3::new(hit[0] as i32, hit[1] as i32, hit[2] as i32),
                t: hit[3] as f64,
                steps: stats[0] as u32,
            },
        }
    }

    /// Every pixel, row by row from the bottom.
    pub fn pixels(&self) -> Vec<CastPixel> {
        (0..self.height)
            .flat_map(|py| (0..self.width).map(move |px| (px, py)))
            .map(|(px, py)| self.pixel(px, py))
            .collect()
    }

    /// Steps per pixel (hit or miss), as the shader counted them.
    pub fn steps(&self) -> Vec<f32> {
        self.stats.chunks_exact(4).map(|s| s[0]).collect()
    }

    /// The entry parameter of each pixel's hit, 0 where none.
    pub fn distances(&self) -> Vec<f32> {
        self.hit.chunks_exact(4).map(|h| h[3].max(0.0)).collect()
    }

    /// The hit target as read back (voxel i, j, l and t; t = -1 where nothing was hit).
    pub fn hits(&self) -> &[f32] {
        &self.hit
    }

    /// An error if any traversal ran out of steps.
    pub fn check_finished(&self) -> Result<(), Error> {
        let n = self
            .pixels()
            .iter()
            .filter(|p| **p == CastPixel::Unfinished)
            .count();
        if n > 0 {
            return Err(Error::Result(format!(
                "{n} pixels' casts did not end within their step bound"
            )));
        }
        Ok(())
    }
}

/// Where casts are drawn: hit and statistics targets.
pub struct CastTarget {
    framebuffer: Framebuffer,
}

impl OctreeCaster {
    /// Builds the octree of `voxels` on the GPU (level 0 uploaded, the rest by passes).
    pub fn new(ctx: &Context, voxels: &VoxelGrid) -> Result<OctreeCaster, GlError> {
        let ray = shader!("glsl/lecture3/pixel_ray.glsl");
        let common = shader!("glsl/lecture3/octree_common.glsl");
        Ok(OctreeCaster {
            ctx: ctx.clone(),
            levels: LevelBuilder::new(ctx)?.build(voxels)?,
            octree_program: Program::rect(
                ctx,
                &[ray, common, shader!("glsl/lecture3/octree_cast.frag")],
            )?,
            flat_program: Program::rect(
                ctx,
                &[ray, common, shader!("glsl/lecture3/octree_flat.frag")],
            )?,
        })
    }

    /// The leaf grid's side.
    pub fn n(&self) -> u32 {
        self.levels.n
    }

    pub fn target(&self, width: u32, height: u32) -> Result<CastTarget, GlError> {
        let hit = Texture::new_2d(&self.ctx, width, height, TextureFormat::Rgba32F)?;
        let stats = Texture::new_2d(&self.ctx, width, height, TextureFormat::Rgba32F)?;
        Ok(CastTarget {
            framebuffer: Framebuffer::new(&self.ctx, "octree cast", &[&hit, &stats], None)?,
        })
    }

    /// A bound on any cast's steps: the flat walk crosses at most 3N voxels; the octree's
    /// each of those at most once per level, entering and leaving.
    pub fn max_iterations(&self) -> i32 {
        (3 * self.n() as i32 + 3) * 2 * (self.levels.count() as i32 + 1)
    }

    /// Casts every pixel of `camera` into `target` (its size must be the camera's).
    pub fn cast(
        &self,
        target: &CastTarget,
        camera: &Camera,
        search: Search,
    ) -> Result<(), GlError> {
        let fb = &target.framebuffer;
        let program = match search {
            Search::Octree => &self.octree_program,
            Search::Flat => &self.flat_program,
        };
        let tiles_x: Vec<i32> = (0..8)
            .map(|k| grid::tiles((self.n() >> k).max(1)).0 as i32)
            .collect();
        let mut pass = fb.pass(program, "octree ray cast")?;
        camera.set_ray_uniforms(&mut pass, fb)?;
        pass.uniform("u_world_to_grid", self.n() as f32 / WORLD_SIDE)
            .uniform("u_n", self.n() as i32)
            .uniform_if_used("u_top", self.levels.count() as i32 - 1)
            .uniform("u_tiles_x", &tiles_x[..])
            .uniform("u_max_iterations", self.max_iterations());
        // The flat search reads level 0 only (the compiler may drop the other samplers).
        let bound = if search == Search::Octree { 8 } else { 1 };
        for k in 0..bound {
            let texture = self
                .levels
                .textures
                .get(k)
                .unwrap_or(&self.levels.textures[0]);
            pass.texture(&format!("u_level{k}"), texture);
        }
        pass.draw_full()
    }

    pub fn read(&self, target: &CastTarget) -> Result<CastFrame, GlError> {
        let fb = &target.framebuffer;
        let rect = Rect::sized(fb.width(), fb.height());
        Ok(CastFrame {
            width: fb.width(),
            height: fb.height(),
            hit: fb.read_f32(0, rect)?,
            stats: fb.read_f32(1, rect)?,
        })
    }
}
