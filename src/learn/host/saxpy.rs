//! Host exercise of lesson 1 (a quad is a loop): saxpy, `y = a x + y`, with every GL call
//! written by the learner in the order of Göddeke's GPGPU::Basic Math tutorial: arrays become
//! textures, a framebuffer draws into the result's texture, a program is built, its inputs
//! and uniform set, the viewport made the array's size, one rectangle drawn, the result read
//! back (`examples/saxpy.rs`).

use super::{Gap, HostExercise};
use crate::learn::quad_is_loop::{saxpy_cpu, SAXPY_TOLERANCE};
use crate::learn::{Grid, LessonRun};
use crate::shader;

/// The arrays are `W x H` (the lesson's size).
pub const W: u32 = 16;
pub const H: u32 = 12;
pub const A: f32 = 2.5;

/// The vertex shader of every host exercise: the rectangle that covers the viewport.
pub const VERTEX: &str = shader!("glsl/learn/host/quad.vert").source;
/// The loop's body, the lesson's own shader.
pub const FRAGMENT: &str = shader!("glsl/learn/saxpy.frag").source;

/// x and y, rows from the bottom: a ramp and a short repeating pattern, so that a read one
/// texel off, or x and y swapped, gives a value no texel should have. Every value is a
/// multiple of 1/8 below 64, so a x + y is exact in fp32.
pub fn inputs() -> (Vec<f32>, Vec<f32>) {
    let n = (W * H) as usize;
    let x = (0..n).map(|k| k as f32 / 8.0).collect();
    let y = (0..n).map(|k| ((k * 5) % 11) as f32 / 4.0 - 1.0).collect();
    (x, y)
}

/// The lesson's check: the new y against the CPU loop, texel by texel.
fn check(run: &mut LessonRun, y_new: &[f32]) {
    let (x, y) = inputs();
    run.check_texels(
        "saxpy = the CPU loop",
        Grid::new(W, H, 1),
        y_new,
        &saxpy_cpu(A, &x, &y),
        SAXPY_TOLERANCE,
    );
}

