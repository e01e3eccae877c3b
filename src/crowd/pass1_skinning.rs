//! Pass 1 [section 2, Fig. 2]: one draw call of a rectangle covering n characters x m
//! vertices; the pixel shader (`glsl/crowd/pass1_skinning.frag`) skins one vertex of one
//! character per texel. Positions go to colour target 0 and normals to colour target 1
//! (two render targets of one draw, so the blend of bone matrices serves both).
//!
//! Rows hold at most [`MAX_ROW_CHARACTERS`] characters: pass 2 reads a character's
//! vertices one row apart, and OpenGL 4.4+ caps a vertex attribute's stride at
//! `GL_MAX_VERTEX_ATTRIB_STRIDE` (2048 bytes on Mesa; the paper's OpenGL 2 had no such
//! cap). More characters continue in further blocks of m rows below the first, as many
//! blocks as the largest texture holds. So one draw skins at most
//! [`characters_per_target`] characters, not all of them as in the paper: 128 x
//! floor(16384 / 562) = 3,712 soldiers at LOD 0 on 16384-texel targets. The renderer skins
//! a larger crowd in several batches, a draw each.

use crate::gl::{Context, Framebuffer, GlError, Program, Rect, Texture, TextureFormat};
use crate::shader;

use super::bone_textures::BoneTextures;
use super::vertex_textures::VertexTextures;

/// The name of pass 1 (errors name it).
pub const SKINNING_PASS: &str = "crowd pass 1 (skinning)";

/// Characters per render-target row: 2048-byte vertex stride / 16 bytes per RGBA32F texel.
pub const MAX_ROW_CHARACTERS: u32 = 2048 / 16;

/// Most characters one target of at most `max_texture_size` texels a side can hold for
/// meshes of `vertices` vertices: whole blocks of m rows of [`MAX_ROW_CHARACTERS`], and
/// bone textures of one row per character.
pub fn characters_per_target(max_texture_size: u32, vertices: u32) -> u32 {
    let max = max_texture_size;
    (MAX_ROW_CHARACTERS * (max / vertices.max(1))).min(max)
}

/// [`characters_per_target`] on this renderer: the most characters one pass-1 draw skins.
pub fn max_characters(ctx: &Context, vertices: u32) -> u32 {
    characters_per_target(ctx.max_texture_size(), vertices)
}

/// The render target texture(s): `row_characters` columns x (`blocks` x `vertices`) rows,
/// RGBA32F, for up to `characters` characters.
pub struct SkinningTarget {
    pub framebuffer: Framebuffer,
    pub characters: u32,
    pub vertices: u32,
    pub row_characters: u32,
    pub blocks: u32,
}

impl SkinningTarget {
    pub fn new(ctx: &Context, characters: u32, vertices: u32) -> Result<Self, GlError> {
        let row_characters = characters.clamp(1, MAX_ROW_CHARACTERS);
        let blocks = characters.div_ceil(row_characters);
        if characters > max_characters(ctx, vertices) {
            return Err(GlError::Limit(format!(
                "a render target for {characters} characters of {vertices} vertices needs \
                 {blocks} x {vertices} rows, more than this renderer's {} texels",
                ctx.max_texture_size()
            )));
        }
        let texture = || {
            Texture::new_2d(
                ctx,
                row_characters,
                blocks * vertices,
                TextureFormat::Rgba32F,
            )
        };
        let (positions, normals) = (texture()?, texture()?);
        let framebuffer =
            Framebuffer::new(ctx, "crowd render target", &[&positions, &normals], None)?;
        Ok(Self {
            framebuffer,
            characters,
            vertices,
            row_characters,
            blocks,
        })
    }

    /// Rows holding the first `n` characters (whole blocks).
    pub fn rows_for(&self, n: u32) -> u32 {
        n.div_ceil(self.row_characters) * self.vertices
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

    /// Skins the first `n` characters of `target` in one draw call (the last block may be
    /// partly filled; its unused columns compute values nobody draws).
    pub fn run(
        &self,
        target: &SkinningTarget,
        vertices: &VertexTextures,
        bones: &BoneTextures,
        n: u32,
    ) -> Result<(), GlError> {
        if vertices.vertices != target.vertices || n > target.characters || n > bones.capacity {
            return Err(GlError::Invalid(format!(
                "pass 1: {n} characters of {} vertices do not fit a target for {} characters \
                 of {} vertices with bone textures for {}",
                vertices.vertices, target.characters, target.vertices, bones.capacity
            )));
        }
        // region: pass1
        let mut pass = target.framebuffer.pass(&self.program, SKINNING_PASS)?;
        pass.texture("u_position", &vertices.position)
            .texture("u_normal", &vertices.normal)
            .texture("u_bone_index", &vertices.bone_index)
            .texture("u_bone_weight", &vertices.bone_weight)
            .texture("u_row0", &bones.rows[0])
            .texture("u_row1", &bones.rows[1])
            .texture("u_row2", &bones.rows[2])
            .uniform("u_vertices", target.vertices as i32)
            .uniform("u_row_characters", target.row_characters as i32);
        pass.draw_rect(Rect::sized(
            target.row_characters.min(n),
            target.rows_for(n),
        ))
        // endregion
    }
}
