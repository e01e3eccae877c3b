//! What the saxpy exercise (`examples/saxpy.rs`) has the learner write, written once here for
//! the exercises after it: a float texture, a framebuffer that draws into it, a program from
//! two shaders, and the vertex array a draw needs. Do saxpy first: these are its answers.
//! Every call goes through the exercise's recorder, so it shows in the trace like yours.
#![allow(dead_code)]

use classic_gpgpu::gl::trace::Gl;

/// A `width x height` texture of `channels` floats a texel (GL_R32F, GL_RG32F or
/// GL_RGBA32F), holding `data` (rows from the bottom) or, with `None`, nothing yet; sampled
/// texel for texel (GL_NEAREST, so it is complete without mipmaps).
///
/// # Safety
///
/// `gl` is the exercise's recorder, its context current on this thread.
pub unsafe fn float_texture(
    gl: &Gl,
    width: u32,
    height: u32,
    channels: usize,
    data: Option<&[f32]>,
) -> anyhow::Result<glow::Texture> {
    let (internal, format) = match channels {
        1 => (glow::R32F, glow::RED),
        2 => (glow::RG32F, glow::RG),
        _ => (glow::RGBA32F, glow::RGBA),
    };
    let texture = gl.create_texture().map_err(anyhow::Error::msg)?;
    gl.bind_texture(glow::TEXTURE_2D, Some(texture));
    for filter in [glow::TEXTURE_MIN_FILTER, glow::TEXTURE_MAG_FILTER] {
        gl.tex_parameter_i32(glow::TEXTURE_2D, filter, glow::NEAREST as i32);
    }
    gl.tex_image_2d(
        glow::TEXTURE_2D,
        0,
        internal as i32,
        width as i32,
        height as i32,
        0,
        format,
        glow::FLOAT,
        glow::PixelUnpackData::Slice(data.map(bytemuck::cast_slice)),
    );
    Ok(texture)
}

/// A framebuffer whose colour attachment 0 is `texture`, left bound, checked complete.
///
/// # Safety
///
/// As [`float_texture`]; `texture` was made by it.
pub unsafe fn framebuffer_on(gl: &Gl, texture: glow::Texture) -> anyhow::Result<glow::Framebuffer> {
    let framebuffer = gl.create_framebuffer().map_err(anyhow::Error::msg)?;
    gl.bind_framebuffer(glow::FRAMEBUFFER, Some(framebuffer));
    gl.framebuffer_texture_2d(
        glow::FRAMEBUFFER,
        glow::COLOR_ATTACHMENT0,
        glow::TEXTURE_2D,
        Some(texture),
        0,
    );
    let status = gl.check_framebuffer_status(glow::FRAMEBUFFER);
    anyhow::ensure!(
        status == glow::FRAMEBUFFER_COMPLETE,
        "the framebuffer on texture {texture:?} is incomplete (status {status:#x})"
    );
    Ok(framebuffer)
}

/// A program linked from a vertex and a fragment shader's source; an error carries the log.
///
/// # Safety
///
/// As [`float_texture`].
pub unsafe fn program(gl: &Gl, vertex: &str, fragment: &str) -> anyhow::Result<glow::Program> {
    let program = gl.create_program().map_err(anyhow::Error::msg)?;
    for (kind, source) in [
        (glow::VERTEX_SHADER, vertex),
        (glow::FRAGMENT_SHADER, fragment),
    ] {
        let shader = gl.create_shader(kind).map_err(anyhow::Error::msg)?;
        gl.shader_source(shader, source);
        gl.compile_shader(shader);
        anyhow::ensure!(
            gl.get_shader_compile_status(shader),
            "a shader did not compile: {}",
            gl.get_shader_info_log(shader)
        );
        gl.attach_shader(program, shader);
    }
    gl.link_program(program);
    anyhow::ensure!(
        gl.get_program_link_status(program),
        "the program did not link: {}",
        gl.get_program_info_log(program)
    );
    Ok(program)
}

/// An empty vertex array, bound: a core context draws only with one, and the rectangle's
/// vertex shader makes its corners from the vertex's number.
///
/// # Safety
///
/// As [`float_texture`].
pub unsafe fn vertex_array(gl: &Gl) -> anyhow::Result<glow::VertexArray> {
    let vao = gl.create_vertex_array().map_err(anyhow::Error::msg)?;
    gl.bind_vertex_array(Some(vao));
    Ok(vao)
}
