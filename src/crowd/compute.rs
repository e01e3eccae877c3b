//! The compute formulation (OpenGL 4.3), "then and now" for section 2: skinning is a compute
//! pass (`glsl/crowd/compute/skin.comp`) that writes every character's vertices into a
//! shader storage buffer, and the drawing pass reads that buffer directly
//! (`glsl/crowd/compute/draw_skinned.vert`), all characters of a LOD in one instanced draw.
//! Gone: the n x m render target and its row-length cap, the copy through a pixel buffer,
//! one vertex array per character, and batching by texture size. The bone matrices are the
//! same rows as Fig. 1-(b), in a storage buffer instead of three textures.

use glam::DAffine3;
use std::time::Instant;

use super::bone_textures::matrix_row;
use super::character::{CharacterModel, Instances};
use super::culling::{plan_frame, Camera, FramePlan};
use super::pass2_draw::{scene_state, Shading};
use super::render_to_vbo::SkinnedColumn;
use super::renderer::{colour_of, FrameStats};
use super::scene::{clear, placements, RunStats, Scene};
use super::validate::SkinnedMesh;
use crate::gl::{
    ensure_finite, memory_barrier, time_finished, Barrier, Buffer, BufferUsage, ComputeProgram,
    Context, Framebuffer, GlError, Primitive, Program, VertexArray,
};
use crate::shader;

/// The name of the skinning pass (errors name it).
pub const COMPUTE_SKINNING_PASS: &str = "crowd compute skinning";

/// One LOD mesh: its bind-pose vertices, its index buffer, and the skinned output.
struct ComputeLod {
    vertices: u32,
    index_count: usize,
    triangles: usize,
    mesh: Buffer,
    indices: VertexArray,
    /// Two `vec4` per skinned vertex, `capacity` characters.
    skinned: Buffer,
    bone_rows: Buffer,
    capacity: usize,
}

/// Skins and draws crowds of one model with compute passes.
pub struct ComputeCrowd {
    ctx: Context,
    pub model: CharacterModel,
    skin: ComputeProgram,
    draw: Program,
    lods: Vec<ComputeLod>,
    shading_colour: glam::Vec3,
    light: glam::Vec3,
}

/// The bind-pose vertex as the shader's `BindVertex`: position, normal, bones, weights.
fn bind_vertices(mesh: &SkinnedMesh) -> Vec<[u32; 16]> {
    (0..mesh.vertex_count())
        .map(|v| {
            let (p, n) = (mesh.mesh.positions[v], mesh.normals[v]);
            let w = mesh.bone_weights[v];
            let f = [p.x, p.y, p.z, 1.0, n.x, n.y, n.z, 0.0].map(f32::to_bits);
            let b = mesh.bone_indices[v];
            [
                f[0],
                f[1],
                f[2],
                f[3],
                f[4],
                f[5],
                f[6],
                f[7],
                b[0],
                b[1],
                b[2],
                b[3],
                w[0].to_bits(),
                w[1].to_bits(),
                w[2].to_bits(),
                w[3].to_bits(),
            ]
        })
        .collect()
}

impl ComputeCrowd {
    /// On a context below OpenGL 4.3, the error naming it.
    pub fn new(ctx: &Context, model: CharacterModel) -> Result<Self, GlError> {
        ctx.require_compute("the compute formulation of paper 2")?;
        let lods = model
            .lods
            .iter()
            .map(|mesh| {
                let index_buffer =
                    Buffer::from_slice(ctx, &mesh.mesh.triangles, BufferUsage::Static)?;
                let mut indices = VertexArray::new(ctx)?;
                indices.set_index_buffer(&index_buffer)?;
                Ok(ComputeLod {
                    vertices: mesh.vertex_count() as u32,
                    index_count: mesh.triangle_count() * 3,
                    triangles: mesh.triangle_count(),
                    mesh: Buffer::from_slice(ctx, &bind_vertices(mesh), BufferUsage::Static)?,
                    indices,
                    skinned: Buffer::new(ctx, 32, BufferUsage::GpuCopy)?,
                    bone_rows: Buffer::new(ctx, 16, BufferUsage::Dynamic)?,
                    capacity: 0,
                })
            })
            .collect::<Result<Vec<_>, GlError>>()?;
        Ok(Self {
            ctx: ctx.clone(),
            skin: ComputeProgram::new(ctx, &[shader!("glsl/crowd/compute/skin.comp")])?,
            draw: Program::new(
                ctx,
                &[shader!("glsl/crowd/compute/draw_skinned.vert")],
                &[shader!("glsl/crowd/shade.frag")],
            )?,
            shading_colour: colour_of(model.kind),
            light: glam::Vec3::new(0.4, 0.8, 0.45).normalize(),
            model,
            lods,
        })
    }

