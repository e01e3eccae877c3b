//! One frame of crowd rendering, either method: bone matrices on the CPU (both methods),
//! then pass 1 + render-to-VBO + pass 2 per LOD ("two-pass"), or vertex-shader skinning
//! ("vertex-shader"); sprites for the far field when the plan has them (this project's
//! extension). The paper skins every character in one draw; here a LOD's characters go
//! through pass 1 in batches of at most [`pass1_skinning::max_characters`] (3,712 soldiers
//! at LOD 0 on 16384-texel targets), each batch with its own pass 1, copy and pass 2, so a
//! larger crowd takes several draws ([`FrameStats::pass1_draws`]). Each stage can be timed twice: with a GL
//! timer query, and by wall clock between `glFinish` calls. Both are kept because a
//! software renderer such as llvmpipe runs vertex shaders on the CPU while the draw call
//! is made, outside the span its timer queries measure (they then read ~0 for the
//! vertex-shader method), while on a GPU the timer query is the precise one.

use std::time::Instant;

use glam::{DAffine3, Vec3};
use serde::Serialize;

use crate::gl::{ensure_finite, query, Buffer, BufferUsage, Context, Framebuffer, GlError};

use super::bone_textures::BoneTextures;
use super::character::{CharacterModel, Instances, ModelKind};
use super::culling::{Camera, FramePlan};
use super::pass1_skinning::{self, Pass1, SkinningTarget};
use super::pass2_draw::{CharacterArrays, Pass2, Shading};
use super::render_to_vbo::{SkinnedColumn, SkinnedVbo};
use super::sprites::Sprites;
use super::vertex_shader_skinning::VertexShaderSkinning;
use super::vertex_textures::VertexTextures;

/// The two methods of Table 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// The paper's pixel-shader skinning, render-to-VBO, drawing pass.
    TwoPass,
    /// Skinning in the vertex shader with bone matrices in uniforms.
    VertexShader,
}

impl Method {
    pub const ALL: [Method; 2] = [Method::TwoPass, Method::VertexShader];

    pub fn name(self) -> &'static str {
        match self {
            Method::TwoPass => "two-pass",
            Method::VertexShader => "vertex-shader",
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Method {
    type Err = String;

    /// `two-pass` or `vertex-shader`.
    fn from_str(text: &str) -> Result<Self, String> {
        Method::ALL
            .into_iter()
            .find(|m| m.name() == text)
            .ok_or_else(|| {
                format!("unknown skinning method '{text}' (expected two-pass or vertex-shader)")
            })
    }
}

/// Times of the GPU stages of a frame, in milliseconds.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub struct PassTimes {
    pub pass1: f64,
    pub copy: f64,
    pub pass2: f64,
    pub vertex_shader: f64,
    pub sprites: f64,
}

/// A GPU stage of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stage {
    Pass1,
    Copy,
    Pass2,
    VertexShader,
    Sprites,
}

impl PassTimes {
    fn add(&mut self, stage: Stage, ms: f64) {
        let slot = match stage {
            Stage::Pass1 => &mut self.pass1,
            Stage::Copy => &mut self.copy,
            Stage::Pass2 => &mut self.pass2,
            Stage::VertexShader => &mut self.vertex_shader,
            Stage::Sprites => &mut self.sprites,
        };
        *slot += ms;
    }
}

/// What one frame cost. Stage times are filled only when timing was asked for.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FrameStats {
    /// CPU: animation sampling and bone matrices (both methods).
    pub bones_ms: f64,
    /// CPU: upload of the bone row textures (two-pass; the VS method's uniform uploads are
    /// part of its stage).
    pub upload_ms: f64,
    /// GL timer queries around each stage.
    pub gl_timer: PassTimes,
    /// Wall clock around each stage, with `glFinish` before and after.
    pub wall: PassTimes,
    /// Pass-1 draws (one per batch of each LOD; the paper has one in all).
    pub pass1_draws: usize,
    /// Characters drawn with a skinned mesh, and with a sprite.
    pub skinned: usize,
    pub sprites: usize,
    pub triangles: usize,
}

impl FrameStats {
    fn record(&mut self, stage: Stage, (gl, wall): (f64, f64)) {
        self.gl_timer.add(stage, gl);
        self.wall.add(stage, wall);
    }
}

/// Pass-1 resources for up to `capacity` characters of one LOD.
struct SkinBatch {
    bones: BoneTextures,
    target: SkinningTarget,
    vbo: SkinnedVbo,
    arrays: CharacterArrays,
}

