//! The minification prefilter of pyramidal displacement mapping: where a pixel covers many
//! patches, the traversal stops at pyramid nodes the pixel's footprint covers and intersects a
//! prefiltered surface there instead of the finest bilinear patches. The VRST 2006 abstract
//! names a "mipmap-like prefilter" at minification that improves quality and speed; its
//! construction is not given, so what follows is our reconstruction.
//!
//! - Footprint: the pixel's ray cone. A pixel spans `2 tan(fov_y / 2) / height` radians, so at
//!   ray parameter t it covers `t` times that (world units), `footprint(t)` patches. The rule
//!   takes it where the ray enters the box (the smallest footprint along the ray's segment in
//!   the box, so it never blurs more than the pixel covers), constant for the pixel.
//! - Stop level: the coarsest level L (at most the top) whose nodes, `2^L` patches wide, are no
//!   wider than the footprint: `2^L <= footprint(t_in)`; L = 0 (no prefilter) below 2 patches.
//! - Covered nodes: a node of level `1..=L` is covered when it is also no wider than the
//!   footprint on the plane perpendicular to the ray, its height range seen from the side
//!   included: `2^k sin(e) + (max - min) cos(e) <= footprint` (patches; e the ray's elevation,
//!   max and min the node's highest and lowest point, from the max and min pyramids of the
//!   patch bounds). Each patch is met on its coarsest covered node, or on itself where none
//!   is. Without the height term the rule put the prefiltered surface where the rays do not
//!   meet anything: over thin tall walls the mean surface lies far under the walls' tops, and a
//!   ray that would meet a wall's side or top goes on several patches to that low surface (at
//!   35 degrees a height error of half the depth moves the hit about 5 patches). That, not the
//!   shading, is what made prefiltered frames worse than unfiltered ones on the generated map:
//!   shading the exact hits with the same facet weights was better than the unfiltered frame at
//!   every view of the report's sweep. Where neighbouring patches are met at different levels
//!   the field steps; a ray meets the step as the higher side's surface.
//! - Prefiltered surface at level L: each node of level L carries one bilinear patch spanning
//!   it. Its corner at grid point `(X, Y) = (c_x 2^L, c_y 2^L)` is the average of the four
//!   level-L nodes of the mean pyramid of the height samples that touch it (nodes `c - 1` and
//!   `c` on each axis, clamped to the nodes that cover samples): the mean of the samples in a
//!   box of `2^(L+1)` samples a side about the corner. Each corner is then clamped to the
//!   node's bound (the max pyramid), so the patch lies under its node's bound and the
//!   traversal's skips stay safe for it.
//! - Shading: every hit of a pixel whose stop level is above 0 (on a prefiltered patch or a
//!   finest one) is shaded at the stop level with the mean shading of the facets about the hit
//!   that face the eye, each weighted by its area projected toward the eye
//!   ([`super::visible_shading`], a pyramid drawn for each view), with the same checkerboard
//!   and light as unfiltered hits. The prefiltered surface's own normal would be wrong: it is
//!   the normal of a smoothed surface, nearly flat where the map is rough, and shades every
//!   rough region as brightly as a plane. A view-independent mean of the unit normals was too:
//!   it weights the facets the pixel does not see.
//!
//! [`Prefilter`] is the CPU reference of the same rule, in f64: the level per pixel, the covered
//! node per patch and an exact tracer of the field they make; [`super::compare`] judges prefiltered GPU frames
//! against it pixel by pixel. [`image_error`] measures quality against the average of many
//! unfiltered rays per pixel (the GPU tracer's supersampled frame, or [`cpu_supersampled`]).

use super::bounds::cpu_bound_pyramid;
use super::camera::Camera;
use super::exact::{self, box_interval, walk, Cells, Hit};
use super::patch::Corners;
use super::shading;
use super::surface::Surface;
use super::visible_shading::{cpu_shading_levels, ShadingLevel};
use crate::gl::{Context, GlError};
use crate::lecture3::pyramid::{cpu_pyramid, Extreme, Level, PyramidBuilder};
use crate::lecture3::pyramid_atlas::{AtlasBuilder, PyramidAtlas};
use crate::lecture3::HeightMap;
use glam::DVec3;

