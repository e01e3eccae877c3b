//! The 2D generalized Voronoi diagram of points, segments and triangles by rasterization:
//! Hoff, Keyser, Lin, Manocha & Culver, "Fast computation of generalized Voronoi diagrams
//! using graphics hardware", SIGGRAPH 1999 (`lecture1-sources.md`, section 5).
//!
//! What the sources confirm: every site's distance function is rendered over the planar grid
//! as a distance mesh (a polygonal approximation with a bounded error) and the depth test
//! keeps the nearest site, its id in the colour buffer and its distance in the depth buffer.
//! Two methods ([`raster::Method`]):
//! - `mesh`: the distance meshes ([`mesh`]: cones, tents and flat tops, the number of cone
//!   sides chosen from the asked error), `glsl/lecture1/voronoi_mesh.vert` and `.frag`;
//! - `exact` (ours, for OpenGL 3.3): each site draws one rectangle over the whole domain and
//!   every fragment computes its exact distance to the site and writes it to `gl_FragDepth`
//!   (`glsl/lecture1/voronoi_site.vert` and `voronoi_site.frag`).
//!
//! [`reference`](mod@reference) is brute force per pixel in f64.
//!
//! Ties: sites are drawn in id order and the depth test is LESS, so where two sites' depths
//! are equal (the same fp32 value of distance / depth range) the site with the smaller id
//! keeps the pixel; the reference takes the smallest id among exactly equal f64 distances.
//! The two can differ only where the distances agree within [`Diagram::tolerance`].

pub mod mesh;
pub mod raster;
pub mod reference;
pub mod sites;

pub use sites::{Domain, Site, Sites};

/// A diagram: per pixel (rows from the bottom, `n x n`) the nearest site and its distance.
#[derive(Clone, Debug)]
pub struct Diagram {
    pub n: usize,
    pub domain: Domain,
    /// The nearest site's index in the input list.
    pub site: Vec<u32>,
    /// Its distance from the pixel's centre (input units).
    pub distance: Vec<f32>,
    /// The depth values are distance / depth_range (input units).
    pub depth_range: f64,
    /// The distance meshes' tessellation bound (input units; 0 when exact): the distance is
    /// at most this much above the true one.
    pub mesh_error: f64,
    /// How far a mesh distance may fall on the wrong side of the truth by where the
    /// rasterizer's snapped edges put a pixel centre (input units; 0 when exact): see
    /// [`coverage_error`].
    pub coverage_error: f64,
}

/// What the distance meshes may err by at a pixel centre that the rasterizer counts inside
/// a triangle it lies outside of (input units, for pixels of `pixel` units): vertices snap
/// to `2^-subpixel_bits` of a pixel, so such a centre lies within `2^-bits / sqrt(2)` pixel
/// of the edge, where the triangle's plane, extended (slope at most 2, a cone of three
/// sides), and the neighbour's differ by at most `3 · 2^-bits / sqrt(2)`; four steps bound
/// it. Seen on llvmpipe (8 bits): pixel centres under 0.001 pixel from a segment read the
/// other side's tent, minus their distance.
pub fn coverage_error(subpixel_bits: u32, pixel: f64) -> f64 {
    4.0 * 2f64.powi(-(subpixel_bits as i32)) * pixel
}

impl Diagram {
    /// Pixels won by each site.
    pub fn pixel_counts(&self, sites: usize) -> Vec<usize> {
        let mut counts = vec![0; sites];
        for &s in &self.site {
            if let Some(c) = counts.get_mut(s as usize) {
                *c += 1;
            }
        }
        counts
    }

    /// How far two distances may differ and still be a tie (input units): fp32 on coordinates
    /// of at most a few thousand pixels (1e-4 pixel), four steps of the fp32 depth value
    /// (2^-22 of the depth range), and the distance meshes' tessellation bound with the fp32
    /// interpolation across their triangles (2^-18 of the depth range, the triangles spanning
    /// it) and the rasterizer's coverage at their edges.
    pub fn tolerance(&self) -> f64 {
        let meshed = if self.mesh_error > 0.0 {
            self.mesh_error + self.depth_range * 2f64.powi(-18) + self.coverage_error
        } else {
            0.0
        };
        1e-4 * self.domain.pixel(self.n) + self.depth_range * 2f64.powi(-22) + meshed
    }
}
