//! The normal pyramid the minification prefilter shades with (our reconstruction, as the rest
//! of the prefilter: [`super::prefilter`]).
//!
//! A pixel far away covers many patches; what it should show is the mean of their shadings.
//! The shading (`shading::shade`) is linear in the normal wherever the surface faces the
//! light, so the mean of the shadings is the shading of the mean of the unit normals, kept at
//! its length (shorter than 1 where the normals spread, as Toksvig's mipmapped normals are):
//! a rough patch far away is darker than its mean surface's own normal would make it. Mean
//! normals rather than mean shaded colours keep the pyramid independent of the light.
//!
//! - Level 0: for each patch, the mean of its bilinear field's unit normals, by the midpoint
//!   rule on its four quarters (`(s, t)` in {1/4, 3/4}).
//! - Level L: node (i, j) the mean of the level-0 means of the patches it covers (the mean
//!   pyramid, [`crate::lecture3::pyramid`], on all three components at once).
//! - At a hit on level L's prefiltered surface: the level's means interpolated bilinearly
//!   between node centres (node n's at `(n + 1/2) 2^L` patches), constant beyond the outer
//!   centres; not normalised.
//!
//! [`cpu_normal_levels`] is the CPU reference (f64); [`NormalPyramidBuilder`] draws level 0
//! by one pass (`glsl/lecture3/patch_normals.frag`) and the levels above by the mean pyramid's
//! passes, into one RGBA32F atlas the traversal reads.

use super::shading::patch_normal;
use super::surface::Surface;
use crate::gl::{Context, GlError, Program, Texture, TextureFormat};
use crate::lecture3::pyramid::{Extreme, PyramidBuilder};
use crate::lecture3::pyramid_atlas::{AtlasBuilder, PyramidAtlas};
use crate::shader;
use glam::{DVec3, IVec2};

/// Where level 0 samples each patch's unit normal (local s or t).
const QUARTER_CENTRES: [f64; 2] = [0.25, 0.75];

/// The mean unit normal (world) of patch (i, j) of `surface`.
pub fn patch_mean_normal(surface: &Surface, i: u32, j: u32) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for t in QUARTER_CENTRES {
        for s in QUARTER_CENTRES {
            sum += patch_normal(surface, (i, j), (s, t));
        }
    }
    0.25 * sum
}

/// One level of mean normals: the nodes that cover patches, row by row from the bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalLevel {
    pub level: u32,
    /// Nodes along x and y.
    pub nodes: (u32, u32),
    pub normals: Vec<DVec3>,
}

impl NormalLevel {
    /// Node (i, j), clamped to the level's nodes.
    pub fn at(&self, i: i64, j: i64) -> DVec3 {
        let i = i.clamp(0, self.nodes.0 as i64 - 1) as u32;
        let j = j.clamp(0, self.nodes.1 as i64 - 1) as u32;
        self.normals[(j * self.nodes.0 + i) as usize]
    }

    /// The prefiltered normal at grid point `g`: bilinear between node centres.
    pub fn interpolate(&self, g: DVec3) -> DVec3 {
        let side = (1u64 << self.level) as f64;
        let (px, py) = (g.x / side - 0.5, g.y / side - 0.5);
        let (i, j) = (px.floor(), py.floor());
        let (fx, fy) = (px - i, py - j);
        let (i, j) = (i as i64, j as i64);
        let bottom = self.at(i, j).lerp(self.at(i + 1, j), fx);
        let top = self.at(i, j + 1).lerp(self.at(i + 1, j + 1), fx);
        bottom.lerp(top, fy)
    }
}

/// Every level of the normal pyramid on the CPU (f64): level L's node (i, j) is the mean of
/// the patch means over the patches `[i 2^L, (i + 1) 2^L) x [j 2^L, (j + 1) 2^L)` (cut at the
/// map's edge), up to the level of one node.
pub fn cpu_normal_levels(surface: &Surface) -> Vec<NormalLevel> {
    let (wp, hp) = surface.patches();
    let patches: Vec<DVec3> = (0..hp)
        .flat_map(|j| (0..wp).map(move |i| (i, j)))
        .map(|(i, j)| patch_mean_normal(surface, i, j))
        .collect();
    let levels = crate::lecture3::pyramid::level_count(wp, hp);
    (0..levels)
        .map(|level| {
            let side = 1u32 << level;
            let nodes = (wp.div_ceil(side), hp.div_ceil(side));
            let normals = (0..nodes.1)
                .flat_map(|j| (0..nodes.0).map(move |i| (i, j)))
                .map(|(i, j)| {
                    let xs = i * side..((i + 1) * side).min(wp);
                    let ys = j * side..((j + 1) * side).min(hp);
                    let count = (xs.len() * ys.len()) as f64;
                    let sum: DVec3 = ys
                        .flat_map(|y| xs.clone().map(move |x| (x, y)))
                        .map(|(x, y)| patches[(y * wp + x) as usize])
                        .sum();
                    sum / count
                })
                .collect();
            NormalLevel {
                level,
                nodes,
                normals,
            }
        })
        .collect()
}

