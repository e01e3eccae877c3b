//! Transform feedback (OpenGL 3.0): the vertex shader's outputs written into a buffer instead
//! of being rasterized. It is the later way to do what paper 2's render-to-vertex-buffer does
//! through a fragment pass and a pixel buffer: vertices computed on the GPU, kept on the GPU,
//! drawn from there.

use super::{Buffer, Context, GlError, Program};

/// Run `program` (made by [`Program::feedback`]) over `count` vertices with no vertex buffer
/// (the shader builds each from `gl_VertexID`), capturing its varyings into `buffer` from
/// byte 0, with the rasterizer off. Returns how many vertices the GL says it wrote (a
/// `TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN` query: points, so one per vertex).
pub fn capture_points(
    ctx: &Context,
    program: &Program,
    buffer: &Buffer,
    count: usize,
) -> Result<u64, GlError> {
    let gl = ctx.gl();
    let _scope = super::profile::scope(ctx, "transform feedback");
    let written = unsafe {
        let query = gl.create_query().map_err(GlError::Invalid)?;
        program.bind();
        gl.bind_vertex_array(Some(ctx.inner.empty_vao));
        gl.bind_buffer_base(glow::TRANSFORM_FEEDBACK_BUFFER, 0, Some(buffer.id()));
        gl.enable(glow::RASTERIZER_DISCARD);
        gl.begin_query(glow::TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, query);
        gl.begin_transform_feedback(glow::POINTS);
        gl.draw_arrays(glow::POINTS, 0, count as i32);
        gl.end_transform_feedback();
        gl.end_query(glow::TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
        gl.disable(glow::RASTERIZER_DISCARD);
        gl.bind_buffer_base(glow::TRANSFORM_FEEDBACK_BUFFER, 0, None);
        gl.bind_vertex_array(None);
        let written = gl.get_query_parameter_u32(query, glow::QUERY_RESULT);
        gl.delete_query(query);
        written
    };
    ctx.check("transform feedback")?;
    Ok(written as u64)
}
