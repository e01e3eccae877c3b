//! Step 3b, "rasterization hardware runs a closest-point query on the union of those sums"
//! (OpenGL 3.3; the pass structure is a reconstruction). Per pixel ray of the cube layout,
//! T is where the ray leaves the union, T₀ = 0. Each pass copies T into the other target of a
//! ping-pong pair and draws the back faces of every sum into it, through all six views, with
//! MAX blending; the fragment stage (`glsl/lecture1/penetration_exit.frag`) computes its sum's
//! entry and exit on the pixel's ray from the sum's planes (an RGBA32F plane texture) and
//! writes the exit when the entry lies within the previous T and the exit beyond it. An
//! occlusion query around the pass counts the pixels raised; a pass that raises none ends
//! the query.

use super::cube_map::faces;
use super::minkowski::Polytope;
use crate::gl::{
    query::time_gpu, AttribType, Blend, Buffer, BufferUsage, Context, DrawState, Face, Framebuffer,
    GlError, OcclusionQuery, Primitive, Program, Rect, Texture, TextureFormat, VertexArray,
};
use crate::shader;

/// The sums as the GPU reads them: their triangles (unit frame) with each vertex's plane
/// range, and the plane texture.
pub struct SumBuffers {
    pub vertices: VertexArray,
    pub vertex_count: usize,
    pub planes: Texture,
    pub planes_per_row: usize,
    pub sums: usize,
}

impl SumBuffers {
    /// `sums` in the unit frame (coordinates within [-1, 1]).
    pub fn new(ctx: &Context, sums: &[Polytope]) -> Result<SumBuffers, GlError> {
        let mut positions: Vec<[f32; 3]> = Vec::new();
        let mut ranges: Vec<[i32; 2]> = Vec::new();
        let mut planes: Vec<f32> = Vec::new();
        for sum in sums {
            let range = [(planes.len() / 4) as i32, sum.planes.len() as i32];
            for p in &sum.planes {
                planes.extend([
                    p.normal.x as f32,
                    p.normal.y as f32,
                    p.normal.z as f32,
                    p.offset as f32,
                ]);
            }
            for tri in &sum.triangles {
                for &v in tri {
                    positions.push(sum.vertices[v as usize].as_vec3().to_array());
                    ranges.push(range);
                }
            }
        }
        let count = (planes.len() / 4).max(1);
        let limit = ctx.info().limits.max_texture_size as usize;
        let per_row = count.min(limit);
        let rows = count.div_ceil(per_row);
        if rows > limit {
            return Err(GlError::Limit(format!(
                "{count} planes of Minkowski sums do not fit a {limit} x {limit} texture"
            )));
        }
        planes.resize(4 * per_row * rows, 0.0);
        let texture = Texture::from_f32(
            ctx,
            per_row as u32,
            rows as u32,
            TextureFormat::Rgba32F,
            &planes,
        )?;
        let mut vertices = VertexArray::new(ctx)?;
        if !positions.is_empty() {
            let position_buffer = Buffer::from_slice(ctx, &positions, BufferUsage::Static)?;
            let range_buffer = Buffer::from_slice(ctx, &ranges, BufferUsage::Static)?;
            vertices.float_attribute(0, &position_buffer, 3, 12, 0, 0)?;
            vertices.attribute(1, &range_buffer, 2, AttribType::I32, 8, 0, 0)?;
        }
        Ok(SumBuffers {
            vertices,
            vertex_count: positions.len(),
            planes: texture,
            planes_per_row: per_row,
            sums: sums.len(),
        })
    }
}

/// The two T targets (`6N x N`, R32F) of the ping-pong.
pub struct ExitTargets {
    pub targets: [Framebuffer; 2],
    pub resolution: usize,
}

