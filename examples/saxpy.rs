//! Host exercise 1: saxpy (`y = a x + y`) with every GL call yours, in the order of
//! Göddeke's GPGPU::Basic Math tutorial (lesson 1, a quad is a loop: `classic-gpgpu learn
//! quad-is-loop`). Arrays are textures, computing is drawing, the viewport is the loop's range,
//! the rectangle drawn over it is the loop, and the result comes back by a readback.
//!
//! Run it from the repository: `cargo run --release --example saxpy` (only this file
//! compiles). Each gap, a line `ex.gap(N)?` or `ex.gap_value(N)?`, stops the run naming the
//! GL step it stands for: replace the line with your GL calls, made on `gl` with glow's names
//! (`gl.bind_texture(glow::TEXTURE_2D, Some(t))`). The lines after a gap check your step; the
//! result is checked against the CPU texel by texel, and your GL calls are set beside the
//! solution's, the first difference marked.
//!
//! Hints: `cargo run --release --example saxpy -- --hint N.1` (the idea), `N.2` (the call),
//! `N.3` (the solution's lines). The solution: `examples/saxpy-solution.rs`.

use classic_gpgpu::learn::host::{self, saxpy, Exercise};
use classic_gpgpu::learn::Grid;
use std::process::ExitCode;

/// The shipped solution, run beside yours so that the two traces can be compared (it
/// includes `given` too, hence the second allow).
#[allow(dead_code, clippy::duplicate_mod)]
#[path = "saxpy-solution.rs"]
mod solution;

fn main() -> ExitCode {
    host::main(&saxpy::CARD, exercise, solution::exercise)
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
        let (tex_x, tex_y): (glow::Texture, glow::Texture) = ex.gap_value(1)?;
        ex.texture_holds(1, tex_x, grid, &x)?;
        ex.texture_holds(1, tex_y, grid, &y)?;

        // Gap 2. Computing is drawing: `tex_out`, the result's texture (made like x's, with no
        // data yet), and `fbo`, a framebuffer that draws into it, which GL says it can.
        let (tex_out, fbo): (glow::Texture, glow::Framebuffer) = ex.gap_value(2)?;
        ex.float_texture(2, tex_out, grid)?;
        ex.framebuffer_on(2, fbo, tex_out)?;

        // Gap 3. Kernels are programs: `program`, built from saxpy::VERTEX and
        // saxpy::FRAGMENT (the files glsl/learn/host/quad.vert and glsl/learn/saxpy.frag).
        let program: glow::Program = ex.gap_value(3)?;
        ex.linked(3, program)?;

        // Gap 4. The kernel's inputs: the program in use, x on texture unit 0 and y on unit 1,
        // the samplers u_x and u_y reading those units, and the uniform u_a = saxpy::A.
        ex.gap(4)?;
        ex.in_use(4, program)?;
        ex.sampler_reads(4, "u_x", tex_x)?;
        ex.sampler_reads(4, "u_y", tex_y)?;
        ex.uniform_f32(4, "u_a", &[saxpy::A])?;

        // Gap 5. The loop's range: one pixel per element.
        ex.gap(5)?;
        ex.viewport_covers(5, tex_out)?;

        // Gap 6. The loop: draw the rectangle that covers the viewport (four vertices of a
        // triangle strip, which the vertex shader makes from their numbers).
        ex.gap(6)?;
        ex.drew(6)?;

        // Gap 7. Feedback: read the result into `y_new`, W x H floats.
        let y_new: Vec<f32> = ex.gap_value(7)?;
        ex.no_errors(7)?;
        Ok(y_new)
    }
}
