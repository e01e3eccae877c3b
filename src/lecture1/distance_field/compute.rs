//! The compute counterpart (OpenGL 4.3, "then and now"): one invocation per voxel over every
//! triangle (`glsl/lecture1/compute/distance_field.comp`), the field written into a storage
//! buffer and read back once. No render target, no rectangles, no blending.

use super::{check_input, corners_in_voxels, DistanceField, FieldTimings, Grid};
use crate::gl::{time_finished, Buffer, BufferUsage, ComputeProgram, Context};
use crate::mesh::Mesh;
use crate::shader;
use std::time::Instant;

/// The compute program of one context (OpenGL 4.3 or later).
pub struct ComputeField {
    ctx: Context,
    program: ComputeProgram,
}

impl ComputeField {
    /// The compute formulation; a clear error on a context older than 4.3.
    pub fn new(ctx: &Context) -> anyhow::Result<ComputeField> {
        ctx.require_compute("the compute distance field")?;
        Ok(ComputeField {
            ctx: ctx.clone(),
            program: ComputeProgram::new(
                ctx,
                &[
                    shader!("glsl/lecture1/point_triangle.glsl"),
                    shader!("glsl/lecture1/compute/distance_field.comp"),
                ],
            )?,
        })
    }

    /// The field of `mesh` on `grid` (see [`super::slices::SliceRasterizer::field`]).
    pub fn field(
        &self,
        mesh: &Mesh,
        grid: &Grid,
        clamp: Option<f64>,
    ) -> anyhow::Result<(DistanceField, FieldTimings)> {
        check_input(mesh, clamp)?;
        let voxels = grid.len();
        anyhow::ensure!(
            voxels < u32::MAX as usize,
            "{voxels} voxels: the compute field counts voxels in 32 bits"
        );
        let mut timings = FieldTimings::default();
        let start = Instant::now();
        let corners = Buffer::from_slice(
            &self.ctx,
            &corners_in_voxels(mesh, grid),
            BufferUsage::Static,
        )?;
        let field = Buffer::new(&self.ctx, 4 * voxels, BufferUsage::GpuCopy)?;
        timings.upload_ms = start.elapsed().as_secs_f64() * 1e3;
        let ((), ms) = time_finished(&self.ctx, || {
            self.program
                .dispatch("distance field (compute)")
                .storage(0, &corners)
                .storage(1, &field)
                .uniform("u_n", grid.n as u32)
                .uniform("u_triangles", mesh.triangles.len() as u32)
                .uniform("u_spacing", grid.spacing as f32)
                .uniform("u_clamp", clamp.map_or(f32::MAX, |d| d as f32))
                .run_over_in_chunks(voxels as u32, "u_first")
        })?;
        timings.passes_ms = ms;
        timings.triangles_drawn = (mesh.triangles.len() * voxels) as u64;
        let start = Instant::now();
        crate::gl::memory_barrier(&self.ctx, &[crate::gl::Barrier::BufferUpdate]);
        let values: Vec<f32> = field.read()?;
        timings.readback_ms = start.elapsed().as_secs_f64() * 1e3;
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            anyhow::bail!(
                "the compute field gave {} at voxel {i}; a distance must be finite",
                values[i]
            );
        }
        Ok((
            DistanceField {
                grid: *grid,
                values,
                clamp,
            },
            timings,
        ))
    }
}
