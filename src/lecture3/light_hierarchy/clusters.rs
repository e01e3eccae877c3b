//! The light hierarchy: the VPL image and the image pyramid of its clusters. Level 0 holds
//! one VPL per texel; each node of level k + 1 clusters its four children (flux summed,
//! position and normal averaged by flux, a radius that bounds every VPL below it). Built by
//! one pass per level with three render targets; [`cpu_clusters`] is the same on the CPU.
//!
//! Reconstruction: the abstract says the lights are clustered into image pyramids by "a
//! simple, fast clustering"; this 2x2 flux-weighted merge is ours.

use crate::gl::{Context, Framebuffer, GlError, Program, Texture, TextureFormat};
use crate::lecture3::pyramid_atlas::{AtlasBuilder, PyramidAtlas};
use crate::shader;
use glam::Vec3;
use serde::Serialize;

/// A VPL or a cluster of VPLs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Cluster {
    /// Flux-weighted mean position.
    pub position: Vec3,
    /// Every VPL of the cluster lies within this distance of `position` (0 for one VPL).
    pub radius: f32,
    /// Flux-weighted mean normal (not normalised).
    pub normal: Vec3,
    /// The flux's r + g + b; 0 for a texel that saw nothing.
    pub weight: f32,
    pub flux: Vec3,
    /// How many VPLs (texels) it holds.
    pub count: f32,
}

impl Cluster {
    /// From the three texels (position+radius, normal+weight, flux+count).
    pub fn from_texels(p: &[f32], n: &[f32], f: &[f32]) -> Cluster {
        Cluster {
            position: Vec3::new(p[0], p[1], p[2]),
            radius: p[3],
            normal: Vec3::new(n[0], n[1], n[2]),
            weight: n[3],
            flux: Vec3::new(f[0], f[1], f[2]),
            count: f[3],
        }
    }
}

/// One level of the hierarchy, `size x size` nodes, row by row from the bottom.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClusterLevel {
    pub size: u32,
    pub nodes: Vec<Cluster>,
}

impl ClusterLevel {
    pub fn at(&self, x: u32, y: u32) -> &Cluster {
        &self.nodes[(y * self.size + x) as usize]
    }
}

/// Four children clustered, in the shader's order and fp32 arithmetic.
pub fn merge(children: [&Cluster; 4]) -> Cluster {
    let mut out = Cluster::default();
    let mut centre = Vec3::ZERO;
    let mut normal = Vec3::ZERO;
    for c in children {
        out.flux += c.flux;
        out.count += c.count;
        out.weight += c.weight;
        centre += c.weight * c.position;
        normal += c.weight * c.normal;
    }
    if out.weight > 0.0 {
        out.position = centre / out.weight;
        out.normal = normal / out.weight;
        out.radius = children
            .iter()
            .filter(|c| c.weight > 0.0)
            .map(|c| c.position.distance(out.position) + c.radius)
            .fold(0.0, f32::max);
    }
    out
}

/// Every level from the VPL image (level 0) up to the root.
pub fn cpu_clusters(vpls: ClusterLevel) -> Vec<ClusterLevel> {
    let mut levels = vec![vpls];
    while levels.last().expect("level 0").size > 1 {
        let below = levels.last().expect("a level");
        let size = below.size / 2;
        let nodes = (0..size * size)
            .map(|i| {
                let (x, y) = (2 * (i % size), 2 * (i / size));
                merge([
                    below.at(x, y),
                    below.at(x + 1, y),
                    below.at(x, y + 1),
                    below.at(x + 1, y + 1),
                ])
            })
            .collect();
        levels.push(ClusterLevel { size, nodes });
    }
    levels
}

/// The hierarchy on the GPU: three mipmapped RGBA32F textures (position+radius,
/// normal+weight, flux+count), one level per hierarchy level, and their atlases.
pub struct GpuClusters {
    pub textures: [Texture; 3],
    /// Level 0's framebuffer, with a depth buffer (the VPL pass draws the scene into it).
    pub level0: Framebuffer,
    levels: Vec<Framebuffer>,
    pub atlases: Vec<PyramidAtlas>,
    program: Program,
    atlas_builder: AtlasBuilder,
}

