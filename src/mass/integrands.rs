//! Integrands [section 3.1]: the listing's fragment program, the geometry it draws (each
//! vertex carrying its triangle's normal, so `n_z` is the face's), and the decoding of the
//! three summed render targets into the ten integrals of eq. 4 and 6.

use super::framing::Framing;
use super::integrals::VolumeIntegrals;
use crate::gl::{peel, Buffer, BufferUsage, Context, GlError, Program, ShaderSource, VertexArray};
use crate::mesh::Mesh;
use crate::shader;

/// Body geometry under the orthographic view: `p` and `n_z` for the listing.
pub const VERTEX: ShaderSource<'static> = shader!("glsl/mass/integrands.vert");
/// Renames the listing's `main` so a peel test can run first.
pub const PRELUDE: ShaderSource<'static> = shader!("glsl/mass/peel_prelude.frag");
/// The fragment shader of section 3.1, ported line for line.
pub const LISTING: ShaderSource<'static> = shader!("cg_ports/mass_integrands.frag");
/// Peel test + water test + the listing.
pub const PEEL_MAIN: ShaderSource<'static> = shader!("glsl/mass/peel_main.frag");
/// The fluid surface quad of one tile.
pub const WATER_VERTEX: ShaderSource<'static> = shader!("glsl/mass/water_surface.vert");
/// Pass 0 of 5.2: depth only.
pub const WATER_DEPTH: ShaderSource<'static> = shader!("glsl/mass/water_depth.frag");
/// The last pass of 5.2: the listing on the fluid surface inside the body.
pub const WATER_PATCH: ShaderSource<'static> = shader!("glsl/mass/water_patch.frag");

/// The three render targets (MRT) and what each channel holds, as the listing comments:
/// `(rx, ry, rz, V)`, `(Ixx, Ixy, Ixz, .)`, `(Iyy, Iyz, Izz, .)`.
pub const TARGETS: usize = 3;

/// The program of the peel passes: the listing wrapped by the peel and water tests.
pub fn peel_program(ctx: &Context) -> Result<Program, GlError> {
    Program::new(
        ctx,
        &[VERTEX],
        &[PRELUDE, LISTING, peel::PEEL_SNIPPET, PEEL_MAIN],
    )
}

/// The program of pass 0 of 5.2 (the fluid surface's depth `T_dw`).
pub fn water_depth_program(ctx: &Context) -> Result<Program, GlError> {
    Program::new(ctx, &[WATER_VERTEX], &[WATER_DEPTH])
}

/// The program of the last pass of 5.2 (the fluid-surface patch `T_w`).
pub fn water_patch_program(ctx: &Context) -> Result<Program, GlError> {
    Program::new(ctx, &[WATER_VERTEX], &[PRELUDE, LISTING, WATER_PATCH])
}

/// Several meshes in one vertex buffer, each triangle with its own three vertices: per
/// vertex its position and its triangle's unit normal (body frame), 6 floats. An index
/// buffer, rewritten per batch, selects the triangles to draw (all of them, or those
/// that reach below the water).
pub struct Soup {
    pub vertices: VertexArray,
    /// (first vertex, vertex count) of each mesh; triangle t of mesh m is vertices
    /// `ranges[m].0 + 3t ..+ 3`.
    pub ranges: Vec<(usize, usize)>,
    indices: Buffer,
}

impl Soup {
    pub fn new(ctx: &Context, meshes: &[&Mesh]) -> Result<Soup, GlError> {
        let mut data: Vec<[f32; 6]> = Vec::new();
        let mut ranges = Vec::new();
        for mesh in meshes {
            let first = data.len();
            for t in 0..mesh.triangles.len() {
                let [a, b, c] = mesh.triangle(t);
                let n = (b - a).cross(c - a).normalize_or_zero();
                for v in [a, b, c] {
                    data.push([v.x, v.y, v.z, n.x, n.y, n.z]);
                }
            }
            ranges.push((first, data.len() - first));
        }
        let buffer = Buffer::from_slice(ctx, &data, BufferUsage::Static)?;
        let indices = Buffer::from_slice(ctx, &[0u32; 3], BufferUsage::Dynamic)?;
        let mut vertices = VertexArray::new(ctx)?;
        vertices.float_attribute(0, &buffer, 3, 24, 0, 0)?;
        vertices.float_attribute(1, &buffer, 3, 24, 12, 0)?;
        vertices.set_index_buffer(&indices)?;
        Ok(Soup {
            vertices,
            ranges,
            indices,
        })
    }

    /// Every triangle of mesh `m`, as indices.
    pub fn all_triangles(&self, m: usize) -> impl Iterator<Item = u32> {
        let (first, count) = self.ranges[m];
        (first as u32)..(first + count) as u32
    }

    /// The index list the next batch draws from.
    /// Rewritten in place when it fits (no reallocation per step), else grown.
    pub fn set_indices(&self, indices: &[u32]) -> Result<(), GlError> {
        if std::mem::size_of_val(indices) <= self.indices.len_bytes() {
            self.indices.write(0, indices)
        } else {
            self.indices.replace(indices)
        }
    }
}

/// The ten integrals from the three target sums of one body, in world coordinates: the
/// listing writes `sgn(n_z) z · (x, y, z, 1)`, `x` times that, and `sgn(n_z) z (y², yz, z²)`;
/// eq. 4 and 6 add the factors 1/2 and 1/3 and the pixel area `dx dy`.
pub fn decode(sums: [[f64; 4]; TARGETS], framing: &Framing) -> VolumeIntegrals {
    let [t0, t1, t2] = sums;
    let local = VolumeIntegrals {
        v: t0[3],
        x: t0[0],
        y: t0[1],
        z: t0[2] / 2.0,
        xx: t1[0],
        xy: t1[1],
        zx: t1[2] / 2.0,
        yy: t2[0],
        yz: t2[1] / 2.0,
        zz: t2[2] / 3.0,
    };
    (local * framing.pixel_size().powi(2)).translated(framing.center)
}
