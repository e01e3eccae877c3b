//! Host exercise of lesson 2 (ping-pong): Jacobi steps between two textures, each with its
//! framebuffer, written by the learner: the two targets, the program's uniforms and the
//! viewport, one step (bind the target, bind the input, draw), the swap, and the readback of
//! the last iterate (`examples/ping-pong.rs`). What saxpy taught (a float texture, a
//! framebuffer on it, a program) is given, written with glow in `examples/common/given.rs`.

use super::{Gap, HostExercise};
use crate::learn::ping_pong::{initial_grid, jacobi_cpu, tolerance, N, STEPS};
use crate::learn::{Grid, LessonRun};
use crate::shader;

/// The grid's side and the number of steps, the lesson's.
pub const SIDE: u32 = N;
pub const STEP_COUNT: u32 = STEPS;

pub const VERTEX: &str = super::saxpy::VERTEX;
/// One Jacobi step, the lesson's own shader.
pub const FRAGMENT: &str = shader!("glsl/learn/jacobi.frag").source;

/// The start, the lesson's: zero inside, the top row held at 1.
pub fn start() -> Vec<f32> {
    initial_grid(SIDE)
}

/// The lesson's check of the grid read back after the steps, texel by texel.
fn check_grid(run: &mut LessonRun, grid: &[f32]) {
    run.check_texels(
        &format!("after {STEP_COUNT} steps the grid = the CPU's Jacobi iterate"),
        Grid::new(SIDE, SIDE, 1),
        grid,
        &jacobi_cpu(&start(), SIDE, STEP_COUNT),
        tolerance(STEP_COUNT),
    );
}

pub static CARD: HostExercise = HostExercise {
    example: "ping-pong",
    lesson: "ping-pong",
    title: "ping-pong, the swap yours",
    gaps: &[
        Gap {
            number: 1,
            step: "make the two iterates: texture A holding the start grid, texture B with \
                   nothing yet (glTexImage2D: given::float_texture)",
            hints: [
                "A pass may not read the texture it draws into, so an iteration needs two: \
                 while one is read, the other is drawn. Both are float textures of the grid's \
                 size; only the first holds the start.",
                "given::float_texture(gl, side, side, 1, Some(&start)) for A and \
                 given::float_texture(gl, side, side, 1, None) for B.",
            ],
        },
        Gap {
            number: 2,
            step: "make a framebuffer for each iterate, drawing into it (glGenFramebuffers, \
                   glFramebufferTexture2D: given::framebuffer_on)",
            hints: [
                "Each texture gets its own framebuffer, so that changing the target from one \
                 step to the next is one bind, not an attachment made again.",
                "given::framebuffer_on(gl, a) and given::framebuffer_on(gl, b).",
            ],
        },
        Gap {
            number: 3,
            step: "use the program, point its sampler u_current at texture unit 0, set u_size \
                   to the grid's size, and make the viewport the grid (glUseProgram, \
                   glUniform1i, glUniform2i, glViewport)",
            hints: [
                "What does not change from step to step is set once before the loop: the \
                 program, its uniforms (which unit u_current reads, the grid's size for the \
                 boundary test) and the viewport, the same for A and B.",
                "gl.use_program(Some(program)); gl.uniform_1_i32(gl.get_uniform_location(\
                 program, \"u_current\").as_ref(), 0); gl.uniform_2_i32(.. \"u_size\" .., side, \
                 side); gl.viewport(0, 0, side, side).",
            ],
        },
        Gap {
            number: 4,
            step: "make one Jacobi step: draw into write's framebuffer while read's texture is \
                   on unit 0 (glBindFramebuffer, glActiveTexture, glBindTexture, glDrawArrays)",
            hints: [
                "A step is a draw: its target is the iterate being made, its input the one \
                 made before. `read` and `write` are each a (texture, framebuffer) pair: draw \
                 with write's framebuffer bound, read's texture on the unit u_current reads.",
                "gl.bind_framebuffer(glow::FRAMEBUFFER, Some(write.1)); \
                 gl.active_texture(glow::TEXTURE0); gl.bind_texture(glow::TEXTURE_2D, \
                 Some(read.0)); gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4).",
            ],
        },
        Gap {
            number: 5,
            step: "swap the roles: the iterate just drawn is the next one read (ping-pong: no \
                   GL call, only the two pairs exchanged)",
            hints: [
                "After a step, the texture drawn holds iterate k + 1, and the next step must \
                 read it; the texture read before is free to be drawn over. Nothing is copied: \
                 the two pairs change places.",
                "Exchange read and write: std::mem::swap, or a destructuring assignment of the \
                 pair (write, read).",
            ],
        },
        Gap {
            number: 6,
            step: "read the last iterate back: bind the framebuffer of the texture drawn last \
                   for reading, and read its side x side floats (glBindFramebuffer with \
                   GL_READ_FRAMEBUFFER, glReadPixels)",
            hints: [
                "After the last swap, `read` holds the newest iterate. glReadPixels reads the \
                 framebuffer bound to GL_READ_FRAMEBUFFER, which need not be the one bound for \
                 drawing.",
                "gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(read.1)); gl.read_pixels(0, \
                 0, side, side, glow::RED, glow::FLOAT, \
                 glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut values)))).",
            ],
        },
    ],
    faults: &[],
    solution_file: "examples/ping-pong-solution.rs",
    solution_text: include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/ping-pong-solution.rs"
    )),
    check: check_grid,
};
