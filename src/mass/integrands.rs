//! Integrands [section 3.1]: the listing's fragment program, the geometry it draws (each
//! vertex carrying its triangle's normal, so `n_z` is the face's), and the decoding of the
//! three summed render targets into the ten integrals of eq. 4 and 6.

use super::framing::Framing;
use super::integrals::VolumeIntegrals;
use super::peel_depth::PeelDepth;
use crate::gl::{Buffer, BufferUsage, Context, GlError, Program, Rect, ShaderSource, VertexArray};
use crate::shader;
use glam::DVec3;
use std::cell::RefCell;

/// Body geometry under the orthographic view: `p` and `n_z` for the listing.
pub const VERTEX: ShaderSource<'static> = shader!("glsl/mass/integrands.vert");
/// Renames the listing's `main` so a peel test can run first.
pub const PRELUDE: ShaderSource<'static> = shader!("glsl/mass/peel_prelude.frag");
/// The fragment shader of section 3.1, ported line for line.
pub const LISTING: ShaderSource<'static> = shader!("cg_ports/mass_integrands.frag");
/// Section 5.2's pass 1: eq. 4's four integrands alone (the listing's first target).
pub const LISTING_EQ4: ShaderSource<'static> = shader!("glsl/mass/integrands_eq4.frag");
/// The listing's targets written with constants: the passes' floor, not integrals.
pub const CONSTANT: ShaderSource<'static> = shader!("glsl/mass/integrands_constant.frag");
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

/// The channels of each target by name (the pictures' titles); the fourth of the last two
/// targets is unused.
pub const CHANNELS: [&[&str]; TARGETS] = [
    &["rx", "ry", "rz", "V"],
    &["Ixx", "Ixy", "Ixz"],
    &["Iyy", "Iyz", "Izz"],
];

/// Which integrands the passes evaluate.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Integrands {
    /// The ten of eq. 4 and 6 in three render targets: the section 3.1 listing (mass
    /// properties).
    #[default]
    All,
    /// Eq. 4's four (volume and first moments) in one target: what pass 1 of section 5.2
    /// evaluates, all a buoyancy step needs (volume and centre of buoyancy).
    Eq4,
    /// No integrands: the listing's three targets written with constants. The same passes
    /// with no arithmetic, a floor to time the passes against (`mass` prints it); the sums
    /// are no integrals.
    Constant,
}

impl Integrands {
    /// The render targets the passes write.
    pub fn targets(self) -> usize {
        match self {
            Integrands::All | Integrands::Constant => TARGETS,
            Integrands::Eq4 => 1,
        }
    }

    /// The fragment program that evaluates them.
    fn listing(self) -> ShaderSource<'static> {
        match self {
            Integrands::All => LISTING,
            Integrands::Eq4 => LISTING_EQ4,
            Integrands::Constant => CONSTANT,
        }
    }
}

/// The program of the peel passes: the listing wrapped by the peel and water tests.
pub fn peel_program(ctx: &Context, integrands: Integrands) -> Result<Program, GlError> {
    peel_program_at(ctx, integrands, PeelDepth::Float32)
}

/// [`peel_program`] with the peel test for peel depths stored as `depth`.
pub fn peel_program_at(
    ctx: &Context,
    integrands: Integrands,
    depth: PeelDepth,
) -> Result<Program, GlError> {
    let (test, after) = depth.peel_test();
    let mut parts = vec![PRELUDE, integrands.listing(), test, PEEL_MAIN];
    parts.extend(after);
    Program::new(ctx, &[VERTEX], &parts)
}

/// The program of pass 0 of 5.2 (the fluid surface's depth `T_dw`).
pub fn water_depth_program(ctx: &Context) -> Result<Program, GlError> {
    Program::new(ctx, &[WATER_VERTEX], &[WATER_DEPTH])
}

/// The program of the last pass of 5.2 (the fluid-surface patch `T_w`).
pub fn water_patch_program(ctx: &Context, integrands: Integrands) -> Result<Program, GlError> {
    Program::new(
        ctx,
        &[WATER_VERTEX],
        &[PRELUDE, integrands.listing(), WATER_PATCH],
    )
}