/// A pixel's footprint, in patches, per unit of ray parameter, as the shader's `u_footprint`
/// gets it (f32): the pixel's angle times grid units per world unit (texels are square).
pub fn footprint_per_unit(camera: &Camera, surface: &Surface) -> f32 {
    2.0 * (0.5 * camera.fov_y).tan() / camera.height as f32 * surface.world_to_grid().x
}

/// Whether some pixel of `camera` may stop above level 0: a ray enters the box at a point of
/// the box, so no farther than the box's farthest corner, and its footprint there is under 2
/// patches when that corner's is (with a margin of 1% over fp32 rounding).
pub fn may_act(camera: &Camera, surface: &Surface) -> bool {
    1.01 * farthest_corner(camera, surface) * footprint_per_unit(camera, surface) as f64 >= 2.0
}

/// The deepest stop level a pixel of `camera` may have (at most `top`): that of the footprint
/// at the box's farthest corner, with the same 1% margin as [`may_act`].
pub fn deepest_stop_level(camera: &Camera, surface: &Surface, top: u32) -> u32 {
    let footprint = farthest_corner(camera, surface) * footprint_per_unit(camera, surface) as f64;
    stop_level(1.01 * footprint, top)
}

/// The distance from `camera`'s eye to the box's farthest corner (world).
fn farthest_corner(camera: &Camera, surface: &Surface) -> f64 {
    let eye = camera.eye.as_dvec3();
    let size = surface.size.as_dvec3();
    (0..8)
        .map(|k| {
            let corner = DVec3::new(
                size.x * (k & 1) as f64,
                size.y * (k >> 1 & 1) as f64,
                size.z * (k >> 2) as f64,
            );
            (corner - eye).length()
        })
        .fold(0.0, f64::max)
}

/// The stop level for a footprint of `footprint` patches: the largest L <= `top` with
/// `2^L <= footprint`.
pub fn stop_level(footprint: f64, top: u32) -> u32 {
    (1..=top)
        .take_while(|&k| (1u64 << k) as f64 <= footprint)
        .last()
        .unwrap_or(0)
}

/// Whether fp32 rounding of the footprint could change the stop level (the footprint within a
/// relative 1e-4 of a power of two): such pixels are not judged.
pub fn level_is_borderline(footprint: f64, top: u32) -> bool {
    (1..=top).any(|k| ((1u64 << k) as f64 / footprint - 1.0).abs() < 1e-4)
}

/// The prefiltered height field of one level on the CPU: one bilinear patch per node.
#[derive(Clone, Debug)]
pub struct LevelField {
    pub level: u32,
    /// Nodes along x and y (those covering patches).
    pub nodes: (u32, u32),
    /// The map's patches along x and y (nodes on the far edges are cut there).
    patches: (u32, u32),
    /// Corner heights per node, row by row from the bottom.
    corners: Vec<Corners>,
    /// The level's shading toward the eye (the prefiltered shading).
    shading: ShadingLevel,
}

impl LevelField {
    /// Node width in patches.
    pub fn side(&self) -> f64 {
        (1u64 << self.level) as f64
    }

    /// Corners of node (i, j), raised by `offset`.
    pub fn corners(&self, i: u32, j: u32, offset: f64) -> Corners {
        self.corners[(j * self.nodes.0 + i) as usize].map(|h| h + offset)
    }

    /// The exact first hit of the ray from `eye` along unit `dir` (world) with this field
    /// raised by `offset`: a walk over the level's nodes in order, each node's quadratic solved
    /// ([`super::exact::trace`] over nodes instead of patches).
    pub fn trace(&self, surface: &Surface, eye: DVec3, dir: DVec3, offset: f64) -> Option<Hit> {
        let scale = surface.world_to_grid().as_dvec3();
        let cells = Cells {
            side: self.side(),
            count: self.nodes,
            patches: self.patches,
        };
        walk(&cells, eye * scale, dir * scale, |i, j| {
            self.corners(i, j, offset)
        })
    }

    /// The normal a hit at grid `g` is shaded with: the level's effective normal there
    /// ([`ShadingLevel::effective_normal`]).
    pub fn normal(&self, g: DVec3) -> DVec3 {
        self.shading.effective_normal(g)
    }

    /// The normals a hit at grid `g` may show: the interpolated normal there (it is continuous,
    /// so fp32 rounding of `g` moves it by no more than the tolerance).
    pub fn surface_normals(&self, g: DVec3) -> Vec<DVec3> {
        vec![self.normal(g)]
    }
}