impl GpuClusters {
    /// Targets for a `size x size` VPL image (size a power of two).
    pub fn new(ctx: &Context, size: u32) -> Result<GpuClusters, GlError> {
        if !size.is_power_of_two() || size < 2 {
            return Err(GlError::Invalid(format!(
                "the VPL image side must be a power of two of at least 2, not {size}"
            )));
        }
        let levels = size.trailing_zeros() + 1;
        let texture = || Texture::new_2d_mipmapped(ctx, size, size, TextureFormat::Rgba32F, levels);
        let textures = [texture()?, texture()?, texture()?];
        let refs = [&textures[0], &textures[1], &textures[2]];
        let depth = Texture::new_2d(ctx, size, size, TextureFormat::Depth32F)?;
        let level0 = Framebuffer::new(ctx, "VPL image", &refs, Some(&depth))?;
        let levels = (1..levels)
            .map(|l| Framebuffer::new_at_level(ctx, "light hierarchy level", &refs, None, l))
            .collect::<Result<_, _>>()?;
        let atlas_builder = AtlasBuilder::new(ctx)?;
        let atlases = textures
            .iter()
            .map(|t| atlas_builder.atlas(t))
            .collect::<Result<_, _>>()?;
        Ok(GpuClusters {
            textures,
            level0,
            levels,
            atlases,
            program: Program::rect(ctx, &[shader!("glsl/lecture3/cluster_level.frag")])?,
            atlas_builder,
        })
    }

    pub fn size(&self) -> u32 {
        self.textures[0].width()
    }

    /// The root's level.
    pub fn top(&self) -> u32 {
        self.textures[0].levels() - 1
    }

    /// Draws levels 1.. from level 0 (one pass per level, three targets), then copies the
    /// hierarchy into the atlases the gathers read.
    pub fn build(&self) -> Result<(), GlError> {
        let result = self.levels.iter().enumerate().try_for_each(|(i, target)| {
            let below = i as u32;
            for t in &self.textures {
                t.set_level_range(below, below)?;
            }
            target
                .pass(&self.program, "light hierarchy level")?
                .texture("u_position", &self.textures[0])
                .texture("u_normal", &self.textures[1])
                .texture("u_flux", &self.textures[2])
                .draw_full()
        });
        for t in &self.textures {
            t.set_level_range(0, t.levels() - 1)?;
        }
        result?;
        for (texture, atlas) in self.textures.iter().zip(&self.atlases) {
            self.atlas_builder.fill(texture, atlas)?;
        }
        Ok(())
    }

    /// Every level, read back from the mipmaps.
    pub fn read_levels(&self) -> Result<Vec<ClusterLevel>, GlError> {
        (0..=self.top())
            .map(|level| {
                let data = self
                    .textures
                    .iter()
                    .map(|t| t.download_level_f32(level))
                    .collect::<Result<Vec<_>, _>>()?;
                Ok(ClusterLevel {
                    size: self.size() >> level,
                    nodes: (0..data[0].len() / 4)
                        .map(|i| {
                            let s = 4 * i..4 * i + 4;
                            Cluster::from_texels(
                                &data[0][s.clone()],
                                &data[1][s.clone()],
                                &data[2][s],
                            )
                        })
                        .collect(),
                })
            })
            .collect()
    }

    /// Every level, read back from the atlases (what the gathers read).
    pub fn read_atlas_levels(&self) -> Result<Vec<ClusterLevel>, GlError> {
        (0..=self.top())
            .map(|level| {
                let data = self
                    .atlases
                    .iter()
                    .map(|a| a.read_level(level))
                    .collect::<Result<Vec<_>, _>>()?;
                Ok(ClusterLevel {
                    size: self.size() >> level,
                    nodes: (0..data[0].len() / 4)
                        .map(|i| {
                            let s = 4 * i..4 * i + 4;
                            Cluster::from_texels(
                                &data[0][s.clone()],
                                &data[1][s.clone()],
                                &data[2][s],
                            )
                        })
                        .collect(),
                })
            })
            .collect()
    }
}
