//! The compute formulation (OpenGL 4.3), "then and now" for sections 2.2-3.3: the volume
//! integrals by the divergence theorem summed directly over triangles. One compute pass
//! writes each triangle's signed-tetrahedron integrals (`glsl/mass/compute/
//! triangle_integrals.comp`), and a reduction in shared memory
//! ([`crate::gl::reduce_shared`]) sums them per body. Where the paper rasterizes the
//! projected surface, peels every depth layer and sums pixels, this sums the exact
//! per-triangle terms: no framing, no resolution, no peels.
//!
//! Meshes larger than one storage buffer holds go through in chunks of triangles, each chunk
//! one integrand pass and one reduction, their sums added in f64; dispatches past the
//! renderer's work-group limit are split.
//!
//! Every body goes through fp32 in a unit frame (its bounding-box centre subtracted in f64,
//! divided per axis by a power of two), as the classic path does, and the sums are scaled
//! back in f64.
//!
//! **The part below a plane** (`--below`, and the submerged part of section 5.2): the kernel
//! clips each triangle of a body that the plane `z = level` crosses to `z <= level` (one or
//! two triangles) and sums those. The clipped surface is open along the plane; the solid below
//! is closed by the plane's cross-section, the cap, which the classic path gets from its
//! water-surface passes and the CPU reference ([`super::clip::below_plane`]) triangulates.
//! Here the cap is left out, and it adds nothing because the body's unit frame puts the
//! integration origin on the plane (its centre's z is `level`). Every integrand the kernel
//! sums, `f` = 1, x, y, z, x², y², z², xy, yz, zx, is homogeneous of some degree `k` (0, 1
//! or 2) about the origin, so `div(f p) = (3 + k) f` for the position `p`, and by the
//! divergence theorem `∫ f dV = 1/(3 + k) ∮ f (p · n) dA`; the kernel's signed tetrahedron
//! over a triangle is exactly that surface term (the cone from the origin over it). On the
//! cap `p · n = ±z = 0`, since the cap lies in the plane through the origin: each of the ten
//! surface terms vanishes there (every tetrahedron over a cap triangle is flat, `det = 0`).
//! A body wholly below the plane is summed whole about its own centre, and one wholly above
//! adds nothing.

use super::integrals::VolumeIntegrals;
use crate::gl::reduce::ReduceOp;
use crate::gl::reduce_shared::SharedReducer;
use crate::gl::{
    ensure_finite, memory_barrier, time_finished, Barrier, Buffer, BufferUsage, ComputeProgram,
    Context, GlError,
};
use crate::mesh::Mesh;
use crate::shader;
use glam::{DVec3, Vec3, Vec4};

/// The integrand pass and the reduction.
pub struct ComputeMass {
    ctx: Context,
    program: ComputeProgram,
    reducer: SharedReducer,
}

/// What the compute path found for a set of bodies.
#[derive(Clone, Debug)]
pub struct ComputeResult {
    /// One per body, about its bounding-box centre (with a plane that crosses the body: that
    /// centre moved onto the plane).
    pub integrals: Vec<VolumeIntegrals>,
    /// Time of the integrand pass and the reduction (wall clock between `glFinish` calls,
    /// [`time_finished`]), milliseconds.
    pub gpu_ms: f64,
}

/// Which integrals a pass sums.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Moments {
    /// All ten (mass properties).
    Second,
    /// Eq. 4's four, the volume and the first moments (buoyancy: the volume and the centre of
    /// buoyancy); the second moments come back zero.
    First,
}

impl Moments {
    fn lanes(self) -> usize {
        match self {
            Moments::Second => 3,
            Moments::First => 1,
        }
    }
}

/// A body's vertices: a mesh's own, or posed in f64 (a floating body in the world).
#[derive(Clone, Copy, Debug)]
pub enum Positions<'a> {
    Single(&'a [Vec3]),
    Double(&'a [DVec3]),
}

/// One body for [`ComputeMass::integrate_bodies`]: its triangles and its vertices.
#[derive(Clone, Copy, Debug)]
pub struct Body<'a> {
    pub triangles: &'a [[u32; 3]],
    pub positions: Positions<'a>,
}

impl<'a> Body<'a> {
    pub fn mesh(mesh: &'a Mesh) -> Self {
        Body {
            triangles: &mesh.triangles,
            positions: Positions::Single(&mesh.positions),
        }
    }