pub static CARD: HostExercise = HostExercise {
    example: "saxpy",
    lesson: "quad-is-loop",
    title: "saxpy, every GL call yours",
    gaps: &[
        Gap {
            number: 1,
            step: "make textures for x and y: W x H texels of one 32-bit float each (GL_R32F), \
                   holding the arrays, sampled texel for texel (glGenTextures, glBindTexture, \
                   glTexParameteri, glTexImage2D)",
            hints: [
                "Arrays are textures: one texel per element. A texture is made (an id), bound \
                 to the target GL_TEXTURE_2D, and given storage and values in one call that \
                 names the size, the internal format (how each texel is stored: one 32-bit \
                 float) and the layout of your data (one red float per element). Until its \
                 minifying filter is one without mipmaps, GL calls the texture incomplete and \
                 every read of it gives 0.",
                "glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, W, H, 0, GL_RED, GL_FLOAT, data) after \
                 glBindTexture(GL_TEXTURE_2D, t); with glow: gl.create_texture(), \
                 gl.bind_texture(glow::TEXTURE_2D, Some(t)), \
                 gl.tex_parameter_i32(glow::TEXTURE_2D, glow::TEXTURE_MIN_FILTER, glow::NEAREST \
                 as i32) (and MAG), gl.tex_image_2d(glow::TEXTURE_2D, 0, glow::R32F as i32, w, \
                 h, 0, glow::RED, glow::FLOAT, PixelUnpackData::Slice(Some(bytemuck::cast_slice(\
                 &x)))). Make it once for x and once for y.",
            ],
        },
        Gap {
            number: 2,
            step: "make the result's texture and a framebuffer that draws into it, and check \
                   that it is complete (glGenFramebuffers, glBindFramebuffer, \
                   glFramebufferTexture2D, glCheckFramebufferStatus)",
            hints: [
                "Computing is drawing, and a drawing goes into a framebuffer. A framebuffer \
                 object has no storage of its own: a texture attached as its colour attachment \
                 0 receives what the fragment shader writes. The result's texture is made like \
                 x's, with no data yet. GL says whether the framebuffer can be drawn into.",
                "glBindFramebuffer(GL_FRAMEBUFFER, fbo); glFramebufferTexture2D(GL_FRAMEBUFFER, \
                 GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, out, 0); then \
                 glCheckFramebufferStatus(GL_FRAMEBUFFER) must be GL_FRAMEBUFFER_COMPLETE. With \
                 glow: gl.create_framebuffer(), gl.bind_framebuffer(glow::FRAMEBUFFER, \
                 Some(fbo)), gl.framebuffer_texture_2d(glow::FRAMEBUFFER, \
                 glow::COLOR_ATTACHMENT0, glow::TEXTURE_2D, Some(out), 0), \
                 gl.check_framebuffer_status(glow::FRAMEBUFFER).",
            ],
        },
        Gap {
            number: 3,
            step: "build the program from the vertex and fragment shaders and check that they \
                   compiled and linked (glCreateShader, glShaderSource, glCompileShader, \
                   glCreateProgram, glAttachShader, glLinkProgram)",
            hints: [
                "Kernels are fragment programs. Each shader is compiled on its own from its \
                 source text (saxpy::VERTEX, saxpy::FRAGMENT); a program takes both and is \
                 linked. Compiling and linking report failure only when asked: read the \
                 status, and the log when it failed.",
                "For each stage: glCreateShader(GL_VERTEX_SHADER or GL_FRAGMENT_SHADER), \
                 glShaderSource, glCompileShader, then glGetShaderiv(GL_COMPILE_STATUS); then \
                 glCreateProgram, glAttachShader twice, glLinkProgram, \
                 glGetProgramiv(GL_LINK_STATUS). With glow: gl.create_shader(kind), \
                 gl.shader_source(s, source), gl.compile_shader(s), \
                 gl.get_shader_compile_status(s), gl.create_program(), gl.attach_shader(p, s), \
                 gl.link_program(p), gl.get_program_link_status(p).",
            ],
        },
        Gap {
            number: 4,
            step: "use the program; put x on texture unit 0 and y on unit 1, point the samplers \
                   u_x and u_y at those units, and set u_a (glUseProgram, glActiveTexture, \
                   glBindTexture, glGetUniformLocation, glUniform1i, glUniform1f)",
            hints: [
                "A sampler in the shader reads a texture unit, not a texture: bind each input \
                 texture to a unit, and set each sampler uniform to its unit's number. \
                 Uniforms are set on the program in use, so make it current first.",
                "glUseProgram(p); glActiveTexture(GL_TEXTURE0 + k); glBindTexture(GL_TEXTURE_2D, \
                 t); glUniform1i(glGetUniformLocation(p, \"u_x\"), k); \
                 glUniform1f(glGetUniformLocation(p, \"u_a\"), a). With glow: \
                 gl.use_program(Some(p)), gl.active_texture(glow::TEXTURE0 + k), \
                 gl.uniform_1_i32(gl.get_uniform_location(p, \"u_x\").as_ref(), k as i32), \
                 gl.uniform_1_f32(.., saxpy::A).",
            ],
        },
        Gap {
            number: 5,
            step: "make the viewport the array's size: the range of the loop (glViewport)",
            hints: [
                "The viewport maps the drawing onto the target's pixels: one pixel per element, \
                 so it is the array's size, starting at the corner. A headless context starts \
                 with a viewport of 0 x 0.",
                "glViewport(0, 0, W, H); with glow: gl.viewport(0, 0, w as i32, h as i32).",
            ],
        },
        Gap {
            number: 6,
            step: "draw the rectangle that covers the viewport: four vertices of a triangle \
                   strip, with a vertex array bound (glGenVertexArrays, glBindVertexArray, \
                   glDrawArrays)",
            hints: [
                "The rectangle is the loop: one fragment per pixel it covers, each running the \
                 shader once. The vertex shader makes the four corners from the vertex's \
                 number, so no vertex buffer is needed; but a core context draws only with a \
                 vertex array object bound, even an empty one.",
                "glGenVertexArrays, glBindVertexArray(vao), glDrawArrays(GL_TRIANGLE_STRIP, 0, \
                 4); with glow: gl.create_vertex_array(), gl.bind_vertex_array(Some(vao)), \
                 gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4).",
            ],
        },
        Gap {
            number: 7,
            step: "read the result back into an array of W x H floats (glReadPixels)",
            hints: [
                "Feedback to the CPU: read the framebuffer's colour attachment into client \
                 memory, one red float per texel, rows from the bottom. The array must have \
                 room for every value: GL writes as many as the rectangle and format say.",
                "glReadPixels(0, 0, W, H, GL_RED, GL_FLOAT, values) with the framebuffer bound; \
                 with glow: gl.read_pixels(0, 0, w as i32, h as i32, glow::RED, glow::FLOAT, \
                 glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut values)))).",
            ],
        },
    ],
    faults: &[],
    solution_file: "examples/saxpy-solution.rs",
    solution_text: include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/saxpy-solution.rs"
    )),
    check,
};
