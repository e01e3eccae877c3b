//! The shading pyramid the minification prefilter shades with, rebuilt for each view (our
//! reconstruction, as the rest of the prefilter: [`super::prefilter`]).
//!
//! A pixel far away covers many patches; what it should show is the mean of the shadings of
//! the facets it sees, each weighted by the area it covers in the pixel: the facet's area
//! projected toward the eye, `max(n . v, 0) dA` for a unit normal `n`, view direction `v` and
//! surface area `dA`. Over the map's grid (equal areas `dA_xy = n_z dA` in the plane) the
//! weight is `max(g . v, 0) dA_xy` with `g = n / n_z`, the unnormalised normal `(-dz/dx,
//! -dz/dy, 1)`. A view-independent mean of the unit normals weights every facet alike, the
//! ones facing away included; seen at 35 degrees that made the prefiltered frames further
//! from the supersampled image than the unfiltered ones.
//!
//! - Level 0: for each patch, at the centres of its four quarters (`(s, t)` in {1/4, 3/4},
//!   the midpoint rule), the weight `w = max(g . v, 0)` with `v` the unit direction from that
//!   point of the patch to the eye, and the weighted lit cosine `w max(n . l, 0)` (`l` the
//!   light); their means are the node's value `(W, S)`.
//! - Level L: node (i, j) the mean of the level-0 values of the patches it covers (the mean
//!   pyramid, [`crate::lecture3::pyramid`]).
//! - At a hit on level L's prefiltered surface: `(W, S)` interpolated bilinearly between node
//!   centres (node n's at `(n + 1/2) 2^L` patches), constant beyond the outer centres; the
//!   visible facets' mean lit cosine is `S / W` (0 where no facet faces the eye). The pixel is
//!   shaded with the effective normal `(S / W) l`, whose shading is that mean.
//!
//! Facets hidden behind others (self-occlusion) still count: only their orientation is
//! weighted, not their visibility. Measured, that is not what limits the prefilter: on the
//! generated map (thin walls one sample wide), with each pixel's exact hit shaded this way, the
//! error against 4x4 rays per pixel was below the unfiltered frame's at every view of the
//! report's sweep (128x128 frames, 35 degrees, distance 12.8: 0.074 against 0.084, CPU
//! reference); the prefiltered surface's place was ([`super::prefilter`]).
//!
//! Storing moments instead (the mean of `n g^T`, six values, and of `g`, two, per node, so
//! that `l^T mean(n g^T) v / (mean(g) . v)` gives the same mean view-independently) drops both
//! clamps; where a node's facets face away from the eye or the light that ratio left [0, 1]
//! (errors above 1 against the supersampled image at 15 and 35 degrees), so the pyramid is
//! drawn per view instead.
//!
//! [`cpu_shading_levels`] is the CPU reference (f64); [`VisibleShadingPyramid`] draws each level
//! a view reads (1 up to the deepest stop level of its pixels) by one pass straight from the
//! height map into its place in one RGBA32F atlas the traversal reads
//! (`glsl/lecture3/node_visible_shading.frag`: each node sums its patches' facets). Drawing
//! level 0 and the mean pyramid's passes above it, then copying every level into the atlas,
//! took about 14 passes for the report's map, whatever the view; this takes one per level read
//! (2 at the report's far views), each doing as much arithmetic as the level-0 pass.

use super::shading::{light, patch_normal};
use super::surface::Surface;
use crate::gl::{Context, Framebuffer, GlError, Program, Rect, Texture, TextureFormat};
use crate::lecture3::pyramid::{Extreme, PyramidBuilder};
use crate::lecture3::pyramid_atlas::{AtlasBuilder, PyramidAtlas};
use crate::shader;
use glam::{DVec2, DVec3, IVec2, Vec3};

/// Where level 0 samples each patch (local s or t).
const QUARTER_CENTRES: [f64; 2] = [0.25, 0.75];

/// The world point of patch (i, j) of `surface` at local `(s, t)`, on its bilinear field.
fn patch_point(surface: &Surface, (i, j): (u32, u32), (s, t): (f64, f64)) -> DVec3 {
    let h = surface.corners(i, j, 0.0);
    let z =
        h[0] * (1.0 - s) * (1.0 - t) + h[1] * s * (1.0 - t) + h[2] * (1.0 - s) * t + h[3] * s * t;
    surface.grid_to_world(DVec3::new(i as f64 + s, j as f64 + t, z))
}