    /// `triangles` over vertices placed in f64.
    pub fn posed(triangles: &'a [[u32; 3]], positions: &'a [DVec3]) -> Self {
        Body {
            triangles,
            positions: Positions::Double(positions),
        }
    }

    fn vertex(&self, i: usize) -> DVec3 {
        match self.positions {
            Positions::Single(p) => p[i].as_dvec3(),
            Positions::Double(p) => p[i],
        }
    }

    fn vertices(&self) -> usize {
        match self.positions {
            Positions::Single(p) => p.len(),
            Positions::Double(p) => p.len(),
        }
    }

    /// The first vertex that is not finite, if any.
    fn non_finite(&self) -> Option<(usize, DVec3)> {
        (0..self.vertices())
            .map(|i| (i, self.vertex(i)))
            .find(|(_, p)| !p.is_finite())
    }

    /// Bounding box; a body without vertices is a point at the origin.
    fn bounds(&self) -> (DVec3, DVec3) {
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for i in 0..self.vertices() {
            lo = lo.min(self.vertex(i));
            hi = hi.max(self.vertex(i));
        }
        if self.vertices() == 0 {
            (DVec3::ZERO, DVec3::ZERO)
        } else {
            (lo, hi)
        }
    }
}

/// A body's unit frame, `unit = (world - center) / scale` (scale a power of two per axis),
/// and what of it the pass sums.
#[derive(Clone, Copy, Debug)]
struct Frame {
    center: DVec3,
    scale: DVec3,
    part: Part,
}

/// The part of a body a pass sums.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Part {
    /// All of it (no plane, or the body wholly below it).
    Whole,
    /// Below the plane through the frame's centre: clipped in the kernel.
    Clipped,
    /// Nothing (the body wholly above the plane).
    Nothing,
}

fn power_of_two_above(x: f64) -> f64 {
    2f64.powi(x.max(f64::MIN_POSITIVE).log2().ceil() as i32)
}

/// The unit frame of `body`: about its bounding-box centre, or, where the plane `z = below`
/// crosses it, about that centre moved onto the plane (so the cap adds nothing, see the
/// module doc), the z scale then covering the body on both sides of the plane.
fn unit_frame(body: &Body, below: Option<f64>) -> Frame {
    let (lo, hi) = body.bounds();
    let center = (lo + hi) / 2.0;
    let half = (hi - lo) / 2.0;
    let whole = Frame {
        center,
        scale: DVec3::from_array(half.to_array().map(power_of_two_above)),
        part: Part::Whole,
    };
    match below {
        None => whole,
        Some(level) if level >= hi.z => whole,
        Some(level) if level <= lo.z => Frame {
            part: Part::Nothing,
            ..whole
        },
        Some(level) => Frame {
            center: DVec3::new(center.x, center.y, level),
            scale: DVec3::new(
                whole.scale.x,
                whole.scale.y,
                power_of_two_above((hi.z - level).max(level - lo.z)),
            ),
            part: Part::Clipped,
        },
    }
}

impl ComputeMass {
    /// On a context below OpenGL 4.3, the error naming it.
    pub fn new(ctx: &Context) -> Result<ComputeMass, GlError> {
        ctx.require_compute("the compute formulation of paper 4")?;
        Ok(ComputeMass {
            ctx: ctx.clone(),
            program: ComputeProgram::new(
                ctx,
                &[shader!("glsl/mass/compute/triangle_integrals.comp")],
            )?,
            reducer: SharedReducer::new(ctx)?,
        })
    }

    /// The ten integrals of each body, all bodies in one integrand pass and one reduction
    /// (or, past what one storage buffer holds, one per chunk of triangles).
    pub fn integrate(&self, bodies: &[&Mesh]) -> Result<ComputeResult, GlError> {
        let bodies: Vec<Body> = bodies.iter().map(|m| Body::mesh(m)).collect();
        self.integrate_bodies(&bodies, None, Moments::Second)
    }

    /// The ten integrals of the part of each body below the plane `z = level`, clipped in
    /// the kernel, in the same passes.
    pub fn integrate_below(&self, bodies: &[&Mesh], level: f64) -> Result<ComputeResult, GlError> {
        let bodies: Vec<Body> = bodies.iter().map(|m| Body::mesh(m)).collect();
        self.integrate_bodies(&bodies, Some(level), Moments::Second)
    }