    /// Upload the bone rows of `n` characters (CPU to GPU), growing the buffers if needed.
    fn upload(&mut self, lod: usize, matrices: &[DAffine3], n: usize) -> Result<(), GlError> {
        let ctx = self.ctx.clone();
        let resources = &mut self.lods[lod];
        if n > resources.capacity {
            resources.capacity = n.next_power_of_two();
            resources.skinned = Buffer::new(
                &ctx,
                resources.capacity * resources.vertices as usize * 32,
                BufferUsage::GpuCopy,
            )?;
        }
        let rows: Vec<[f32; 4]> = matrices
            .iter()
            .flat_map(|m| [0, 1, 2].map(|r| matrix_row(m, r)))
            .collect();
        resources.bone_rows.replace(&rows)
    }

    /// The compute pass: skin `n` characters of LOD `lod` into its storage buffer.
    fn skin_pass(&self, lod: usize, n: usize) -> Result<(), GlError> {
        let resources = &self.lods[lod];
        let [gx, _, _] = self.skin.local_size();
        self.skin
            .dispatch(COMPUTE_SKINNING_PASS)
            .storage(0, &resources.mesh)
            .storage(1, &resources.bone_rows)
            .storage(2, &resources.skinned)
            .uniform("u_vertices", resources.vertices)
            .uniform("u_bones", self.model.bone_count() as u32)
            .uniform("u_characters", n as u32)
            .run([resources.vertices.div_ceil(gx), n as u32, 1])?;
        memory_barrier(&self.ctx, &[Barrier::Storage, Barrier::BufferUpdate]);
        Ok(())
    }

    /// The drawing pass: `n` characters of LOD `lod`, one instanced draw.
    fn draw_pass(
        &self,
        scene: &Framebuffer,
        shading: &Shading,
        lod: usize,
        n: usize,
    ) -> Result<(), GlError> {
        let resources = &self.lods[lod];
        resources.skinned.bind_storage(2)?;
        let mut pass = scene.pass(&self.draw, "crowd compute draw (from the storage buffer)")?;
        pass.state(scene_state())
            .uniform("u_view_projection", shading.view_projection)
            .uniform("u_vertices", resources.vertices)
            .uniform("u_colour", shading.colour)
            .uniform("u_light", shading.light);
        pass.draw_elements_instanced(
            &resources.indices,
            Primitive::Triangles,
            0,
            resources.index_count,
            n,
        )
    }

    /// Renders one frame into `scene` (cleared by the caller). The times use the classic
    /// names: `pass1` the compute skinning, `pass2` the draw, `copy` zero. Sprites belong to
    /// the classic renderer: a plan with sprites is an error.
    pub fn render(
        &mut self,
        scene: &Framebuffer,
        camera: &Camera,
        instances: &Instances,
        plan: &FramePlan,
        timing: bool,
    ) -> Result<FrameStats, GlError> {
        if !plan.sprites.is_empty() {
            return Err(GlError::Invalid(format!(
                "the compute formulation of paper 2 draws skinned characters only; {} \
                 characters are planned as sprites (turn sprites off, or use the classic \
                 formulation)",
                plan.sprites.len()
            )));
        }
        let mut stats = FrameStats::default();
        let shading = Shading {
            view_projection: camera.view_projection(),
            colour: self.shading_colour,
            light: self.light,
        };
        for lod in 0..self.lods.len() {
            let ids = &plan.lods[lod];
            if ids.is_empty() {
                continue;
            }
            let started = Instant::now();
            let matrices = instances.bone_matrices(&self.model, ids);
            stats.bones_ms += started.elapsed().as_secs_f64() * 1e3;
            let started = Instant::now();
            self.upload(lod, &matrices, ids.len())?;
            stats.upload_ms += started.elapsed().as_secs_f64() * 1e3;
            stats.skinned += ids.len();
            stats.triangles += ids.len() * self.lods[lod].triangles;
            stats.pass1_draws += 1;
            let n = ids.len();
            let (gl, wall) = timed(&self.ctx, timing, || self.skin_pass(lod, n))?;
            stats.gl_timer.pass1 += gl;
            stats.wall.pass1 += wall;
            let (gl, wall) = timed(&self.ctx, timing, || {
                self.draw_pass(scene, &shading, lod, n)
            })?;
            stats.gl_timer.pass2 += gl;
            stats.wall.pass2 += wall;
        }
        Ok(stats)
    }

