//! Host exercise 2: Jacobi steps ping-ponged between two textures, the targets, the step
//! and the swap yours (lesson 2, ping-pong: `classic-gpgpu learn ping-pong`). What saxpy
//! taught (a float texture, a framebuffer on it, a program) is given in
//! `examples/common/given.rs`: do saxpy first.
//!
//! Run it from the repository: `cargo run --release --example ping-pong` (only this file
//! compiles). Each gap, a line `ex.gap(N)?` or `ex.gap_value(N)?`, stops the run naming the
//! GL step it stands for: replace the line with your GL calls, made on `gl` with glow's names
//! (`gl.bind_texture(glow::TEXTURE_2D, Some(t))`). The lines after a gap check your step; the
//! result is checked against the CPU texel by texel, and your GL calls are set beside the
//! solution's, the first difference marked.
//!
//! Hints: `cargo run --release --example ping-pong -- --hint N.1` (the idea), `N.2` (the call),
//! `N.3` (the solution's lines). The solution: `examples/ping-pong-solution.rs`.

use classic_gpgpu::learn::host::{self, ping_pong, Exercise};
use classic_gpgpu::learn::Grid;
use std::process::ExitCode;

#[path = "common/given.rs"]
mod given;

/// The shipped solution, run beside yours so that the two traces can be compared (it
/// includes `given` too, hence the second allow).
#[allow(dead_code, clippy::duplicate_mod)]
#[path = "ping-pong-solution.rs"]
mod solution;

fn main() -> ExitCode {
    host::main(&ping_pong::CARD, exercise, solution::exercise)
}

/// `ping_pong::STEP_COUNT` Jacobi steps on the start grid: the last iterate, read back.
pub fn exercise(ex: &Exercise) -> anyhow::Result<Vec<f32>> {
    let gl = ex.gl();
    let side = ping_pong::SIDE;
    let start = ping_pong::start();
    let grid = Grid::new(side, side, 1);
    // SAFETY: every call is made on the exercise's context, current on this thread, with
    // objects made on it; every array handed to GL has room for what GL writes into it.
    unsafe {
        let program = given::program(gl, ping_pong::VERTEX, ping_pong::FRAGMENT)?;
        given::vertex_array(gl)?;

        // Gap 1. Two iterates: texture `a` holding the start grid, texture `b` with nothing
        // yet.
        let [a, b]: [glow::Texture; 2] = ex.gap_value(1)?;
        ex.texture_holds(1, a, grid, &start)?;
        ex.float_texture(1, b, grid)?;

        // Gap 2. For each iterate a framebuffer that draws into it: `fb_a` and `fb_b`.
        let [fb_a, fb_b]: [glow::Framebuffer; 2] = ex.gap_value(2)?;
        ex.framebuffer_on(2, fb_a, a)?;
        ex.framebuffer_on(2, fb_b, b)?;

        // Gap 3. What every step shares: the program in use, its sampler u_current reading
        // texture unit 0, u_size the grid's size, and the viewport the grid.
        ex.gap(3)?;
        ex.in_use(3, program)?;
        ex.uniform_i32(3, "u_current", &[0])?;
        ex.uniform_i32(3, "u_size", &[side as i32, side as i32])?;
        ex.viewport_covers(3, a)?;

        // The pairs (texture, framebuffer): `read` holds iterate k, `write` receives k + 1.
        let (mut read, mut write) = ((a, fb_a), (b, fb_b));
        for _ in 0..ping_pong::STEP_COUNT {
            // Gap 4. One step: draw into write's framebuffer with read's texture on unit 0.
            ex.gap(4)?;
            ex.drew_into(4, write.1)?;

            // Gap 5. The swap: the iterate just drawn is the one the next step reads.
            (read, write) = ex.gap_value(5)?;
            ex.reads_what_was_drawn(5, read.0)?;
        }

        // Gap 6. The last iterate, side x side floats, read back into `last`.
        let last: Vec<f32> = ex.gap_value(6)?;
        ex.reading_from(6, read.1)?;
        Ok(last)
    }
}