    /// The `moments` of each body (below `z = below` when given), every body in one integrand
    /// pass and one reduction (or one per chunk of triangles past a storage buffer's size).
    pub fn integrate_bodies(
        &self,
        bodies: &[Body],
        below: Option<f64>,
        moments: Moments,
    ) -> Result<ComputeResult, GlError> {
        if bodies.is_empty() {
            return Ok(ComputeResult {
                integrals: Vec::new(),
                gpu_ms: 0.0,
            });
        }
        if below.is_some_and(|z| !z.is_finite()) {
            return Err(GlError::Invalid(format!(
                "the plane z = {below:?} is not finite"
            )));
        }
        let mut frames = Vec::with_capacity(bodies.len());
        for (k, body) in bodies.iter().enumerate() {
            if let Some((i, p)) = body.non_finite() {
                return Err(GlError::Invalid(format!(
                    "body {k}: vertex {i} is not finite ({p:?})"
                )));
            }
            frames.push(unit_frame(body, below));
        }
        // Each body's triangles in a segment of `per_body` slots; the rest are zero
        // triangles, which add nothing.
        let per_body = bodies
            .iter()
            .map(|b| b.triangles.len())
            .max()
            .unwrap_or(0)
            .max(1);
        // A chunk takes up to `chunk` triangles of every body: its corner and term buffers
        // (at most three vec4 a triangle each) within what one storage buffer holds.
        let bytes_per_slot = 3 * std::mem::size_of::<Vec4>() * bodies.len();
        let most = self.ctx.max_storage_buffer_bytes() / bytes_per_slot;
        if most == 0 {
            return Err(GlError::Limit(format!(
                "{} bodies: one triangle of each needs {bytes_per_slot} bytes of a storage \
                 buffer; this renderer allows {}",
                bodies.len(),
                self.ctx.max_storage_buffer_bytes()
            )));
        }
        let chunk = per_body.min(most);
        let lanes = moments.lanes();
        let mut sums = vec![[0f64; 4]; 3 * bodies.len()];
        let mut gpu_ms = 0.0;
        for first in (0..per_body).step_by(chunk) {
            let count = chunk.min(per_body - first);
            let (partial, ms) = self.integrate_chunk(bodies, &frames, first, count, moments)?;
            ensure_finite(
                partial.iter().flatten().copied(),
                "the volume integrals",
                "triangle integrals (compute)",
            )?;
            for (sum, part) in sums.iter_mut().zip(&partial) {
                for (s, p) in sum.iter_mut().zip(part) {
                    *s += *p as f64;
                }
            }
            gpu_ms += ms;
        }
        ensure_finite(
            sums.iter().flatten().copied(),
            "the volume integrals",
            "triangle integrals (compute)",
        )?;
        let n = bodies.len();
        let integrals = frames
            .iter()
            .enumerate()
            .map(|(body, frame)| {
                let lane = |l: usize| {
                    if l < lanes {
                        sums[l * n + body]
                    } else {
                        [0.0; 4]
                    }
                };
                let [l0, l1, l2] = [lane(0), lane(1), lane(2)];
                let unit = VolumeIntegrals {
                    origin: DVec3::ZERO,
                    v: l0[0],
                    x: l0[1],
                    y: l0[2],
                    z: l0[3],
                    xx: l1[0],
                    yy: l1[1],
                    zz: l1[2],
                    xy: l2[0],
                    yz: l2[1],
                    zx: l2[2],
                };
                VolumeIntegrals {
                    origin: frame.center,
                    ..unit.stretched(frame.scale)
                }
            })
            .collect();
        Ok(ComputeResult { integrals, gpu_ms })
    }