impl SkinBatch {
    fn new(
        ctx: &Context,
        bones: u32,
        vertices: u32,
        capacity: u32,
        indices: &Buffer,
    ) -> Result<Self, GlError> {
        let target = SkinningTarget::new(ctx, capacity, vertices)?;
        let vbo = SkinnedVbo::new(ctx, &target)?;
        let batch = Self {
            bones: BoneTextures::new(ctx, bones, capacity)?,
            arrays: CharacterArrays::new(ctx, &vbo, indices)?,
            target,
            vbo,
        };
        // Written once when made (cleared target, copied into the VBO), so that the first
        // frame using the batch does not pay for touching its memory.
        batch.target.framebuffer.clear_colors([0.0; 4])?;
        batch.vbo.copy_from(&batch.target, capacity)?;
        Ok(batch)
    }
}

/// GPU resources of one LOD mesh.
struct LodResources {
    textures: VertexTextures,
    indices: Buffer,
    index_count: usize,
    triangles: usize,
    batches: Vec<SkinBatch>,
    vertex_shader: VertexShaderSkinning,
}

/// Renders crowds of one model.
pub struct CrowdRenderer {
    ctx: Context,
    pub model: CharacterModel,
    lods: Vec<LodResources>,
    pass1: Pass1,
    pass2: Pass2,
    sprites: Sprites,
    colour: Vec3,
    /// Colour each LOD mesh in its own colour ([`LOD_COLOURS`]) instead of the model's.
    lod_colours: bool,
    light: Vec3,
    /// At most this many characters per pass-1 batch, below what the render target holds.
    batch_limit: Option<usize>,
}

/// Colour of each model.
/// The colours of LOD 0, 1 and 2 when [`CrowdRenderer::set_lod_colours`] is on.
pub const LOD_COLOURS: [Vec3; 3] = [
    Vec3::new(0.9, 0.25, 0.2),
    Vec3::new(0.95, 0.85, 0.25),
    Vec3::new(0.3, 0.8, 0.35),
];

pub(super) fn colour_of(kind: ModelKind) -> Vec3 {
    match kind {
        ModelKind::Soldier => Vec3::new(0.55, 0.6, 0.45),
        ModelKind::Horse => Vec3::new(0.6, 0.42, 0.28),
    }
}

impl CrowdRenderer {
    pub fn new(ctx: &Context, model: CharacterModel) -> Result<Self, GlError> {
        let bones = model.bone_count() as u32;
        let lods = model
            .lods
            .iter()
            .map(|mesh| {
                let indices = Buffer::from_slice(ctx, &mesh.mesh.triangles, BufferUsage::Static)?;
                Ok(LodResources {
                    textures: VertexTextures::upload(ctx, mesh)?,
                    vertex_shader: VertexShaderSkinning::new(ctx, mesh, &indices, bones)?,
                    index_count: mesh.triangle_count() * 3,
                    triangles: mesh.triangle_count(),
                    indices,
                    batches: Vec::new(),
                })
            })
            .collect::<Result<Vec<_>, GlError>>()?;
        let light = Vec3::new(0.4, 0.8, 0.45).normalize();
        let colour = colour_of(model.kind);
        let sprites = Sprites::new(
            ctx,
            &model,
            &lods[lods.len() - 1].vertex_shader,
            colour,
            light,
        )?;
        Ok(Self {
            ctx: ctx.clone(),
            pass1: Pass1::new(ctx)?,
            pass2: Pass2::new(ctx)?,
            sprites,
            model,
            lods,
            colour,
            lod_colours: false,
            light,
            batch_limit: None,
        })
    }

    /// Characters the vertex-shader baseline skins per draw call.
    pub fn vertex_shader_batch(&self) -> u32 {
        self.lods[0].vertex_shader.batch()
    }

    /// Limits the vertex-shader baseline to `batch` characters per draw call (see
    /// [`VertexShaderSkinning::set_batch`]); `u32::MAX` restores the most that fit.
    pub fn set_vertex_shader_batch(&mut self, batch: u32) {
        for lod in &mut self.lods {
            lod.vertex_shader.set_batch(batch);
        }
    }

    /// Draw each LOD mesh in its own colour ([`LOD_COLOURS`]: finest red, then yellow,
    /// coarsest green), to see where the LOD distances fall.
    pub fn set_lod_colours(&mut self, on: bool) {
        self.lod_colours = on;
    }

