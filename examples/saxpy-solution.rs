//! Host exercise 1, the solution: saxpy (`y = a x + y`) with every GL call written out, in
//! the order of Göddeke's GPGPU::Basic Math tutorial (lesson 1, a quad is a loop). Each gap of
//! the template `examples/saxpy.rs` is filled here between `// region: gap-N` and
//! `// endregion`; those lines are the third hint of the gap.
//!
//! Run it from the repository: `cargo run --release --example saxpy-solution`.

use classic_gpgpu::learn::host::{self, saxpy, Exercise};
use classic_gpgpu::learn::Grid;
use std::process::ExitCode;

fn main() -> ExitCode {
    host::solution_main(&saxpy::CARD, exercise)
}

/// y = a x + y on the GPU: the new y, read back.
// Until its gaps are filled, the template makes no GL call on `gl` in its unsafe block.
#[allow(unused_variables, unused_unsafe)]
pub fn exercise(ex: &Exercise) -> anyhow::Result<Vec<f32>> {
    let gl = ex.gl();
    let (w, h) = (saxpy::W, saxpy::H);
    let (x, y) = saxpy::inputs();
    let grid = Grid::new(w, h, 1);
    // SAFETY: every call is made on the exercise's context, current on this thread, with
    // objects made on it; every array handed to GL has room for what GL writes into it.
    unsafe {
        // Gap 1. Arrays are textures: `tex_x` and `tex_y`, W x H texels of one 32-bit float
        // each, holding x and y.
        // region: gap-1
        let float_texture = |data: Option<&[f32]>| -> anyhow::Result<glow::Texture> {
            let texture = gl.create_texture().map_err(anyhow::Error::msg)?;
            gl.bind_texture(glow::TEXTURE_2D, Some(texture));
            for filter in [glow::TEXTURE_MIN_FILTER, glow::TEXTURE_MAG_FILTER] {
                gl.tex_parameter_i32(glow::TEXTURE_2D, filter, glow::NEAREST as i32);
            }
            let values = glow::PixelUnpackData::Slice(data.map(bytemuck::cast_slice));
            let (w, h) = (w as i32, h as i32);
            let r32f = glow::R32F as i32;
            gl.tex_image_2d(
                glow::TEXTURE_2D,
                0,
                r32f,
                w,
                h,
                0,
                glow::RED,
                glow::FLOAT,
                values,
            );
            Ok(texture)
        };
        let (tex_x, tex_y) = (float_texture(Some(&x))?, float_texture(Some(&y))?);
        // endregion
        ex.texture_holds(1, tex_x, grid, &x)?;
        ex.texture_holds(1, tex_y, grid, &y)?;

        // Gap 2. Computing is drawing: `tex_out`, the result's texture (made like x's, with no
        // data yet), and `fbo`, a framebuffer that draws into it, which GL says it can.
        // region: gap-2
        let tex_out = float_texture(None)?;
        let fbo = gl.create_framebuffer().map_err(anyhow::Error::msg)?;
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
        let (target, colour0) = (glow::FRAMEBUFFER, glow::COLOR_ATTACHMENT0);
        gl.framebuffer_texture_2d(target, colour0, glow::TEXTURE_2D, Some(tex_out), 0);
        let status = gl.check_framebuffer_status(glow::FRAMEBUFFER);
        anyhow::ensure!(
            status == glow::FRAMEBUFFER_COMPLETE,
            "incomplete: {status:#x}"
        );
        // endregion
        ex.float_texture(2, tex_out, grid)?;
        ex.framebuffer_on(2, fbo, tex_out)?;

        // Gap 3. Kernels are programs: `program`, built from saxpy::VERTEX and
        // saxpy::FRAGMENT (the files glsl/learn/host/quad.vert and glsl/learn/saxpy.frag).
        // region: gap-3
        let program = gl.create_program().map_err(anyhow::Error::msg)?;
        let stages = [
            (glow::VERTEX_SHADER, saxpy::VERTEX),
            (glow::FRAGMENT_SHADER, saxpy::FRAGMENT),
        ];
        for (kind, source) in stages {
            let shader = gl.create_shader(kind).map_err(anyhow::Error::msg)?;
            gl.shader_source(shader, source);
            gl.compile_shader(shader);
            let log = gl.get_shader_info_log(shader);
            anyhow::ensure!(gl.get_shader_compile_status(shader), "compile: {log}");
            gl.attach_shader(program, shader);
        }
        gl.link_program(program);
        let log = gl.get_program_info_log(program);
        anyhow::ensure!(gl.get_program_link_status(program), "link: {log}");
        // endregion
        ex.linked(3, program)?;

        // Gap 4. The kernel's inputs: the program in use, x on texture unit 0 and y on unit 1,
        // the samplers u_x and u_y reading those units, and the uniform u_a = saxpy::A.
        // region: gap-4
        gl.use_program(Some(program));
        for (unit, (name, texture)) in [("u_x", tex_x), ("u_y", tex_y)].into_iter().enumerate() {
            gl.active_texture(glow::TEXTURE0 + unit as u32);
            gl.bind_texture(glow::TEXTURE_2D, Some(texture));
            let sampler = gl.get_uniform_location(program, name);
            gl.uniform_1_i32(sampler.as_ref(), unit as i32);
        }
        let a = gl.get_uniform_location(program, "u_a");
        gl.uniform_1_f32(a.as_ref(), saxpy::A);
        // endregion
        ex.in_use(4, program)?;
        ex.sampler_reads(4, "u_x", tex_x)?;
        ex.sampler_reads(4, "u_y", tex_y)?;
        ex.uniform_f32(4, "u_a", &[saxpy::A])?;

        // Gap 5. The loop's range: one pixel per element.
        // region: gap-5
        gl.viewport(0, 0, w as i32, h as i32);
        // endregion
        ex.viewport_covers(5, tex_out)?;

        // Gap 6. The loop: draw the rectangle that covers the viewport (four vertices of a
        // triangle strip, which the vertex shader makes from their numbers).
        // region: gap-6
        let vao = gl.create_vertex_array().map_err(anyhow::Error::msg)?;
        gl.bind_vertex_array(Some(vao));
        gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4);
        // endregion
        ex.drew(6)?;

        // Gap 7. Feedback: read the result into `y_new`, W x H floats.
        // region: gap-7
        let mut y_new = vec![0f32; x.len()];
        let into = glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut y_new)));
        gl.read_pixels(0, 0, w as i32, h as i32, glow::RED, glow::FLOAT, into);
        // endregion
        ex.no_errors(7)?;
        Ok(y_new)
    }
}