/// The CPU reference of the prefilter for one view: the footprint rule, every level's
/// prefiltered field and the height range of every node (the max and min pyramids of the patch
/// bounds).
#[derive(Clone, Debug)]
pub struct Prefilter {
    /// `footprint_per_unit` of the view.
    pub footprint: f32,
    /// The bound pyramid's top level.
    pub top: u32,
    /// Level L's prefiltered field at index L (index 0 is the map's own field).
    pub levels: Vec<LevelField>,
    /// The highest and lowest point of each node's patches.
    maxes: Vec<Level>,
    mins: Vec<Level>,
    /// Patches per unit of grid height (`Lz` in patch widths): a height range seen from the
    /// side, in patches.
    relief: f64,
}

/// One pixel's ray traced by the rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Traced {
    /// The stop level of the pixel's footprint: the level its hit is shaded at.
    pub level: u32,
    /// Where the ray meets the cut field.
    pub hit: Option<Hit>,
    /// Some node's fit to the footprint on the ray's way is within fp32 rounding of either
    /// answer.
    pub borderline: bool,
}

/// How wide a node `side` patches wide whose points span `relief` patches of height looks
/// across a ray whose direction makes an angle with sine `sin` with the map's plane: its
/// width foreshortened plus its height range seen from the side (along the view, on the plane
/// perpendicular to the ray; across the view it is `side` wide).
pub fn projected_extent(side: f64, relief: f64, sin: f64) -> f64 {
    let cos = (1.0 - sin * sin).max(0.0).sqrt();
    side * sin + relief * cos
}

impl Prefilter {
    /// The rule for `camera` on `surface`.
    pub fn new(surface: &Surface, camera: &Camera) -> Prefilter {
        let levels = level_fields(surface, camera.eye.as_dvec3());
        let scale = surface.world_to_grid().as_dvec3();
        Prefilter {
            footprint: footprint_per_unit(camera, surface),
            top: levels.len() as u32 - 1,
            levels,
            maxes: cpu_bound_pyramid(&surface.map, Extreme::Max),
            mins: cpu_bound_pyramid(&surface.map, Extreme::Min),
            relief: scale.x / scale.z,
        }
    }

    /// How wide node (n, m) of `level` looks across a ray of elevation sine `sin`, in patches
    /// ([`projected_extent`]).
    pub fn node_extent(&self, level: u32, (n, m): (u32, u32), sin: f64) -> f64 {
        let range = self.maxes[level as usize].at(n, m) - self.mins[level as usize].at(n, m);
        projected_extent((1u64 << level) as f64, range as f64 * self.relief, sin)
    }

    /// The level patch (i, j) is met at by a ray of elevation sine `sin` and a footprint of
    /// `footprint` patches: the coarsest node over the patch that the footprint covers (no
    /// wider than it, and no wider across the ray, [`Prefilter::node_extent`]), 0 if none;
    /// and whether fp32 rounding could change that answer.
    pub fn cut_level(&self, (i, j): (u32, u32), sin: f64, footprint: f64) -> (u32, bool) {
        let stop = stop_level(footprint, self.top);
        let fits = |level: u32| self.node_extent(level, (i >> level, j >> level), sin) / footprint;
        let borderline = (1..=stop).any(|level| (fits(level) - 1.0).abs() < 1e-4);
        // A node's extent is at most its parent's: the covered levels are 0..=cut.
        let cut = (1..=stop)
            .take_while(|&l| fits(l) <= 1.0)
            .last()
            .unwrap_or(0);
        (cut, borderline)
    }

