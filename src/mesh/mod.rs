//! Indexed triangle meshes: the one geometry type every paper module shares.
//!
//! - [`Mesh`]: positions and counter-clockwise triangles, with the measures the papers
//!   use (bounds, normals, area, signed volume) and rigid/affine transforms.
//! - [`obj`]: OBJ reading (through `tobj`) and writing; errors name the file and line.
//! - [`validate`]: a report of what is wrong with a mesh (non-finite vertices, indices
//!   out of range, degenerate triangles) and the closedness (watertightness) query.
//! - [`generate`]: the test objects of the papers (paper 4's Table 1 counts are reached in
//!   `mass::models`, which refines the bunny and the pipe and says where a count differs).
//! - [`retessellate`](mod@retessellate): refinement to a requested triangle count.
//! - [`load_bunny`]: the Stanford bunny shipped in `assets/bunny.obj` (1839 vertices, 3674
//!   faces; Table 1's 2557 and 5110 are `mass::models::table1_bunny`).

mod error;
pub mod generate;
pub mod obj;
pub mod retessellate;
pub mod validate;

pub use error::{Location, MeshError};
pub use generate::{
    cube, cuboid, pipe, teapot, teapot_patches, torus, torus_closed, torus_knot,
    torus_with_triangles, uv_sphere, Pipe, TorusKnot,
};
pub use obj::{load_bunny, load_obj, parse_obj, to_obj_string, write_obj};
pub use retessellate::{retessellate, subdivide};
pub use validate::{Closedness, ValidationReport};

use glam::{Affine3A, Vec3};

/// An indexed triangle mesh. Triangles are counter-clockwise seen from outside, so that
/// the right-hand normal points out of a closed mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
}

/// An axis-aligned box. The bounds of an empty mesh are the empty box
/// (`min = +inf`, `max = -inf`), for which [`Bounds::is_empty`] is true.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub min: Vec3,
    pub max: Vec3,
}

impl Bounds {
    pub const EMPTY: Bounds = Bounds {
        min: Vec3::INFINITY,
        max: Vec3::NEG_INFINITY,
    };

    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }
    pub fn size(&self) -> Vec3 {
        self.max - self.min
    }
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }
    /// The smallest box holding this one and `p`.
    pub fn including(self, p: Vec3) -> Bounds {
        Bounds {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }
}

impl Mesh {
    pub fn new(positions: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Self {
        Self {
            positions,
            triangles,
        }
    }

    /// The positions as plain float triples, without a copy (for GPU upload).
    pub fn positions_f32(&self) -> &[[f32; 3]] {
        bytemuck::cast_slice(&self.positions)
    }

    /// The three corners of triangle `t`.
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        self.triangles[t].map(|i| self.positions[i as usize])
    }

    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The box around all positions (referenced or not).
    pub fn bounds(&self) -> Bounds {
        self.positions
            .iter()
            .fold(Bounds::EMPTY, |b, &p| b.including(p))
    }

    /// `(b - a) x (c - a)` of triangle `t`: its normal scaled by twice its area.
    pub fn triangle_cross(&self, t: usize) -> Vec3 {
        let [a, b, c] = self.triangle(t);
        (b - a).cross(c - a)
    }

    /// Unit normal of every triangle (right-hand rule); zero for a zero-area triangle.
    pub fn face_normals(&self) -> Vec<Vec3> {
        (0..self.triangles.len())
            .map(|t| self.triangle_cross(t).normalize_or_zero())
            .collect()
    }

    /// Area of every triangle.
    pub fn face_areas(&self) -> Vec<f32> {
        (0..self.triangles.len())
            .map(|t| 0.5 * self.triangle_cross(t).length())
            .collect()
    }

    /// Unit vertex normals, the area-weighted mean of the normals of the triangles around
    /// each vertex; zero for a vertex no triangle uses. Vertices duplicated along a seam
    /// get one-sided normals (weld first with [`Mesh::welded`] for smooth ones).
    pub fn vertex_normals(&self) -> Vec<Vec3> {
        let mut sums = vec![Vec3::ZERO; self.positions.len()];
        for (t, tri) in self.triangles.iter().enumerate() {
            // The cross product's length is twice the area: the area weighting for free.
            let n = self.triangle_cross(t);
            for &i in tri {
                sums[i as usize] += n;
            }
        }
        sums.into_iter().map(Vec3::normalize_or_zero).collect()
    }

    /// Total surface area (accumulated in f64).
    pub fn surface_area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| 0.5 * self.triangle_cross(t).as_dvec3().length())
            .sum()
    }

    /// Signed volume by the divergence theorem: the sum over triangles of
    /// `a . (b x c) / 6` (accumulated in f64). For a closed mesh it is the enclosed volume,
    /// positive when the triangles are counter-clockwise seen from outside and negative
    /// for an inside-out mesh. For an open mesh it depends on the origin.
    pub fn signed_volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|tri| {
                let [a, b, c] = tri.map(|i| self.positions[i as usize].as_dvec3());
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// True when the signed volume is positive: the triangles face outward (for a closed
    /// mesh). Paper 4 needs this: an inside-out mesh gives negated mass properties.
    pub fn is_outward(&self) -> bool {
        self.signed_volume() > 0.0
    }

    /// The same surface with every triangle's winding reversed (normals point inward).
    pub fn flipped(&self) -> Mesh {
        let triangles = self.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect();
        Mesh::new(self.positions.clone(), triangles)
    }

    /// This mesh with `transform` applied to every position. A transform that mirrors
    /// (negative determinant) would turn the mesh inside out, so the winding is reversed
    /// to keep the triangles counter-clockwise seen from outside.
    pub fn transformed(&self, transform: &Affine3A) -> Mesh {
        let positions = self
            .positions
            .iter()
            .map(|&p| transform.transform_point3(p))
            .collect();
        let moved = Mesh::new(positions, self.triangles.clone());
        if transform.matrix3.determinant() < 0.0 {
            moved.flipped()
        } else {
            moved
        }
    }

    /// This mesh moved by `offset`.
    pub fn translated(&self, offset: Vec3) -> Mesh {
        self.transformed(&Affine3A::from_translation(offset))
    }

    /// This mesh scaled about the origin.
    pub fn scaled(&self, scale: Vec3) -> Mesh {
        self.transformed(&Affine3A::from_scale(scale))
    }

    /// Several meshes as one (positions concatenated, indices offset), in order.
    pub fn merged<'a>(meshes: impl IntoIterator<Item = &'a Mesh>) -> Mesh {
        let mut out = Mesh::default();
        for m in meshes {
            let base = out.positions.len() as u32;
            out.positions.extend_from_slice(&m.positions);
            out.triangles
                .extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        out
    }
}