impl ExitTargets {
    pub fn new(ctx: &Context, resolution: usize) -> Result<ExitTargets, GlError> {
        let limits = &ctx.info().limits;
        let widest = (limits.max_texture_size as usize)
            .min(limits.max_viewport_dims[0] as usize)
            .min(limits.max_viewport_dims[1] as usize);
        if resolution == 0 || 6 * resolution > widest {
            return Err(GlError::Limit(format!(
                "a cube resolution of {resolution} needs a {} x {resolution} target; this \
                 renderer allows 1 to {} per face",
                6 * resolution,
                widest / 6
            )));
        }
        let target = |name| -> Result<Framebuffer, GlError> {
            let t = Texture::new_2d(
                ctx,
                6 * resolution as u32,
                resolution as u32,
                TextureFormat::R32F,
            )?;
            Framebuffer::new(ctx, name, &[&t], None)
        };
        Ok(ExitTargets {
            targets: [target("exit T ping")?, target("exit T pong")?],
            resolution,
        })
    }
}

/// What the passes did.
#[derive(Clone, Copy, Debug, Default)]
pub struct PassStats {
    /// Passes drawn (the last one raised no pixel).
    pub passes: usize,
    /// Pixels raised, all passes together (the occlusion queries' counts).
    pub raised: u64,
    /// GPU time of the passes (timer queries), ms.
    pub gpu_ms: f64,
}

/// The exit program and its occlusion query.
pub struct ExitPasses {
    program: Program,
    query: OcclusionQuery,
}

impl ExitPasses {
    pub fn new(ctx: &Context) -> Result<ExitPasses, GlError> {
        Ok(ExitPasses {
            program: Program::new(
                ctx,
                &[shader!("glsl/lecture1/penetration_back_faces.vert")],
                &[
                    shader!("glsl/lecture1/penetration_ray.glsl"),
                    shader!("glsl/lecture1/penetration_exit.frag"),
                ],
            )?,
            query: OcclusionQuery::new(ctx)?,
        })
    }

    /// Run passes until one raises no pixel (at most one per sum, plus that last one: each
    /// sum raises a ray at most once). Returns which target holds the final T.
    pub fn run(
        &self,
        sums: &SumBuffers,
        targets: &ExitTargets,
    ) -> Result<(usize, PassStats), GlError> {
        let mut stats = PassStats::default();
        targets.targets[0].clear_color(0, [0.0; 4])?;
        let mut current = 0;
        let most = sums.sums + 1;
        loop {
            if stats.passes >= most {
                return Err(GlError::Invalid(format!(
                    "the exit passes did not settle after {most} passes (one per Minkowski \
                     sum and one more)"
                )));
            }
            let (from, to) = (&targets.targets[current], &targets.targets[1 - current]);
            let (raised, ms) = time_gpu(from.context(), || self.pass(sums, from, to, targets))?;
            stats.passes += 1;
            stats.raised += raised;
            stats.gpu_ms += ms;
            current = 1 - current;
            if raised == 0 {
                return Ok((current, stats));
            }
        }
    }

    /// One pass: T_prev from `from`, copied into `to`, raised there; the pixels raised.
    fn pass(
        &self,
        sums: &SumBuffers,
        from: &Framebuffer,
        to: &Framebuffer,
        targets: &ExitTargets,
    ) -> Result<u64, GlError> {
        to.blit_from(from, from.rect(), to.rect())?;
        if sums.vertex_count == 0 {
            return Ok(0);
        }
        let n = targets.resolution as u32;
        self.query.begin();
        let drawn = faces().iter().enumerate().try_for_each(|(f, face)| {
            let mut pass = to.pass(&self.program, "penetration exit pass")?;
            pass.viewport(Rect::new(f as u32 * n, 0, n, n))
                // Back faces only: seen from the origin, a sum's far side.
                .state(DrawState {
                    blend: Some(Blend::Max),
                    cull: Some(Face::Front),
                    ..DrawState::default()
                })
                .texture("u_planes", &sums.planes)
                .texture("u_previous", from.color(0))
                .uniform("u_planes_per_row", sums.planes_per_row as i32)
                .uniform("u_view_projection", face.view_projection())
                .uniform("u_face", face.basis())
                .uniform("u_face_index", f as i32)
                .uniform("u_resolution", n as f32);
            pass.draw_arrays(&sums.vertices, Primitive::Triangles, 0, sums.vertex_count)
        });
        self.query.end();
        drawn?;
        self.query.samples()
    }
}