    /// The ray from `eye` along unit `dir` (world), entering the box at `t_in`, through the
    /// field the rule makes for it, raised by `offset`: each patch the ray crosses is met on
    /// the prefiltered patch of its cut node ([`Prefilter::cut_level`]; the part of it over
    /// that patch), or on itself where no node over it is covered. Where neighbouring cut
    /// nodes differ in level the field may step; a ray meets such a step as a wall of the
    /// higher side.
    pub fn trace_ray(
        &self,
        surface: &Surface,
        eye: DVec3,
        dir: DVec3,
        t_in: f64,
        offset: f64,
    ) -> Traced {
        let footprint = self.footprint_at(t_in);
        let level = stop_level(footprint, self.top);
        let borderline = std::cell::Cell::new(level_is_borderline(footprint, self.top));
        let scale = surface.world_to_grid().as_dvec3();
        let patches = surface.patches();
        let cells = Cells {
            side: 1.0,
            count: patches,
            patches,
        };
        let sin = dir.z.abs();
        let hit = walk(&cells, eye * scale, dir * scale, |i, j| {
            let (cut, near) = self.cut_level((i, j), sin, footprint);
            borderline.set(borderline.get() || near);
            if cut == 0 {
                return surface.corners(i, j, offset);
            }
            let field = &self.levels[cut as usize];
            let (n, m) = (i >> cut, j >> cut);
            let h = field.corners(n, m, offset);
            let at = |x: u32, y: u32| {
                let side = field.side();
                let s = (x - (n << cut)) as f64 / side;
                let t = (y - (m << cut)) as f64 / side;
                super::patch::height(h, s, t)
            };
            [at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)]
        });
        Traced {
            level,
            hit,
            borderline: borderline.get(),
        }
    }

    /// The footprint (patches) of a ray entering the box at parameter `t_in`.
    pub fn footprint_at(&self, t_in: f64) -> f64 {
        t_in * self.footprint as f64
    }

    /// Pixel (px, py) of `camera` traced by the rule: its stop level and its hit
    /// ([`Prefilter::trace_ray`]).
    pub fn trace_pixel(
        &self,
        surface: &Surface,
        camera: &Camera,
        px: u32,
        py: u32,
    ) -> Option<(u32, Hit)> {
        let eye = camera.eye.as_dvec3();
        let scale = surface.world_to_grid().as_dvec3();
        let (wp, hp) = surface.patches();
        let dir = camera.pixel_direction(px, py);
        let (t_in, _) = box_interval(eye * scale, dir * scale, wp as f64, hp as f64)?;
        let traced = self.trace_ray(surface, eye, dir, t_in, 0.0);
        Some((traced.level, traced.hit?))
    }
}

/// Every pixel of `camera`'s image traced by the rule, row by row from the bottom.
pub fn trace_image(surface: &Surface, camera: &Camera) -> Vec<Option<Hit>> {
    let rule = Prefilter::new(surface, camera);
    pixels(camera)
        .map(|(px, py)| Some(rule.trace_pixel(surface, camera, px, py)?.1))
        .collect()
}

/// The pixels of `camera`'s image, row by row from the bottom.
fn pixels(camera: &Camera) -> impl Iterator<Item = (u32, u32)> + '_ {
    (0..camera.height).flat_map(|py| (0..camera.width).map(move |px| (px, py)))
}

/// Every level's prefiltered field, from the CPU bound pyramid, the CPU mean pyramid of the
/// height samples and the CPU shading pyramid toward `eye` (world; level 0: the map's own
/// patches).
pub fn level_fields(surface: &Surface, eye: DVec3) -> Vec<LevelField> {
    let map = &surface.map;
    let bounds = cpu_bound_pyramid(map, Extreme::Max);
    let means = cpu_pyramid(map.width(), map.height(), map.heights(), Extreme::Mean);
    let patches = map.patches();
    // Both pyramids span the patches: one shading level per bound level.
    cpu_shading_levels(surface, eye)
        .into_iter()
        .map(|shading| {
            let level = shading.level;
            let side = 1u32 << level;
            let nodes = (patches.0.div_ceil(side), patches.1.div_ceil(side));
            // Mean nodes that cover samples at this level.
            let valid = (map.width().div_ceil(side), map.height().div_ceil(side));
            let mean = |x: i64, y: i64| {
                let x = x.clamp(0, valid.0 as i64 - 1) as u32;
                let y = y.clamp(0, valid.1 as i64 - 1) as u32;
                means[level as usize].at(x, y) as f64
            };
            let corner = |cx: u32, cy: u32| {
                if level == 0 {
                    return map.at(cx, cy) as f64;
                }
                let (x, y) = (cx as i64, cy as i64);
                0.25 * ((mean(x - 1, y - 1) + mean(x, y - 1)) + (mean(x - 1, y) + mean(x, y)))
            };
            let corners = (0..nodes.1)
                .flat_map(|j| (0..nodes.0).map(move |i| (i, j)))
                .map(|(i, j)| {
                    let bound = bounds[level as usize].at(i, j) as f64;
                    [
                        corner(i, j),
                        corner(i + 1, j),
                        corner(i, j + 1),
                        corner(i + 1, j + 1),
                    ]
                    .map(|h| h.min(bound))
                })
                .collect();
            LevelField {
                level,
                nodes,
                patches,
                corners,
                shading,
            }
        })
        .collect()
}

