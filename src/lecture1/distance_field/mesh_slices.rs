//! Hoff et al.'s method on the GPU (OpenGL 3.3), one z slice at a time: build the slice's
//! distance meshes ([`super::meshes`]), draw them all into an R32F target with a 32-bit float
//! depth buffer (LESS: the nearest feature's mesh wins, its interpolated distance in the
//! colour), read the slice back. The method `mesh` of `lecture1 distance-field`, beside the
//! exact per-fragment slices ([`super::slices`]).

use super::meshes::Features;
use super::{check_input, DistanceField, FieldTimings, Grid};
use crate::gl::{
    query::time_gpu, Buffer, BufferUsage, Compare, Context, DepthTest, DrawState, Framebuffer,
    GlError, Primitive, Program, Rect, Texture, TextureFormat, VertexArray,
};
use crate::lecture1::voronoi::coverage_error;
use crate::mesh::Mesh;
use crate::shader;
use std::time::Instant;

/// What the meshes promise of a field: every value is within
/// `[d - coverage, d + bound + coverage]` voxels of the exact distance `d` (or of the clamp).
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct MeshBound {
    /// The asked tessellation error, voxels.
    pub asked_voxels: f64,
    /// The largest tessellation bound of any feature drawn, voxels (at most the asked).
    pub tessellation_voxels: f64,
    /// How far a pixel centre the rasterizer counts inside a triangle it lies outside of
    /// may read the triangle's plane extended, voxels ([`coverage_error`]).
    pub coverage_voxels: f64,
    /// Vertices, edges and faces drawn per slice.
    pub features: [usize; 3],
}

impl MeshBound {
    /// How far below and above the exact field a value may be, voxels, with fp32 rounding
    /// of the interpolated distance (`2^-18` of the deepest value, `deepest` voxels).
    pub fn tolerance(&self, deepest: f64) -> (f64, f64) {
        let rounding = deepest * 2f64.powi(-18) + 1e-5;
        (
            self.coverage_voxels + rounding,
            self.tessellation_voxels + self.coverage_voxels + rounding,
        )
    }

    /// The meshes' field `meshes` against the exact field `exact` on the same grid, in voxels,
    /// with what this bound allows there.
    pub fn compare(&self, meshes: &DistanceField, exact: &DistanceField) -> MeshError {
        let h = exact.grid.spacing;
        let diffs: Vec<f64> = meshes
            .values
            .iter()
            .zip(&exact.values)
            .map(|(&m, &e)| (m as f64 - e as f64) / h)
            .collect();
        let deepest = exact.values.iter().fold(0.0f64, |a, &v| a.max(v as f64)) / h;
        MeshError {
            lowest: diffs.iter().copied().fold(f64::INFINITY, f64::min),
            highest: diffs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            mean: diffs.iter().map(|d| d.abs()).sum::<f64>() / diffs.len().max(1) as f64,
            tolerance: self.tolerance(deepest),
        }
    }
}

/// The distance meshes' field against the exact field, in voxels ([`MeshBound::compare`]).
#[derive(Clone, Copy, Debug)]
pub struct MeshError {
    /// The lowest and highest `mesh - exact`.
    pub lowest: f64,
    pub highest: f64,
    /// The mean `|mesh - exact|`.
    pub mean: f64,
    /// How far below and above the exact field the bound allows ([`MeshBound::tolerance`]).
    pub tolerance: (f64, f64),
}

impl MeshError {
    /// The largest `|mesh - exact|`.
    pub fn max(&self) -> f64 {
        self.lowest.abs().max(self.highest.abs())
    }

    /// Whether every value kept within the bound.
    pub fn within(&self) -> bool {
        self.lowest >= -self.tolerance.0 && self.highest <= self.tolerance.1
    }
}

/// The mesh program of one context.
pub struct MeshSlices {
    ctx: Context,
    program: Program,
}

impl MeshSlices {
    pub fn new(ctx: &Context) -> Result<MeshSlices, GlError> {
        Ok(MeshSlices {
            ctx: ctx.clone(),
            program: Program::new(
                ctx,
                &[shader!("glsl/lecture1/distance_mesh.vert")],
                &[shader!("glsl/lecture1/distance_mesh.frag")],
            )?,
        })
    }

