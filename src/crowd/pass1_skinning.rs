//! Pass 1 [section 2, Fig. 2]: one draw call of a rectangle covering n characters x m
//! vertices; the pixel shader (`glsl/crowd/pass1_skinning.frag`) skins one vertex of one
//! character per texel. Positions go to colour target 0 and normals to colour target 1
//! (two render targets of one draw, so the blend of bone matrices serves both).

use crate::gl::{Context, Framebuffer, GlError, Program, Rect, Texture, TextureFormat};
use crate::shader;

use super::bone_textures::BoneTextures;
use super::vertex_textures::VertexTextures;

/// The render target texture(s): `characters` columns x `vertices` rows, RGBA32F.
pub struct SkinningTarget {
    pub framebuffer: Framebuffer,
    pub characters: u32,
    pub vertices: u32,
}

impl SkinningTarget {
    pub fn new(ctx: &Context, characters: u32, vertices: u32) -> Result<Self, GlError> {
        let texture = || Texture::new_2d(ctx, characters, vertices, TextureFormat::Rgba32F);
        let (positions, normals) = (texture()?, texture()?);
        let framebuffer =
            Framebuffer::new(ctx, "crowd render target", &[&positions, &normals], None)?;
        Ok(Self {
            framebuffer,
            characters,
            vertices,
        })
    }
}

/// The skinning program.
pub struct Pass1 {
    program: Program,
}

impl Pass1 {
    pub fn new(ctx: &Context) -> Result<Self, GlError> {
        Ok(Self {
            program: Program::rect(ctx, &[shader!("glsl/crowd/pass1_skinning.frag")])?,
        })
    }

    /// Skins the first `n` characters (columns) of `target` in one draw call.
    pub fn run(
        &self,
        target: &SkinningTarget,
        vertices: &VertexTextures,
        bones: &BoneTextures,
        n: u32,
    ) -> Result<(), GlError> {
        if vertices.vertices != target.vertices || n > target.characters || n > bones.capacity {
            return Err(GlError::Invalid(format!(
                "pass 1: {n} characters of {} vertices do not fit a {}x{} target with bone \
                 textures for {}",
                vertices.vertices, target.characters, target.vertices, bones.capacity
            )));
        }
        let mut pass = target
            .framebuffer
            .pass(&self.program, "crowd pass 1 (skinning)")?;
        pass.texture("u_position", &vertices.position)
            .texture("u_normal", &vertices.normal)
            .texture("u_bone_index", &vertices.bone_index)
            .texture("u_bone_weight", &vertices.bone_weight)
            .texture("u_row0", &bones.rows[0])
            .texture("u_row1", &bones.rows[1])
            .texture("u_row2", &bones.rows[2]);
        pass.draw_rect(Rect::sized(n, target.vertices))
    }
}