/// The mean pyramid of the height samples as the traversal reads it (one atlas).
pub fn mean_atlas(ctx: &Context, map: &HeightMap) -> Result<PyramidAtlas, GlError> {
    let means = PyramidBuilder::new(ctx)?.from_image(
        map.width(),
        map.height(),
        map.heights(),
        Extreme::Mean,
    )?;
    AtlasBuilder::new(ctx)?.atlas(&means.texture)
}

/// An image's pixels as RGB in [0, 1] and whether anything is shown there; rows from the
/// bottom.
pub type Shown = Vec<Option<[f64; 3]>>;

/// An RGBA8 frame as [`Shown`] (alpha 0: nothing shown).
pub fn shown_of_rgba8(colour: &[u8]) -> Shown {
    colour
        .chunks_exact(4)
        .map(|c| (c[3] > 0).then(|| [0, 1, 2].map(|k| c[k] as f64 / 255.0)))
        .collect()
}

/// The mean of the `samples x samples` sub-pixels of a `samples`-times larger image, per
/// pixel (where no sub-pixel shows anything the pixel shows nothing; otherwise those that
/// show nothing count as black).
pub(super) fn box_filter(big: &Shown, width: u32, height: u32, samples: u32) -> Shown {
    let (w, s) = (width as usize, samples as usize);
    let mut sum = vec![None::<[f64; 3]>; w * height as usize];
    for (i, px) in big.iter().enumerate() {
        let (x, y) = (i % (w * s) / s, i / (w * s) / s);
        if let Some(c) = px {
            let acc = sum[y * w + x].get_or_insert([0.0; 3]);
            for k in 0..3 {
                acc[k] += c[k] / (s * s) as f64;
            }
        }
    }
    sum
}

/// What a CPU-traced hit shows: the wall's or `surface_normal`'s shading of the
/// checkerboard there.
fn hit_colour(surface: &Surface, hit: &Hit, surface_normal: DVec3) -> [f64; 3] {
    let normal = if hit.wall {
        shading::wall_normal(surface, hit.grid)
    } else {
        surface_normal
    };
    shading::shade(shading::albedo(hit.grid), normal)
}

/// The CPU reference of the GPU tracer's supersampled image: every sub-pixel ray traced
/// exactly (f64) and shaded as the shader shades it, then averaged the same way.
pub fn cpu_supersampled(surface: &Surface, camera: &Camera, samples: u32) -> Shown {
    let big = camera.enlarged(samples);
    let shown = exact::trace_image(surface, &big, 0.0)
        .iter()
        .map(|hit| hit.map(|h| hit_colour(surface, &h, shading::field_normal(surface, h.grid))))
        .collect();
    box_filter(&shown, camera.width, camera.height, samples)
}

/// The CPU reference of a prefiltered frame's colours: each pixel traced by the rule and shaded
/// with its stop level's normal (the map's own at level 0).
pub fn cpu_prefiltered(surface: &Surface, camera: &Camera) -> Shown {
    let rule = Prefilter::new(surface, camera);
    pixels(camera)
        .map(|(px, py)| {
            let (level, hit) = rule.trace_pixel(surface, camera, px, py)?;
            let normal = match level {
                0 => shading::field_normal(surface, hit.grid),
                _ => rule.levels[level as usize].normal(hit.grid),
            };
            Some(hit_colour(surface, &hit, normal))
        })
        .collect()
}

