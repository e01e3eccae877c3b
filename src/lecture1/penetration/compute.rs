//! The compute formulation (OpenGL 4.3), "then and now" for the closest-point query: one
//! invocation per pixel ray of the same cube layout walks every sum along its ray until none
//! raises T (`glsl/lecture1/penetration_rays.comp`), with the same interval code as the
//! fragment pass. No rasterization, no ping-pong, no occlusion queries: the loop that the
//! classic path spreads over passes runs inside each invocation. T comes back whole and its
//! minimum is taken on the CPU.

use super::cube_map::{faces, NEAR};
use super::minkowski::Polytope;
use crate::gl::{
    memory_barrier, time_finished, Barrier, Buffer, BufferUsage, ComputeProgram, Context, GlError,
};
use crate::shader;
use glam::Vec4;

/// The compute program.
pub struct ComputeRays {
    ctx: Context,
    program: ComputeProgram,
}

impl ComputeRays {
    /// On a context below OpenGL 4.3, the error naming it.
    pub fn new(ctx: &Context) -> Result<ComputeRays, GlError> {
        ctx.require_compute("the compute formulation of the penetration-depth query")?;
        Ok(ComputeRays {
            ctx: ctx.clone(),
            program: ComputeProgram::new(
                ctx,
                &[
                    shader!("glsl/lecture1/penetration_ray.glsl"),
                    shader!("glsl/lecture1/penetration_rays.comp"),
                ],
            )?,
        })
    }

    /// T of every pixel (`6N x N`, row-major from the bottom) for `sums` in the unit frame,
    /// and the wall time between `glFinish` calls, ms.
    pub fn exits(&self, sums: &[Polytope], resolution: usize) -> Result<(Vec<f32>, f64), GlError> {
        let mut planes: Vec<Vec4> = Vec::new();
        let mut ranges: Vec<[i32; 2]> = Vec::new();
        for sum in sums {
            ranges.push([planes.len() as i32, sum.planes.len() as i32]);
            planes.extend(
                sum.planes
                    .iter()
                    .map(|p| p.normal.as_vec3().extend(p.offset as f32)),
            );
        }
        // Storage buffers may not be empty.
        planes.push(Vec4::ZERO);
        ranges.push([0, 0]);
        let pixels = 6 * resolution * resolution;
        let plane_buffer = Buffer::from_slice(&self.ctx, &planes, BufferUsage::Static)?;
        let sum_buffer = Buffer::from_slice(&self.ctx, &ranges, BufferUsage::Static)?;
        let exits = Buffer::new(&self.ctx, 4 * pixels, BufferUsage::GpuCopy)?;
        let faces = faces();
        let column = |pick: &dyn Fn(&super::cube_map::Face) -> glam::DVec3| -> Vec<Vec4> {
            faces
                .iter()
                .map(|f| pick(f).as_vec3().extend(0.0))
                .collect()
        };
        let (right, up, forward) = (
            column(&|f| f.right),
            column(&|f| f.up),
            column(&|f| f.forward),
        );
        let ((), ms) = time_finished(&self.ctx, || {
            self.program
                .dispatch("penetration rays (compute)")
                .storage(0, &plane_buffer)
                .storage(1, &sum_buffer)
                .storage(2, &exits)
                .uniform("u_sums", sums.len() as i32)
                .uniform("u_resolution", resolution as i32)
                .uniform("u_near", NEAR)
                .uniform("u_right", right.as_slice())
                .uniform("u_up", up.as_slice())
                .uniform("u_forward", forward.as_slice())
                .run_over_in_chunks(pixels as u32, "u_first")?;
            memory_barrier(&self.ctx, &[Barrier::BufferUpdate]);
            Ok(())
        })?;
        Ok((exits.read_prefix::<f32>(pixels)?, ms))
    }
}
