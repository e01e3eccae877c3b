//! Stream update [Sec. 6]: per frame, `T_min`/`T_max` are rebuilt from the vertex texture by
//! one line drawn into two render targets (MRT), the fragment program of paper Table II
//! (`cg_ports/collide_table2_stream_update.frag`) taking column-wise min and max [Eq. 1].
//! The tree is never rebuilt.

use super::aabb_textures::AabbTextures;
use super::vertex_textures::VertexTexture;
use crate::gl::{Context, GlError, Primitive, Program};
use crate::shader;

pub struct StreamUpdate {
    program: Program,
}

impl StreamUpdate {
    pub fn new(ctx: &Context) -> Result<StreamUpdate, GlError> {
        let program = Program::new(
            ctx,
            &[shader!("glsl/collide/stream_line.vert")],
            &[shader!("cg_ports/collide_table2_stream_update.frag")],
        )?;
        Ok(StreamUpdate { program })
    }

    /// Refit the boxes of one segment to its (already uploaded) vertex texture.
    pub fn run(&self, vertices: &VertexTexture, aabb: &AabbTextures) -> Result<(), GlError> {
        // region: stream-update
        let mut pass = aabb
            .targets
            .pass(&self.program, "stream update (Table II)")?;
        pass.texture("vertexTexture", &vertices.texture)
            .uniform("nMax", vertices.layout.height as i32)
            .uniform("u_pad", 1.0 / vertices.layout.width as f32);
        pass.draw_attributeless(Primitive::Lines, 2, 1)
        // endregion
    }
}
