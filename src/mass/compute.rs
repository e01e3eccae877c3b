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

use super::integrals::VolumeIntegrals;
use crate::gl::reduce::ReduceOp;
use crate::gl::reduce_shared::SharedReducer;
use crate::gl::{
    ensure_finite, memory_barrier, time_finished, Barrier, Buffer, BufferUsage, ComputeProgram,
    Context, GlError,
};
use crate::mesh::Mesh;
use crate::shader;
use glam::{DVec3, Vec4};

/// The integrand pass and the reduction.
pub struct ComputeMass {
    ctx: Context,
    program: ComputeProgram,
    reducer: SharedReducer,
}

/// What the compute path found for a set of bodies.
#[derive(Clone, Debug)]
pub struct ComputeResult {
    /// One per body, about its bounding-box centre.
    pub integrals: Vec<VolumeIntegrals>,
    /// Time of the integrand pass and the reduction (wall clock between `glFinish` calls,
    /// [`time_finished`]), milliseconds.
    pub gpu_ms: f64,
}

/// A body's unit frame: `unit = (world - center) / scale`, scale a power of two per axis.
fn unit_frame(mesh: &Mesh) -> (DVec3, DVec3) {
    let b = mesh.bounds();
    let (lo, hi) = (b.min.as_dvec3(), b.max.as_dvec3());
    let center = (lo + hi) / 2.0;
    let half = ((hi - lo) / 2.0).max(DVec3::splat(f64::MIN_POSITIVE));
    let scale = half.to_array().map(|h| 2f64.powi(h.log2().ceil() as i32));
    (center, DVec3::from_array(scale))
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
        if bodies.is_empty() {
            return Ok(ComputeResult {
                integrals: Vec::new(),
                gpu_ms: 0.0,
            });
        }
        let mut frames = Vec::with_capacity(bodies.len());
        for (body, mesh) in bodies.iter().enumerate() {
            if let Some(i) = mesh.positions.iter().position(|p| !p.is_finite()) {
                return Err(GlError::Invalid(format!(
                    "body {body}: vertex {i} is not finite ({:?})",
                    mesh.positions[i]
                )));
            }
            frames.push(unit_frame(mesh));
        }
        // Each body's triangles in a segment of `per_body` slots; the rest are zero
        // triangles, which add nothing.
        let per_body = bodies
            .iter()
            .map(|m| m.triangles.len())
            .max()
            .unwrap_or(0)
            .max(1);
        // A chunk takes up to `chunk` triangles of every body: its corner and term buffers
        // (three vec4 a triangle each) within what one storage buffer holds.
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
        let mut sums = vec![[0f64; 4]; 3 * bodies.len()];
        let mut gpu_ms = 0.0;
        for first in (0..per_body).step_by(chunk) {
            let count = chunk.min(per_body - first);
            let (partial, ms) = self.integrate_chunk(bodies, &frames, first, count)?;
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
            .map(|(body, &(center, scale))| {
                let [l0, l1, l2] = [sums[body], sums[n + body], sums[2 * n + body]];
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
                    origin: center,
                    ..unit.stretched(scale)
                }
            })
            .collect();
        Ok(ComputeResult { integrals, gpu_ms })
    }

    /// Triangles `first .. first + count` of every body through the integrand pass and the
    /// reduction: three sums a body (`[lane * bodies + body]`), and the milliseconds.
    fn integrate_chunk(
        &self,
        bodies: &[&Mesh],
        frames: &[(DVec3, DVec3)],
        first: usize,
        count: usize,
    ) -> Result<(Vec<[f32; 4]>, f64), GlError> {
        let slots = count * bodies.len();
        let mut corners = vec![Vec4::ZERO; 3 * slots];
        for (body, (mesh, &(center, scale))) in bodies.iter().zip(frames).enumerate() {
            let triangles = mesh.triangles.iter().skip(first).take(count);
            for (k, tri) in triangles.enumerate() {
                for (corner, &v) in tri.iter().enumerate() {
                    let p = (mesh.positions[v as usize].as_dvec3() - center) / scale;
                    corners[3 * (body * count + k) + corner] = p.as_vec3().extend(1.0);
                }
            }
        }
        let input = Buffer::from_slice(&self.ctx, &corners, BufferUsage::Static)?;
        let terms = Buffer::new(&self.ctx, 3 * slots * 16, BufferUsage::GpuCopy)?;
        time_finished(&self.ctx, || {
            self.program
                .dispatch("triangle integrals (compute)")
                .storage(0, &input)
                .storage(1, &terms)
                .uniform("u_triangles", slots as u32)
                .run_over_in_chunks(slots as u32, "u_first")?;
            memory_barrier(&self.ctx, &[Barrier::Storage]);
            self.reducer.reduce_segments(
                &terms,
                3 * bodies.len() as u32,
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
    out
}