/// Patch (i, j)'s mean projected-area weight toward `eye` (world) and its mean weighted lit
/// cosine, `(W, S)`.
pub fn patch_visible_shading(surface: &Surface, i: u32, j: u32, eye: DVec3) -> DVec2 {
    let mut sum = DVec2::ZERO;
    for t in QUARTER_CENTRES {
        for s in QUARTER_CENTRES {
            let n = patch_normal(surface, (i, j), (s, t));
            let v = (eye - patch_point(surface, (i, j), (s, t))).normalize();
            let w = (n / n.z).dot(v).max(0.0);
            sum += DVec2::new(w, w * n.dot(light()).max(0.0));
        }
    }
    0.25 * sum
}

/// The visible facets' mean lit cosine from a node value `(W, S)`: `S / W`, 0 where no facet
/// faces the eye.
pub fn mean_lit_cosine(value: DVec2) -> f64 {
    if value.x > 0.0 {
        value.y / value.x
    } else {
        0.0
    }
}

/// One level of the shading pyramid: `(W, S)` of the nodes that cover patches, row by row
/// from the bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadingLevel {
    pub level: u32,
    /// Nodes along x and y.
    pub nodes: (u32, u32),
    pub values: Vec<DVec2>,
}

impl ShadingLevel {
    /// Node (i, j), clamped to the level's nodes.
    pub fn at(&self, i: i64, j: i64) -> DVec2 {
        let i = i.clamp(0, self.nodes.0 as i64 - 1) as u32;
        let j = j.clamp(0, self.nodes.1 as i64 - 1) as u32;
        self.values[(j * self.nodes.0 + i) as usize]
    }

    /// `(W, S)` at grid point `g`: bilinear between node centres.
    pub fn interpolate(&self, g: DVec3) -> DVec2 {
        let side = (1u64 << self.level) as f64;
        let (px, py) = (g.x / side - 0.5, g.y / side - 0.5);
        let (i, j) = (px.floor(), py.floor());
        let (fx, fy) = (px - i, py - j);
        let (i, j) = (i as i64, j as i64);
        let bottom = self.at(i, j).lerp(self.at(i + 1, j), fx);
        let top = self.at(i, j + 1).lerp(self.at(i + 1, j + 1), fx);
        bottom.lerp(top, fy)
    }

    /// The effective normal at grid point `g`: the light's direction scaled by the visible
    /// facets' mean lit cosine there (its shading is their mean shading).
    pub fn effective_normal(&self, g: DVec3) -> DVec3 {
        mean_lit_cosine(self.interpolate(g)) * light()
    }
}

/// Every level of the shading pyramid toward `eye` on the CPU (f64): level L's node (i, j) is
/// the mean of the patch values over the patches `[i 2^L, (i + 1) 2^L) x [j 2^L, (j + 1) 2^L)`
/// (cut at the map's edge), up to the level of one node.
pub fn cpu_shading_levels(surface: &Surface, eye: DVec3) -> Vec<ShadingLevel> {
    let (wp, hp) = surface.patches();
    let patches: Vec<DVec2> = (0..hp)
        .flat_map(|j| (0..wp).map(move |i| (i, j)))
        .map(|(i, j)| patch_visible_shading(surface, i, j, eye))
        .collect();
    let levels = crate::lecture3::pyramid::level_count(wp, hp);
    (0..levels)
        .map(|level| {
            let side = 1u32 << level;
            let nodes = (wp.div_ceil(side), hp.div_ceil(side));
            let values = (0..nodes.1)
                .flat_map(|j| (0..nodes.0).map(move |i| (i, j)))
                .map(|(i, j)| {
                    let xs = i * side..((i + 1) * side).min(wp);
                    let ys = j * side..((j + 1) * side).min(hp);
                    let count = (xs.len() * ys.len()) as f64;
                    let sum: DVec2 = ys
                        .flat_map(|y| xs.clone().map(move |x| (x, y)))
                        .map(|(x, y)| patches[(y * wp + x) as usize])
                        .sum();
                    sum / count
                })
                .collect();
            ShadingLevel {
                level,
                nodes,
                values,
            }
        })
        .collect()
}

/// The shading pyramid of one surface on the GPU, drawn again for each view into the same
/// atlas: each level the view reads by one pass straight from the height map.
pub struct VisibleShadingPyramid {
    program: Program,
    /// Draws into the atlas.
    target: Framebuffer,
    /// What the traversal reads: every level in one image, laid out as the bound pyramid's
    /// (both span the patches).
    pub atlas: PyramidAtlas,
}