    /// The impostor atlas (for figures).
    pub fn sprites(&self) -> &Sprites {
        &self.sprites
    }

    /// The pass-1 render target (positions) of LOD `lod`'s first batch, once it exists.
    pub fn render_target(&self, lod: usize) -> Option<&crate::gl::Texture> {
        self.lods[lod]
            .batches
            .first()
            .map(|b| b.target.framebuffer.color(0))
    }

    /// Most characters one pass-1 draw skins for LOD `lod`: what the render target holds,
    /// or less when [`Self::set_batch_limit`] asked for it.
    pub fn batch_limit(&self, lod: usize) -> usize {
        // At least one: a mesh too large for any target then fails with the target's error.
        let fits = (pass1_skinning::max_characters(&self.ctx, self.lods[lod].textures.vertices)
            as usize)
            .max(1);
        self.batch_limit.map_or(fits, |limit| limit.clamp(1, fits))
    }

    /// Skins at most `limit` characters per pass-1 draw (`None`: as many as a render target
    /// holds). Lets tests and demonstrations run the several-batch path of crowds beyond one
    /// target without allocating targets of the largest size.
    pub fn set_batch_limit(&mut self, limit: Option<usize>) {
        if limit != self.batch_limit {
            self.batch_limit = limit;
            for lod in &mut self.lods {
                lod.batches.clear();
            }
        }
    }

    /// Makes sure LOD `lod` has pass-1 batches for `n` characters (capacity grows in powers
    /// of two so a varying count does not rebuild every frame).
    fn reserve(&mut self, lod: usize, n: usize) -> Result<(), GlError> {
        let limit = self.batch_limit(lod);
        let bones = self.model.bone_count() as u32;
        let resources = &mut self.lods[lod];
        let needed = n.div_ceil(limit);
        for b in 0..needed {
            let count = (n - b * limit).min(limit);
            let fits = resources
                .batches
                .get(b)
                .is_some_and(|x| x.target.characters as usize >= count);
            if !fits {
                let capacity = count.next_power_of_two().min(limit) as u32;
                let batch = SkinBatch::new(
                    &self.ctx,
                    bones,
                    resources.textures.vertices,
                    capacity,
                    &resources.indices,
                )?;
                if b < resources.batches.len() {
                    resources.batches[b] = batch;
                } else {
                    resources.batches.push(batch);
                }
            }
        }
        Ok(())
    }

    /// Makes the pass-1 resources the LOD meshes of `plan` need (as [`Self::render`] would
    /// on its first frame), so that a warm-up frame need not draw the whole crowd.
    pub fn prepare(&mut self, plan: &FramePlan) -> Result<(), GlError> {
        for (lod, ids) in plan.lods.iter().enumerate().take(self.lods.len()) {
            if !ids.is_empty() {
                self.reserve(lod, ids.len())?;
            }
        }
        Ok(())
    }

    /// Renders one frame into `scene` (colour + depth, cleared by the caller).
    pub fn render(
        &mut self,
        scene: &Framebuffer,
        camera: &Camera,
        instances: &Instances,
        plan: &FramePlan,
        method: Method,
        timing: bool,
    ) -> Result<FrameStats, GlError> {
        let mut stats = FrameStats::default();
        for lod in 0..self.lods.len() {
            let ids = &plan.lods[lod];
            if ids.is_empty() {
                continue;
            }
            let shading = Shading {
                view_projection: camera.view_projection(),
                colour: if self.lod_colours {
                    LOD_COLOURS[lod % LOD_COLOURS.len()]
                } else {
                    self.colour
                },
                light: self.light,
            };
            let started = Instant::now();
            let matrices = instances.bone_matrices(&self.model, ids);
            stats.bones_ms += started.elapsed().as_secs_f64() * 1e3;
            stats.skinned += ids.len();
            stats.triangles += ids.len() * self.lods[lod].triangles;
            match method {
                Method::TwoPass => self.two_pass(
                    lod,
                    scene,
                    &shading,
                    &matrices,
                    ids.len(),
                    timing,
                    &mut stats,
                )?,
                Method::VertexShader => {
                    let vs = &self.lods[lod].vertex_shader;
                    stats.record(
                        Stage::VertexShader,
                        timed(&self.ctx, timing, || {
                            vs.draw(scene, &shading, &matrices, None)
                        })?,
                    );
                }
            }
        }
        if !plan.sprites.is_empty() {
            stats.sprites = plan.sprites.len();
            let sprites = &self.sprites;
            let model = &self.model;
            stats.record(
                Stage::Sprites,
                timed(&self.ctx, timing, || {
                    sprites.draw(scene, camera, model, instances, &plan.sprites)
                })?,
            );
        }
        Ok(stats)
    }

