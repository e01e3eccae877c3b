//! Pass 2 [section 2]: every character is rendered by the vertex shader from the VBO of
//! pass 1 with the mesh's shared index buffer. Character c's vertices sit in column c of
//! the render target, so its attributes start at texel c with a stride of one row; one
//! vertex array per column records that, and each character is one indexed draw.

use glam::{Mat4, Vec3};

use crate::gl::{
    Buffer, Compare, Context, DepthTest, DrawState, Face, Framebuffer, GlError, Primitive, Program,
    VertexArray,
};
use crate::shader;

use super::render_to_vbo::SkinnedVbo;

/// The fixed-function state of the scene passes (both methods use the same).
pub fn scene_state() -> DrawState {
    DrawState {
        depth: Some(DepthTest {
            func: Compare::Less,
            write: true,
        }),
        cull: Some(Face::Back),
        ..DrawState::default()
    }
}

/// Colour and light of a draw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shading {
    pub view_projection: Mat4,
    pub colour: Vec3,
    pub light: Vec3,
}

/// One vertex array per render-target column, all sharing the index buffer.
pub struct CharacterArrays {
    arrays: Vec<VertexArray>,
}

impl CharacterArrays {
    pub fn new(ctx: &Context, vbo: &SkinnedVbo, indices: &Buffer) -> Result<Self, GlError> {
        let arrays = (0..vbo.characters)
            .map(|c| {
                let mut va = VertexArray::new(ctx)?;
                va.float_attribute(0, &vbo.buffer, 4, vbo.stride(), vbo.position_offset(c), 0)?;
                va.float_attribute(1, &vbo.buffer, 4, vbo.stride(), vbo.normal_offset(c), 0)?;
                va.set_index_buffer(indices)?;
                Ok(va)
            })
            .collect::<Result<Vec<_>, GlError>>()?;
        Ok(Self { arrays })
    }
}

/// The drawing program of pass 2.
pub struct Pass2 {
    program: Program,
}

impl Pass2 {
    pub fn new(ctx: &Context) -> Result<Self, GlError> {
        Ok(Self {
            program: Program::new(
                ctx,
                &[shader!("glsl/crowd/pass2_draw.vert")],
                &[shader!("glsl/crowd/shade.frag")],
            )?,
        })
    }

    /// Draws the first `n` characters of `arrays`, `index_count` indices each.
    pub fn draw(
        &self,
        scene: &Framebuffer,
        shading: &Shading,
        arrays: &CharacterArrays,
        n: usize,
        index_count: usize,
    ) -> Result<(), GlError> {
        // region: pass2
        let mut pass = scene.pass(&self.program, "crowd pass 2 (draw from VBO)")?;
        pass.state(scene_state())
            .uniform("u_view_projection", shading.view_projection)
            .uniform("u_colour", shading.colour)
            .uniform("u_light", shading.light);
        // One draw per character; the state is the same for all of them, so it is set once.
        let characters: Vec<&VertexArray> = arrays.arrays[..n].iter().collect();
        pass.draw_elements_each(&characters, Primitive::Triangles, 0, index_count)
        // endregion
    }
}