/// A batch's bodies, posed and framed by the CPU, in one vertex and one index buffer, so
/// that each peel is a single draw for every body.
///
/// The listing needs `n_z` to have its triangle's sign at every fragment; with shared
/// vertices that is impossible where up- and down-facing triangles meet. So each posed body
/// is stored twice, once with `n_z = +1` and once with `n_z = -1` at every vertex, and each
/// triangle's indices point into the copy of its facing (the sign of the z component of its
/// world normal). Shared vertices are then shaded once per copy instead of once per
/// triangle corner, which is most of the vertex work on a software rasterizer.
///
/// Bodies come in groups (the buoyancy scene: one per shape), each a range of the index
/// buffer drawn with its own occlusion query, so that a group whose bodies are all peeled
/// through is not drawn again while deeper bodies go on.
///
/// Each vertex carries its clip position in the whole target (the body's orthographic
/// [`Framing`] followed by its tile, [`posed_clip`]) and `p`, its position relative to the
/// framing centre: one draw then needs no per-body uniforms or viewports, and the CPU,
/// which poses every vertex anyway to frame the body and cull its triangles, does it in f64.
pub struct Soup {
    pub vertices: VertexArray,
    buffer: Buffer,
    indices: Buffer,
    /// The batch being built (kept to reuse its allocations).
    staging: RefCell<Staging>,
    /// Index ranges (first, count) of the groups of the last uploaded batch.
    groups: RefCell<Vec<(usize, usize)>>,
}

/// A posed vertex: clip position in the whole target, `n_z`, `p`.
type PosedVertex = [f32; 7];

#[derive(Default)]
struct Staging {
    vertices: Vec<PosedVertex>,
    indices: Vec<u32>,
    /// Where each group's indices start.
    group_starts: Vec<usize>,
    /// [`Soup::push_body`]'s vertex map, kept for its allocation.
    remap: Vec<u32>,
}

/// Where a body lies: its framing and its tile of a `target` of pixels.
#[derive(Clone, Copy, Debug)]
pub struct Placement {
    pub framing: Framing,
    pub tile: Rect,
    pub target: (u32, u32),
}

impl Soup {
    pub fn new(ctx: &Context) -> Result<Soup, GlError> {
        let stride = std::mem::size_of::<PosedVertex>();
        let buffer = Buffer::new(ctx, stride * 3, BufferUsage::Dynamic)?;
        let indices = Buffer::from_slice(ctx, &[0u32; 3], BufferUsage::Dynamic)?;
        let mut vertices = VertexArray::new(ctx)?;
        vertices.float_attribute(0, &buffer, 3, stride, 0, 0)?;
        vertices.float_attribute(1, &buffer, 1, stride, 12, 0)?;
        vertices.float_attribute(2, &buffer, 3, stride, 16, 0)?;
        vertices.set_index_buffer(&indices)?;
        Ok(Soup {
            vertices,
            buffer,
            indices,
            staging: RefCell::default(),
            groups: RefCell::default(),
        })
    }

    /// Room for `bodies` bodies of up to `vertices` vertices and `triangles` triangles each,
    /// so that the buffers never grow during a run.
    pub fn reserve(&self, bodies: usize, vertices: usize, triangles: usize) -> Result<(), GlError> {
        let vertex_bytes = bodies * 2 * vertices * std::mem::size_of::<PosedVertex>();
        let index_bytes = bodies * 3 * triangles * std::mem::size_of::<u32>();
        for (buffer, bytes) in [(&self.buffer, vertex_bytes), (&self.indices, index_bytes)] {
            if bytes > buffer.len_bytes() {
                buffer.replace(&vec![0u8; bytes])?;
            }
        }
        Ok(())
    }

    /// Starts a new batch.
    pub fn clear(&self) {
        let mut s = self.staging.borrow_mut();
        s.vertices.clear();
        s.indices.clear();
        s.group_starts.clear();
    }