    /// Pass 1, render-to-VBO and pass 2 for the `n` characters of LOD `lod`.
    #[allow(clippy::too_many_arguments)]
    fn two_pass(
        &mut self,
        lod: usize,
        scene: &Framebuffer,
        shading: &Shading,
        matrices: &[DAffine3],
        n: usize,
        timing: bool,
        stats: &mut FrameStats,
    ) -> Result<(), GlError> {
        self.reserve(lod, n)?;
        let limit = self.batch_limit(lod);
        let bones = self.model.bone_count();
        let resources = &self.lods[lod];
        for (b, batch) in resources.batches.iter().enumerate().take(n.div_ceil(limit)) {
            let first = b * limit;
            let count = (n - first).min(limit);
            stats.pass1_draws += 1;
            let started = Instant::now();
            batch
                .bones
                .upload(&matrices[first * bones..(first + count) * bones])?;
            stats.upload_ms += started.elapsed().as_secs_f64() * 1e3;
            stats.record(
                Stage::Pass1,
                timed(&self.ctx, timing, || {
                    self.pass1.run(
                        &batch.target,
                        &resources.textures,
                        &batch.bones,
                        count as u32,
                    )
                })?,
            );
            stats.record(
                Stage::Copy,
                timed(&self.ctx, timing, || {
                    batch.vbo.copy_from(&batch.target, count as u32)
                })?,
            );
            stats.record(
                Stage::Pass2,
                timed(&self.ctx, timing, || {
                    self.pass2
                        .draw(scene, shading, &batch.arrays, count, resources.index_count)
                })?,
            );
        }
        Ok(())
    }

    /// Runs pass 1 and the copy for characters `ids` of LOD `lod`, batch by batch as
    /// [`Self::render`] does, and reads back the VBOs (tests: the skinned vertices of each
    /// character, positions and normals, in the order of `ids`).
    pub fn skin_to_vbo(
        &mut self,
        lod: usize,
        instances: &Instances,
        ids: &[usize],
    ) -> Result<Vec<SkinnedColumn>, GlError> {
        let n = ids.len();
        let matrices = instances.bone_matrices(&self.model, ids);
        self.reserve(lod, n)?;
        let limit = self.batch_limit(lod);
        let bones = self.model.bone_count();
        let resources = &self.lods[lod];
        let mut columns = Vec::with_capacity(n);
        for (b, batch) in resources.batches.iter().enumerate().take(n.div_ceil(limit)) {
            let first = b * limit;
            let count = (n - first).min(limit);
            batch
                .bones
                .upload(&matrices[first * bones..(first + count) * bones])?;
            self.pass1.run(
                &batch.target,
                &resources.textures,
                &batch.bones,
                count as u32,
            )?;
            batch.vbo.copy_from(&batch.target, count as u32)?;
            let all: Vec<[f32; 4]> = batch.vbo.buffer.read()?;
            let what = format!(
                "crowd: the skinned vertices of {count} {:?} characters (batch {b}) at LOD {lod}",
                self.model.kind
            );
            ensure_finite(
                batch.vbo.used_texels(count as u32).flat_map(|t| all[t]),
                &what,
                super::pass1_skinning::SKINNING_PASS,
            )?;
            columns.extend((0..count as u32).map(|c| batch.vbo.column_of(&all, c)));
        }
        Ok(columns)
    }
}

/// Runs `work`; when `timing`, inside a GL timer query and between `glFinish` calls, and
/// returns (timer query ms, wall-clock ms), else (0, 0).
fn timed(
    ctx: &Context,
    timing: bool,
    work: impl FnOnce() -> Result<(), GlError>,
) -> Result<(f64, f64), GlError> {
    if !timing {
        return work().map(|()| (0.0, 0.0));
    }
    ctx.finish_all();
    let started = Instant::now();
    let ((), gl_ms) = query::time_gpu(ctx, || {
        work()?;
        ctx.finish_all();
        Ok(())
    })?;
    Ok((gl_ms, started.elapsed().as_secs_f64() * 1e3))
}
