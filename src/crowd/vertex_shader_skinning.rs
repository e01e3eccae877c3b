//! The baseline of Table 1: skinning in the vertex shader, bone matrices in uniforms
//! (`glsl/crowd/vs_skinning.vert`). The paper notes the limited constant registers make
//! this poor for crowds; to be as fast as the method allows, as many characters' matrices
//! as the uniform space holds go into one upload, and one instanced draw skins them all.

use glam::{DAffine3, Vec4};

use crate::gl::{
    Buffer, BufferUsage, Context, Framebuffer, GlError, Primitive, Program, Rect, ShaderSource,
    VertexArray,
};
use crate::shader;

use super::bone_textures::matrix_row;
use super::pass2_draw::{scene_state, Shading};
use super::validate::SkinnedMesh;
use super::vertex_textures;

/// vec4 uniforms left for everything but the bone rows (the view-projection matrix and
/// what the driver reserves).
const RESERVED_VEC4: u32 = 16;

/// Characters per draw for `bones` bones under `max_vertex_uniform_components`.
pub fn batch_size(bones: u32, max_vertex_uniform_components: u32) -> u32 {
    let vec4s = (max_vertex_uniform_components / 4).saturating_sub(RESERVED_VEC4);
    (vec4s / (3 * bones)).max(1)
}

/// The static vertex data and the program for one mesh.
pub struct VertexShaderSkinning {
    program: Program,
    vertices: VertexArray,
    index_count: usize,
    bones: u32,
    /// Characters whose matrices fit the uniform array (its compiled size).
    capacity: u32,
    /// Characters per draw call, at most `capacity`.
    batch: u32,
}

impl VertexShaderSkinning {
    pub fn new(
        ctx: &Context,
        mesh: &SkinnedMesh,
        indices: &Buffer,
        bones: u32,
    ) -> Result<Self, GlError> {
        let batch = batch_size(bones, ctx.info().limits.max_vertex_uniform_components);
        let defines = format!("#define BONES {bones}\n#define BATCH {batch}\n");
        let header = ShaderSource {
            name: "crowd vertex-shader skinning sizes (generated)",
            source: &defines,
        };
        let program = Program::new(
            ctx,
            &[header, shader!("glsl/crowd/vs_skinning.vert")],
            &[shader!("glsl/crowd/shade.frag")],
        )?;
        let texels = vertex_textures::pack(mesh);
        let mut vertices = VertexArray::new(ctx)?;
        for (location, data) in [
            texels.position,
            texels.normal,
            texels.bone_index,
            texels.bone_weight,
        ]
        .iter()
        .enumerate()
        {
            let buffer = Buffer::from_slice(ctx, data, BufferUsage::Static)?;
            vertices.float_attribute(location as u32, &buffer, 4, 16, 0, 0)?;
        }
        vertices.set_index_buffer(indices)?;
        Ok(Self {
            program,
            vertices,
            index_count: mesh.triangle_count() * 3,
            bones,
            capacity: batch,
            batch,
        })
    }

    /// Characters skinned per draw call on this renderer.
    pub fn batch(&self) -> u32 {
        self.batch
    }

    /// Skins at most `batch` characters per draw call (clamped to 1..=what the uniforms
    /// hold). One per draw is how the paper's generation of hardware ran this method: a
    /// few hundred constant registers and no instancing in OpenGL 2.
    pub fn set_batch(&mut self, batch: u32) {
        self.batch = batch.clamp(1, self.capacity);
    }

    /// Skins and draws characters whose skinning matrices are `matrices` (`bones` each),
    /// into `viewport` of `scene` (the whole of it when `None`).
    pub fn draw(
        &self,
        scene: &Framebuffer,
        shading: &Shading,
        matrices: &[DAffine3],
        viewport: Option<Rect>,
    ) -> Result<(), GlError> {
        let per_batch = (self.batch * self.bones) as usize;
        let mut pass = scene.pass(&self.program, "crowd vertex-shader skinning")?;
        pass.viewport(viewport.unwrap_or(scene.rect()));
        pass.state(scene_state())
            .uniform("u_view_projection", shading.view_projection)
            .uniform("u_colour", shading.colour)
            .uniform("u_light", shading.light);
        let mut rows: Vec<Vec4> = Vec::with_capacity(3 * per_batch);
        for chunk in matrices.chunks(per_batch) {
            rows.clear();
            for m in chunk {
                rows.extend((0..3).map(|r| Vec4::from_array(matrix_row(m, r))));
            }
            let characters = chunk.len() / self.bones as usize;
            pass.uniform("u_bone_rows", &rows[..]);
            pass.draw_elements_instanced(
                &self.vertices,
                Primitive::Triangles,
                0,
                self.index_count,
                characters,
            )?;
        }
        Ok(())
    }
}