    /// Starts a new group: the bodies pushed from now on are drawn together.
    pub fn begin_group(&self) {
        let mut s = self.staging.borrow_mut();
        let start = s.indices.len();
        s.group_starts.push(start);
    }

    /// Adds a body to the current group (the first body starts one): those of its
    /// `triangles` for which `keep` holds, with their vertices posed at `world` (world
    /// coordinates) and placed at `at`. Returns the number of triangles added.
    ///
    /// A vertex is stored once per sign of `n_z` among the kept triangles that use it, and
    /// only if one does: the renderer then fetches and shades no vertex that no triangle
    /// draws (a floating body's vertices above the water, those of culled slivers).
    pub fn push_body(
        &self,
        triangles: &[[u32; 3]],
        world: &[DVec3],
        at: &Placement,
        mut keep: impl FnMut(&[u32; 3]) -> bool,
    ) -> usize {
        let mut guard = self.staging.borrow_mut();
        let staging = &mut *guard;
        if staging.group_starts.is_empty() {
            staging.group_starts.push(0);
        }
        // Where vertex i with sign s of n_z went: remap[2 i + (s < 0)].
        staging.remap.clear();
        staging.remap.resize(2 * world.len(), u32::MAX);
        let before = staging.indices.len();
        for tri in triangles.iter().filter(|t| keep(t)) {
            let [a, b, c] = tri.map(|i| world[i as usize]);
            let n_z = (b - a).truncate().perp_dot((c - a).truncate());
            let down = (n_z < 0.0) as usize;
            for i in tri.map(|i| i as usize) {
                let slot = &mut staging.remap[2 * i + down];
                if *slot == u32::MAX {
                    *slot = staging.vertices.len() as u32;
                    let p = world[i] - at.framing.center;
                    let clip = posed_clip(p, at);
                    let sign = if down == 1 { -1.0 } else { 1.0 };
                    staging.vertices.push([
                        clip.x as f32,
                        clip.y as f32,
                        clip.z as f32,
                        sign,
                        p.x as f32,
                        p.y as f32,
                        p.z as f32,
                    ]);
                }
                staging.indices.push(*slot);
            }
        }
        (staging.indices.len() - before) / 3
    }

    /// Sends the batch to the GPU: the buffers are rewritten in place when they fit (no
    /// reallocation per step), else grown.
    pub fn upload(&self) -> Result<(), GlError> {
        let staging = self.staging.borrow();
        let write = |buffer: &Buffer, bytes: &[u8]| {
            if bytes.len() <= buffer.len_bytes() {
                buffer.write(0, bytes)
            } else {
                buffer.replace(bytes)
            }
        };
        write(&self.buffer, bytemuck::cast_slice(&staging.vertices))?;
        write(&self.indices, bytemuck::cast_slice(&staging.indices))?;
        let ends = staging.group_starts.iter().skip(1).copied();
        *self.groups.borrow_mut() = staging
            .group_starts
            .iter()
            .zip(ends.chain([staging.indices.len()]))
            .map(|(&first, end)| (first, end - first))
            .collect();
        Ok(())
    }

    /// The index range (first, count) of each group of the uploaded batch.
    pub fn groups(&self) -> Vec<(usize, usize)> {
        self.groups.borrow().clone()
    }
}

/// The clip position in the whole target of a point at `p` from the framing centre: the
/// framing's orthographic projection ([`Framing::projection`]: x, y onto [-1, 1], higher z
/// nearer), then the tile's viewport within the target, in f64.
pub fn posed_clip(p: DVec3, at: &Placement) -> DVec3 {
    let f = &at.framing;
    let ndc = DVec3::new(p.x / f.half_width, p.y / f.half_width, -p.z / f.half_depth);
    let (w, h) = (at.target.0 as f64, at.target.1 as f64);
    let t = at.tile;
    DVec3::new(
        (2.0 * t.x as f64 + (ndc.x + 1.0) * t.w as f64) / w - 1.0,
        (2.0 * t.y as f64 + (ndc.y + 1.0) * t.h as f64) / h - 1.0,
        ndc.z,
    )
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
