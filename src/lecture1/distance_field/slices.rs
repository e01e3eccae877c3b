//! The classic formulation (OpenGL 3.3): the field slice by slice, one R32F render target per
//! z slice (a reconstruction in DiFi's style).
//!
//! Per slice: clear the target to the clamp (or the largest float), then one instanced draw of
//! every triangle's rectangle (`glsl/lecture1/distance_slice.vert`: the triangle's screen box
//! grown by what the clamp still allows at this slice's height, nothing when the triangle is
//! out of reach, the whole slice without a clamp); each fragment writes its exact distance to
//! that triangle (`distance_slice.frag`) and GL_MIN blending keeps the nearest. The slice is
//! then read back with glReadPixels.

use super::{check_input, corners_in_voxels, DistanceField, FieldTimings, Grid};
use crate::gl::{
    query::time_gpu, Blend, Context, DrawState, Framebuffer, GlError, Primitive, Program, Rect,
    Texture, TextureFormat,
};
use crate::mesh::Mesh;
use crate::shader;
use glam::Vec2;
use std::time::Instant;

/// The slice programs of one context.
pub struct SliceRasterizer {
    ctx: Context,
    program: Program,
}

impl SliceRasterizer {
    pub fn new(ctx: &Context) -> Result<SliceRasterizer, GlError> {
        Ok(SliceRasterizer {
            ctx: ctx.clone(),
            program: Program::new(
                ctx,
                &[shader!("glsl/lecture1/distance_slice.vert")],
                &[
                    shader!("glsl/lecture1/point_triangle.glsl"),
                    shader!("glsl/lecture1/distance_slice.frag"),
                ],
            )?,
        })
    }

    /// The field of `mesh` on `grid`, `min(distance, clamp)` with a clamp (mesh units), and
    /// where the time went.
    pub fn field(
        &self,
        mesh: &Mesh,
        grid: &Grid,
        clamp: Option<f64>,
    ) -> anyhow::Result<(DistanceField, FieldTimings)> {
        check_input(mesh, clamp)?;
        let n = grid.n;
        let limits = &self.ctx.info().limits;
        let side = (limits.max_texture_size as usize)
            .min(limits.max_viewport_dims[0] as usize)
            .min(limits.max_viewport_dims[1] as usize);
        anyhow::ensure!(
            n <= side,
            "a resolution of {n} needs {n} x {n} slices; this renderer allows {side} x {side}"
        );
        let mut timings = FieldTimings::default();
        let start = Instant::now();
        let triangles = TriangleTexture::new(&self.ctx, mesh, grid)?;
        timings.upload_ms = start.elapsed().as_secs_f64() * 1e3;
        let target = Texture::new_2d(&self.ctx, n as u32, n as u32, TextureFormat::R32F)?;
        let framebuffer = Framebuffer::new(&self.ctx, "distance slice", &[&target], None)?;
        let clear = clamp.map_or(f32::MAX, |d| d as f32);
        let bound = clamp.map_or(-1.0, |d| (d / grid.spacing) as f32);
        let mut values = Vec::with_capacity(grid.len());
        for z in 0..n {
            let (_, ms) = time_gpu(&self.ctx, || {
                framebuffer.clear_color(0, [clear; 4])?;
                let mut pass = framebuffer.pass(&self.program, "distance slice")?;
                pass.state(DrawState {
                    blend: Some(Blend::Min),
                    ..DrawState::default()
                })
                .texture("u_triangles", &triangles.texture)
                .uniform("u_per_row", triangles.per_row as i32)
                .uniform("u_slice", z as f32)
                .uniform("u_bound", bound)
                .uniform("u_size", Vec2::splat(n as f32))
                .uniform("u_spacing", grid.spacing as f32);
                pass.draw_attributeless(Primitive::TriangleStrip, 4, triangles.count)
            })?;
            timings.passes_ms += ms;
            timings.triangles_drawn += triangles.reaching(z as f32, bound);
            let start = Instant::now();
            values.extend(framebuffer.read_f32(0, Rect::sized(n as u32, n as u32))?);
            timings.readback_ms += start.elapsed().as_secs_f64() * 1e3;
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            anyhow::bail!(
                "the distance slices gave {} at voxel {i}; a distance must be finite",
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

/// The triangles as texels in voxel units: triangle `t` is texels `3 (t % per_row) + c` of
/// row `t / per_row`, `c = 0..3`.
struct TriangleTexture {
    texture: Texture,
    per_row: usize,
    count: usize,
    /// Each triangle's z range, voxel units (to count the rectangles a slice draws).
    z_ranges: Vec<(f32, f32)>,
}

impl TriangleTexture {
    fn new(ctx: &Context, mesh: &Mesh, grid: &Grid) -> anyhow::Result<TriangleTexture> {
        let corners = corners_in_voxels(mesh, grid);
        let count = mesh.triangles.len();
        let limit = ctx.info().limits.max_texture_size as usize;
        let per_row = count.min(limit / 3).max(1);
        let rows = count.div_ceil(per_row);
        anyhow::ensure!(
            rows <= limit,
            "{count} triangles need a {} x {rows} texture, larger than this renderer's \
             {limit} x {limit}",
            3 * per_row
        );
        let mut texels = vec![0.0f32; 4 * 3 * per_row * rows];
        for (t, three) in corners.chunks(3).enumerate() {
            for (c, corner) in three.iter().enumerate() {
                let at = 4 * ((t / per_row) * 3 * per_row + 3 * (t % per_row) + c);
                texels[at..at + 4].copy_from_slice(corner);
            }
        }
        let z_ranges = corners
            .chunks(3)
            .map(|c| {
                let z = [c[0][2], c[1][2], c[2][2]];
                (z[0].min(z[1]).min(z[2]), z[0].max(z[1]).max(z[2]))
            })
            .collect();
        Ok(TriangleTexture {
            texture: Texture::from_f32(
                ctx,
                (3 * per_row) as u32,
                rows as u32,
                TextureFormat::Rgba32F,
                &texels,
            )?,
            per_row,
            count,
            z_ranges,
        })
    }

    /// The triangles whose rectangle the vertex shader draws at slice `z` (all without a
    /// bound).
    fn reaching(&self, z: f32, bound: f32) -> u64 {
        if bound < 0.0 {
            return self.count as u64;
        }
        self.z_ranges
            .iter()
            .filter(|&&(lo, hi)| (lo - z).max(z - hi).max(0.0) <= bound)
            .count() as u64
    }
}