impl VisibleShadingPyramid {
    /// The atlas for `surface`'s pyramid (drawn by [`VisibleShadingPyramid::draw`]).
    pub fn new(ctx: &Context, surface: &Surface) -> Result<VisibleShadingPyramid, GlError> {
        let (wp, hp) = surface.patches();
        // The layout: the atlas of a mean pyramid of the patches, as the bound pyramid's.
        let pyramid =
            PyramidBuilder::new(ctx)?.allocate_as(wp, hp, Extreme::Mean, TextureFormat::Rgba32F)?;
        let atlas = AtlasBuilder::new(ctx)?.atlas(&pyramid.texture)?;
        Ok(VisibleShadingPyramid {
            program: Program::rect(
                ctx,
                &[
                    shader!("glsl/lecture3/displace_normal.glsl"),
                    shader!("glsl/lecture3/node_visible_shading.frag"),
                ],
            )?,
            target: Framebuffer::new(ctx, "shading pyramid atlas", &[&atlas.texture], None)?,
            atlas,
        })
    }

    /// Draws levels `1..=top` of the pyramid toward `eye` (world) for `surface` (its height
    /// texture `heights`), one pass each, into the atlas. Level 0 and the levels above `top`
    /// are left as they were: a view reads only the levels of its pixels' footprints.
    pub fn draw(
        &self,
        surface: &Surface,
        heights: &Texture,
        eye: Vec3,
        top: u32,
    ) -> Result<(), GlError> {
        let (wp, hp) = surface.patches();
        for level in 1..=top.min(self.atlas.levels() - 1) {
            let (ox, oy) = self.atlas.offsets[level as usize];
            let (w, h) = self.atlas.sizes[level as usize];
            self.target
                .pass(
                    &self.program,
                    "visible facets' weight and lit cosine per node",
                )?
                .viewport(Rect::new(ox, oy, w, h))
                .texture("u_heights", heights)
                .uniform("u_patches", IVec2::new(wp as i32, hp as i32))
                .uniform("u_world_to_grid", surface.world_to_grid())
                .uniform("u_eye", eye)
                .uniform("u_level", level as i32)
                .uniform("u_offset", IVec2::new(ox as i32, oy as i32))
                .draw_full()?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lecture3::HeightMap;

    #[test]
    fn a_plane_shades_as_itself_and_facets_facing_away_weigh_nothing() {
        // A ramp along x (steps of 1/4, exact in f32): every patch the same normal, so at
        // every level the mean lit cosine is the plane's own.
        let ramp = HeightMap::new(
            "ramp",
            5,
            3,
            (0..15).map(|k| (k % 5) as f32 * 0.25).collect(),
        )
        .unwrap();
        let surface = Surface::new(ramp, 0.5).unwrap();
        let n = patch_normal(&surface, (0, 0), (0.5, 0.5));
        let eye = DVec3::new(-1.0, 0.3, 4.0);
        for level in cpu_shading_levels(&surface, eye) {
            for value in &level.values {
                assert!(value.x > 0.0);
                assert!((mean_lit_cosine(*value) - n.dot(light())).abs() < 1e-12);
            }
        }
        // A ridge: up one patch, down the next. Seen from far along +x only the face that
        // falls toward +x is seen, so the node shades as that face.
        let ridge = HeightMap::new("ridge", 3, 2, vec![0.0, 1.0, 0.0, 0.0, 1.0, 0.0]).unwrap();
        let surface = Surface::new(ridge, 0.5).unwrap();
        let far_x = DVec3::new(1e4, 0.5, 0.3);
        let rising = patch_visible_shading(&surface, 0, 0, far_x);
        let falling = patch_visible_shading(&surface, 1, 0, far_x);
        assert_eq!(rising.x, 0.0);
        assert!(falling.x > 0.0);
        let top = cpu_shading_levels(&surface, far_x).last().unwrap().values[0];
        let face = patch_normal(&surface, (1, 0), (0.5, 0.5));
        assert!((mean_lit_cosine(top) - face.dot(light()).max(0.0)).abs() < 1e-12);
        // Seen from above both faces count, by their projected areas (equal here).
        let above = cpu_shading_levels(&surface, DVec3::new(1.0, 0.5, 1e4));
        let rise = patch_normal(&surface, (0, 0), (0.5, 0.5));
        let both = 0.5 * (rise.dot(light()).max(0.0) + face.dot(light()).max(0.0));
        assert!((mean_lit_cosine(above.last().unwrap().values[0]) - both).abs() < 1e-4);
        // Interpolation: at a node centre the node's value, beyond the outer centres constant.
        let level0 = &above[0];
        let at_centre = level0.interpolate(DVec3::new(0.5, 0.5, 0.0));
        assert!((at_centre - level0.values[0]).length() < 1e-12);
        let beyond = level0.interpolate(DVec3::new(-3.0, 0.5, 0.0));
        assert!((beyond - level0.values[0]).length() < 1e-12);
        // The effective normal's shading is the mean.
        let g = DVec3::new(1.0, 0.5, 0.0);
        let effective = level0.effective_normal(g);
        assert!((effective.dot(light()) - mean_lit_cosine(level0.interpolate(g))).abs() < 1e-12);
    }
}