/// The root mean square difference (RGB in [0, 1]) between an image and the supersampled
/// reference, over the pixels where either shows something (nothing counts as black).
pub fn image_error(shown: &Shown, reference: &Shown) -> f64 {
    let (sum, count) = shown
        .iter()
        .zip(reference)
        .filter(|(c, r)| c.is_some() || r.is_some())
        .fold((0.0, 0usize), |(sum, n), (c, r)| {
            let (c, r) = (c.unwrap_or([0.0; 3]), r.unwrap_or([0.0; 3]));
            let d: f64 = (0..3).map(|k| (c[k] - r[k]).powi(2)).sum();
            (sum + d / 3.0, n + 1)
        });
    if count == 0 {
        0.0
    } else {
        (sum / count as f64).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stop_level_is_the_coarsest_node_no_wider_than_the_footprint() {
        assert_eq!(stop_level(0.3, 5), 0);
        assert_eq!(stop_level(1.99, 5), 0);
        assert_eq!(stop_level(2.0, 5), 1);
        assert_eq!(stop_level(7.9, 5), 2);
        assert_eq!(stop_level(1e6, 5), 5);
        assert!(level_is_borderline(4.0001, 5));
        assert!(!level_is_borderline(5.0, 5));
    }

    #[test]
    fn a_node_with_a_tall_wall_is_covered_only_where_its_height_range_fits_the_footprint() {
        // A flat 9x9 map with one wall one sample wide along x = 4, as tall as the box is
        // wide (patches are 0.25 wide, the wall 1 high: 4 patches of relief).
        let heights = (0..81)
            .map(|i| if i % 9 == 4 { 1.0 } else { 0.0 })
            .collect();
        let map = HeightMap::new("wall", 9, 9, heights).unwrap();
        let surface = Surface::new(map, 1.0).unwrap();
        let camera = Camera::orbit(surface.centre(), 20.0, 225.0, 35.0, 16, 16);
        let rule = Prefilter::new(&surface, &camera);
        let sin = 35f64.to_radians().sin();
        // A footprint of 2.5 patches: level 1's nodes (2 patches) are no wider than it.
        assert_eq!(stop_level(2.5, rule.top), 1);
        // A flat node fits: 2 sin(35) = 1.15 patches along the view.
        assert!((rule.node_extent(1, (0, 0), sin) - 2.0 * sin).abs() < 1e-12);
        assert_eq!(rule.cut_level((0, 0), sin, 2.5), (1, false));
        // The wall's node does not: its 4 patches of relief seen from the side add 3.3.
        let wall = rule.node_extent(1, (2, 2), sin);
        assert!((wall - (2.0 * sin + 4.0 * 35f64.to_radians().cos())).abs() < 1e-9);
        assert_eq!(rule.cut_level((4, 4), sin, 2.5), (0, false));
        assert_eq!(rule.cut_level((3, 4), sin, 2.5), (0, false));
        // Seen from straight above the relief is not seen, and the wall's node fits too.
        assert_eq!(rule.cut_level((4, 4), 1.0, 2.5), (1, false));
        // A footprint at the edge of fp32 rounding of the wall node's fit is flagged.
        assert_eq!(rule.cut_level((4, 4), sin, wall * (1.0 + 1e-6)), (1, true));
        assert_eq!(rule.cut_level((4, 4), sin, wall * 1.01), (1, false));
    }

    #[test]
    fn level_zero_is_the_map_and_coarse_patches_stay_under_their_bounds() {
        let heights = (0..17 * 11)
            .map(|i| ((i * 7919) % 101) as f32 / 100.0)
            .collect();
        let map = HeightMap::new("test", 17, 11, heights).unwrap();
        let surface = Surface::new(map.clone(), 0.4).unwrap();
        let levels = level_fields(&surface, DVec3::new(1.0, 0.7, 3.0));
        let bounds = cpu_bound_pyramid(&map, Extreme::Max);
        assert_eq!(levels[0].corners(3, 4, 0.0), surface.corners(3, 4, 0.0));
        for (field, bound) in levels.iter().zip(&bounds) {
            for j in 0..field.nodes.1 {
                for i in 0..field.nodes.0 {
                    let b = bound.at(i, j) as f64;
                    assert!(field.corners(i, j, 0.0).iter().all(|&h| h <= b));
                }
            }
        }
        // Level 0's tracer is the exact tracer.
        let eye = DVec3::new(-1.0, -0.7, 1.3);
        for k in 0..40 {
            let target = DVec3::new(0.05 * k as f64, 0.6, 0.1);
            let dir = (target - eye).normalize();
            assert_eq!(
                levels[0].trace(&surface, eye, dir, 0.0),
                super::super::exact::trace(&surface, eye, dir, 0.0)
            );
        }
    }
}
