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

/// Several meshes in one vertex buffer, drawn through an index buffer rewritten per batch.
///
/// The listing needs `n_z` to have its triangle's sign at every fragment; with shared
/// vertices that is impossible where up- and down-facing triangles meet. So each mesh is
/// stored twice, once with `n_z = +1` and once with `n_z = -1` at every vertex, and each
/// triangle's indices point into the copy of its facing under the current pose (the sign
/// of the z component of its world normal, computed on the CPU from the posed vertices).
/// Shared vertices are then shaded once per copy instead of once per triangle corner,
/// which is most of the vertex work on a software rasterizer.
pub struct Soup {
    pub vertices: VertexArray,
    /// (first vertex, vertex count V) of each mesh: its `n_z = +1` copy is vertices
    /// `first .. first + V`, its `n_z = -1` copy `first + V .. first + 2V`.
    pub ranges: Vec<(usize, usize)>,
    triangles: Vec<Vec<[u32; 3]>>,
    indices: Buffer,
}

impl Soup {
    pub fn new(ctx: &Context, meshes: &[&Mesh]) -> Result<Soup, GlError> {
        let mut data: Vec<[f32; 4]> = Vec::new();
        let mut ranges = Vec::new();
        for mesh in meshes {
            let first = data.len();
            for sign in [1.0, -1.0] {
                data.extend(mesh.positions.iter().map(|p| [p.x, p.y, p.z, sign]));
            }
            ranges.push((first, mesh.positions.len()));
        }
        let buffer = Buffer::from_slice(ctx, &data, BufferUsage::Static)?;
        let indices = Buffer::from_slice(ctx, &[0u32; 3], BufferUsage::Dynamic)?;
        let mut vertices = VertexArray::new(ctx)?;
        vertices.float_attribute(0, &buffer, 3, 16, 0, 0)?;
        vertices.float_attribute(1, &buffer, 1, 16, 12, 0)?;
        vertices.set_index_buffer(&indices)?;
        Ok(Soup {
            vertices,
            ranges,
            triangles: meshes.iter().map(|m| m.triangles.clone()).collect(),
            indices,
        })
    }

    /// Appends the indices of mesh `m`'s triangles posed at `world` (its vertices in
    /// world coordinates) for which `keep` holds, each into the copy of its facing.
    /// Returns the number of indices appended.
    pub fn push_triangles(
        &self,
        m: usize,
        world: &[glam::DVec3],
        mut keep: impl FnMut(&[u32; 3]) -> bool,
        out: &mut Vec<u32>,
    ) -> usize {
        let (first, count) = self.ranges[m];
        let before = out.len();
        for tri in self.triangles[m].iter().filter(|t| keep(t)) {
            let [a, b, c] = tri.map(|i| world[i as usize]);
            let n_z = (b - a).truncate().perp_dot((c - a).truncate());
            let copy = if n_z >= 0.0 { first } else { first + count } as u32;
            out.extend(tri.map(|i| copy + i));
        }
        out.len() - before
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

/// The ten integrals from the three target sums of one body, about the framing centre
/// (where the listing's `p` is measured from): the listing writes `sgn(n_z) z · (x, y, z, 1)`, `x` times that, and `sgn(n_z) z (y², yz, z²)`;
/// eq. 4 and 6 add the factors 1/2 and 1/3 and the pixel area `dx dy`.
pub fn decode(sums: [[f64; 4]; TARGETS], framing: &Framing) -> VolumeIntegrals {
    let [t0, t1, t2] = sums;
    let local = VolumeIntegrals {
        origin: framing.center,
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
    local * framing.pixel_size().powi(2)
}