    /// The field of `mesh` on `grid` by distance meshes within `error_voxels`,
    /// `min(distance, clamp)` with a clamp (mesh units); where the time went (`upload_ms`
    /// holds building the meshes and uploading them, `triangles_drawn` their triangles); and
    /// the bound the meshes keep.
    pub fn field(
        &self,
        mesh: &Mesh,
        grid: &Grid,
        clamp: Option<f64>,
        error_voxels: f64,
    ) -> anyhow::Result<(DistanceField, FieldTimings, MeshBound)> {
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
        let features = Features::new(mesh, grid, error_voxels)?;
        let clamp_voxels = clamp.map(|d| d / grid.spacing);
        let colour = Texture::new_2d(&self.ctx, n as u32, n as u32, TextureFormat::R32F)?;
        let depth = Texture::new_2d(&self.ctx, n as u32, n as u32, TextureFormat::Depth32F)?;
        let framebuffer = Framebuffer::new(&self.ctx, "distance meshes", &[&colour], Some(&depth))?;
        let mut timings = FieldTimings::default();
        let mut bound = MeshBound {
            asked_voxels: error_voxels,
            coverage_voxels: coverage_error(self.ctx.subpixel_bits(), 1.0),
            features: features.counts(),
            ..MeshBound::default()
        };
        let mut values = Vec::with_capacity(grid.len());
        for z in 0..n {
            let start = Instant::now();
            let slice = features.slice(z as f64, clamp_voxels)?;
            bound.tessellation_voxels = bound.tessellation_voxels.max(slice.bound);
            let count = slice.vertices.len();
            let vertices = match count {
                0 => None,
                _ => Some(vertex_array(&self.ctx, &slice.vertices)?),
            };
            timings.upload_ms += start.elapsed().as_secs_f64() * 1e3;
            timings.triangles_drawn += (count / 3) as u64;
            // The deepest vertex stays below the cleared depth 1.
            let depth_scale = 1.0 / (slice.deepest.max(1.0) * (1.0 + 1e-6));
            let ((), ms) = time_gpu(&self.ctx, || {
                framebuffer.clear_color(0, [f32::MAX; 4])?;
                framebuffer.clear_depth_stencil(1.0, 0)?;
                let Some(vertices) = &vertices else {
                    return Ok(());
                };
                let mut pass = framebuffer.pass(&self.program, "distance meshes")?;
                pass.state(DrawState {
                    depth: Some(DepthTest {
                        func: Compare::Less,
                        write: true,
                    }),
                    ..DrawState::default()
                })
                .uniform("u_size", glam::Vec2::splat(n as f32))
                .uniform("u_depth_scale", depth_scale as f32);
                pass.draw_arrays(vertices, Primitive::Triangles, 0, count)
            })?;
            timings.passes_ms += ms;
            let start = Instant::now();
            let slice = framebuffer.read_f32(0, Rect::sized(n as u32, n as u32))?;
            timings.readback_ms += start.elapsed().as_secs_f64() * 1e3;
            for (i, &v) in slice.iter().enumerate() {
                let v = match clamp_voxels {
                    Some(d) => (v as f64).min(d),
                    None => {
                        anyhow::ensure!(
                            v.is_finite() && v < f32::MAX,
                            "voxel ({}, {}, {z}): no distance mesh reached it",
                            i % n,
                            i / n
                        );
                        v as f64
                    }
                };
                values.push((v * grid.spacing) as f32);
            }
        }
        Ok((
            DistanceField {
                grid: *grid,
                values,
                clamp,
            },
            timings,
            bound,
        ))
    }
}

/// The triangles' vertices in a vertex array (attribute 0, four floats).
fn vertex_array(ctx: &Context, vertices: &[[f32; 4]]) -> anyhow::Result<VertexArray> {
    let buffer = Buffer::from_slice(ctx, vertices, BufferUsage::Static)?;
    let mut array = VertexArray::new(ctx)?;
    array.float_attribute(0, &buffer, 4, 16, 0, 0)?;
    Ok(array)
}