/// Draws normal pyramids on the GPU.
pub struct NormalPyramidBuilder {
    pyramids: PyramidBuilder,
    atlases: AtlasBuilder,
    normals_program: Program,
}

impl NormalPyramidBuilder {
    pub fn new(ctx: &Context) -> Result<NormalPyramidBuilder, GlError> {
        Ok(NormalPyramidBuilder {
            pyramids: PyramidBuilder::new(ctx)?,
            atlases: AtlasBuilder::new(ctx)?,
            normals_program: Program::rect(
                ctx,
                &[
                    shader!("glsl/lecture3/displace_normal.glsl"),
                    shader!("glsl/lecture3/patch_normals.frag"),
                ],
            )?,
        })
    }

    /// The normal pyramid of `surface` (its height texture `heights`) as one atlas, laid out
    /// as the bound pyramid's (both span the patches): level 0 by one pass, the levels above
    /// by the mean pyramid's passes.
    pub fn build(&self, surface: &Surface, heights: &Texture) -> Result<PyramidAtlas, GlError> {
        let (wp, hp) = surface.patches();
        let pyramid = self
            .pyramids
            .allocate_as(wp, hp, Extreme::Mean, TextureFormat::Rgba32F)?;
        pyramid
            .target(0)
            .pass(&self.normals_program, "mean unit normal per patch")?
            .texture("u_heights", heights)
            .uniform("u_patches", IVec2::new(wp as i32, hp as i32))
            .uniform("u_world_to_grid", surface.world_to_grid())
            .draw_full()?;
        self.pyramids.build_levels(&pyramid)?;
        self.atlases.atlas(&pyramid.texture)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lecture3::HeightMap;

    #[test]
    fn a_plane_keeps_its_unit_normal_and_a_ridge_shortens_it() {
        // A ramp along x (steps of 1/4, exact in f32): every patch the same unit normal, at
        // every level.
        let ramp = HeightMap::new(
            "ramp",
            5,
            3,
            (0..15).map(|k| (k % 5) as f32 * 0.25).collect(),
        )
        .unwrap();
        let surface = Surface::new(ramp, 0.5).unwrap();
        let n = patch_normal(&surface, (0, 0), (0.5, 0.5));
        for level in cpu_normal_levels(&surface) {
            for m in &level.normals {
                assert!((*m - n).length() < 1e-12, "{level:?}");
            }
        }
        // A ridge: up one patch, down the next; the mean of the pair points up and is short.
        let ridge = HeightMap::new("ridge", 3, 2, vec![0.0, 1.0, 0.0, 0.0, 1.0, 0.0]).unwrap();
        let surface = Surface::new(ridge, 0.5).unwrap();
        let levels = cpu_normal_levels(&surface);
        let top = levels.last().unwrap().normals[0];
        let one = patch_mean_normal(&surface, 0, 0);
        assert!(top.x.abs() < 1e-12 && top.y.abs() < 1e-12);
        assert!((top.z - one.z).abs() < 1e-12 && top.length() < 0.9);
        // Interpolation: at a node centre the node's value, beyond the outer centres constant.
        let level0 = &levels[0];
        let at_centre = level0.interpolate(DVec3::new(0.5, 0.5, 0.0));
        assert!((at_centre - level0.normals[0]).length() < 1e-12);
        let beyond = level0.interpolate(DVec3::new(-3.0, 0.5, 0.0));
        assert!((beyond - level0.normals[0]).length() < 1e-12);
        let middle = level0.interpolate(DVec3::new(1.0, 0.5, 0.0));
        assert!((middle - top).length() < 1e-12);
    }
}