    /// Triangles `first .. first + count` of every body through the integrand pass and the
    /// reduction: a sum per lane and body (`[lane * bodies + body]`), and the milliseconds.
    fn integrate_chunk(
        &self,
        bodies: &[Body],
        frames: &[Frame],
        first: usize,
        count: usize,
        moments: Moments,
    ) -> Result<(Vec<[f32; 4]>, f64), GlError> {
        let slots = count * bodies.len();
        let mut corners = vec![Vec4::ZERO; 3 * slots];
        for (k, (body, frame)) in bodies.iter().zip(frames).enumerate() {
            if frame.part == Part::Nothing {
                continue;
            }
            let clip = if frame.part == Part::Clipped {
                1.0
            } else {
                0.0
            };
            let triangles = body.triangles.iter().skip(first).take(count);
            for (t, tri) in triangles.enumerate() {
                let slot = &mut corners[3 * (k * count + t)..][..3];
                for (corner, &v) in slot.iter_mut().zip(tri) {
                    let p = (body.vertex(v as usize) - frame.center) / frame.scale;
                    *corner = p.as_vec3().extend(0.0);
                }
                slot[0].w = clip;
            }
        }
        let lanes = moments.lanes();
        let input = Buffer::from_slice(&self.ctx, &corners, BufferUsage::Static)?;
        let terms = Buffer::new(&self.ctx, lanes * slots * 16, BufferUsage::GpuCopy)?;
        time_finished(&self.ctx, || {
            self.program
                .dispatch("triangle integrals (compute)")
                .storage(0, &input)
                .storage(1, &terms)
                .uniform("u_triangles", slots as u32)
                .uniform("u_second_moments", moments == Moments::Second)
                .run_over_in_chunks(slots as u32, "u_first")?;
            memory_barrier(&self.ctx, &[Barrier::Storage]);
            self.reducer.reduce_segments(
                &terms,
                (lanes * bodies.len()) as u32,
                count as u32,
                ReduceOp::Sum,
            )
        })
    }
}

/// The same sum on the CPU in f64 (the compute path's reference): the signed tetrahedra of
/// every triangle, about `origin`.
pub fn tetrahedron_sum(mesh: &Mesh, origin: DVec3) -> VolumeIntegrals {
    let mut out = VolumeIntegrals {
        origin,
        ..VolumeIntegrals::default()
    };
    for tri in &mesh.triangles {
        let [a, b, c] = tri.map(|v| mesh.positions[v as usize].as_dvec3() - origin);
        add_tetrahedron(&mut out, a, b, c);
    }
    out
}

/// The kernel's sum below the plane `z = level` on the CPU in f64 (the compute path's
/// reference for `--below`): every triangle clipped to `z <= level` as the kernel clips it,
/// the tetrahedra taken from `(origin_x, origin_y, level)`, no cap. About an origin on the
/// plane that is the submerged solid's integrals (module doc).
pub fn tetrahedron_sum_below(
    mesh: &Mesh,
    level: f64,
    origin_x: f64,
    origin_y: f64,
) -> VolumeIntegrals {
    let origin = DVec3::new(origin_x, origin_y, level);
    let mut out = VolumeIntegrals {
        origin,
        ..VolumeIntegrals::default()
    };
    for tri in &mesh.triangles {
        let v = tri.map(|i| mesh.positions[i as usize].as_dvec3() - origin);
        let crossing = |below: DVec3, above: DVec3| {
            let t = below.z / (below.z - above.z);
            DVec3::new(
                below.x + t * (above.x - below.x),
                below.y + t * (above.y - below.y),
                0.0,
            )
        };
        let mut polygon = Vec::with_capacity(4);
        for k in 0..3 {
            let (i, j) = (v[k], v[(k + 1) % 3]);
            if i.z <= 0.0 {
                polygon.push(i);
            }
            if i.z < 0.0 && j.z > 0.0 {
                polygon.push(crossing(i, j));
            }
            if i.z > 0.0 && j.z < 0.0 {
                polygon.push(crossing(j, i));
            }
        }
        for k in 1..polygon.len().saturating_sub(1) {
            add_tetrahedron(&mut out, polygon[0], polygon[k], polygon[k + 1]);
        }
    }
    out
}

/// Adds the integrals of the signed tetrahedron (origin, a, b, c) to `out`.
fn add_tetrahedron(out: &mut VolumeIntegrals, a: DVec3, b: DVec3, c: DVec3) {
    let det = a.dot(b.cross(c));
    let s = a + b + c;
    let sq = a * a + b * b + c * c + s * s;
    let yzx = |v: DVec3| DVec3::new(v.y, v.z, v.x);
    let pr = a * yzx(a) + b * yzx(b) + c * yzx(c) + s * yzx(s);
    out.v += det / 6.0;
    out.x += det / 24.0 * s.x;
    out.y += det / 24.0 * s.y;
    out.z += det / 24.0 * s.z;
    out.xx += det / 120.0 * sq.x;
    out.yy += det / 120.0 * sq.y;
    out.zz += det / 120.0 * sq.z;
    out.xy += det / 120.0 * pr.x;
    out.yz += det / 120.0 * pr.y;
    out.zx += det / 120.0 * pr.z;
}