    /// Skins characters `ids` at LOD `lod` and reads the storage buffer back (tests): each
    /// character's positions and normals, xyzw, in the order of `ids`.
    pub fn skin(
        &mut self,
        lod: usize,
        instances: &Instances,
        ids: &[usize],
    ) -> Result<Vec<SkinnedColumn>, GlError> {
        let matrices = instances.bone_matrices(&self.model, ids);
        self.upload(lod, &matrices, ids.len())?;
        self.skin_pass(lod, ids.len())?;
        let m = self.lods[lod].vertices as usize;
        let all: Vec<[f32; 4]> = self.lods[lod].skinned.read_prefix(2 * m * ids.len())?;
        let what = format!(
            "crowd: the skinned vertices of {} {:?} characters at LOD {lod} (compute)",
            ids.len(),
            self.model.kind
        );
        ensure_finite(all.iter().flatten().copied(), &what, COMPUTE_SKINNING_PASS)?;
        Ok(all
            .chunks_exact(2 * m)
            .map(|c| {
                let positions = c.iter().step_by(2).copied().collect();
                let normals = c.iter().skip(1).step_by(2).copied().collect();
                (positions, normals)
            })
            .collect())
    }
}

/// Runs `work`; when `timing`, between `glFinish` calls ([`time_finished`]: llvmpipe's
/// timer queries do not see compute passes): (wall-clock ms, wall-clock ms), else (0, 0).
fn timed(
    ctx: &Context,
    timing: bool,
    work: impl FnOnce() -> Result<(), GlError>,
) -> Result<(f64, f64), GlError> {
    if !timing {
        return work().map(|()| (0.0, 0.0));
    }
    let ((), ms) = time_finished(ctx, work)?;
    Ok((ms, ms))
}

/// Plans and renders one frame with the compute formulation (the scene cleared first).
pub fn render_frame(
    crowd: &mut ComputeCrowd,
    target: &Framebuffer,
    scene: &Scene,
    timing: bool,
) -> Result<(FrameStats, FramePlan), GlError> {
    let (models, phases) = placements(&scene.crowd);
    let plan = plan_frame(
        &models,
        crowd.model.bound_centre,
        crowd.model.bound_radius,
        &scene.camera,
        scene.lod.as_ref(),
        scene.cull,
    );
    let instances = Instances {
        models: &models,
        phases: &phases,
    };
    clear(target)?;
    let stats = crowd.render(target, &scene.camera, &instances, &plan, timing)?;
    Ok((stats, plan))
}

/// As [`super::scene::run`] for the compute formulation: one warm-up frame, `frames`
/// wall-clock-timed frames (median) and one frame with per-stage timing.
pub fn run(
    ctx: &Context,
    crowd: &mut ComputeCrowd,
    target: &Framebuffer,
    scene: &mut Scene,
    frames: usize,
    dt: f32,
) -> Result<RunStats, GlError> {
    let stride = crowd.model.clip.stride;
    render_frame(crowd, target, scene, false)?;
    ctx.finish_all();
    let mut times = Vec::with_capacity(frames);
    for _ in 0..frames {
        scene.crowd.step(dt, stride);
        let started = Instant::now();
        render_frame(crowd, target, scene, false)?;
        ctx.finish_all();
        times.push(started.elapsed().as_secs_f64() * 1e3);
    }
    scene.crowd.step(dt, stride);
    let (passes, plan) = render_frame(crowd, target, scene, true)?;
    ctx.finish_all();
    let frame_ms = super::scene::median(&mut times);
    Ok(RunStats {
        frame_ms_range: super::scene::range(&times),
        model: crowd.model.kind.name().to_string(),
        method: "compute".to_string(),
        vertex_shader_batch: 0,
        characters: scene.crowd.agents.len(),
        lod_and_culling: scene.lod.is_some(),
        sprites_enabled: false,
        frames,
        frame_ms,
        fps: 1e3 / frame_ms,
        passes,
        culled: plan.culled,
        per_lod: [0, 1, 2].map(|l| plan.lods[l].len()),
    })
}
