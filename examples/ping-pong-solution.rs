//! Host exercise 2, the solution: Jacobi steps ping-ponged between two textures, every GL
//! call written out (lesson 2, ping-pong). Each gap of the template `examples/ping-pong.rs` is
//! filled here between `// region: gap-N` and `// endregion`; those lines are the third hint
//! of the gap. What saxpy taught is in `examples/common/given.rs`.
//!
//! Run it from the repository: `cargo run --release --example ping-pong-solution`.

use classic_gpgpu::learn::host::{self, ping_pong, Exercise};
use classic_gpgpu::learn::Grid;
use std::process::ExitCode;

#[path = "common/given.rs"]
mod given;

fn main() -> ExitCode {
    host::solution_main(&ping_pong::CARD, exercise)
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
        // region: gap-1
        let a = given::float_texture(gl, side, side, 1, Some(&start))?;
        let b = given::float_texture(gl, side, side, 1, None)?;
        // endregion
        ex.texture_holds(1, a, grid, &start)?;
        ex.float_texture(1, b, grid)?;

        // Gap 2. For each iterate a framebuffer that draws into it: `fb_a` and `fb_b`.
        // region: gap-2
        let (fb_a, fb_b) = (given::framebuffer_on(gl, a)?, given::framebuffer_on(gl, b)?);
        // endregion
        ex.framebuffer_on(2, fb_a, a)?;
        ex.framebuffer_on(2, fb_b, b)?;

        // Gap 3. What every step shares: the program in use, its sampler u_current reading
        // texture unit 0, u_size the grid's size, and the viewport the grid.
        // region: gap-3
        gl.use_program(Some(program));
        let current = gl.get_uniform_location(program, "u_current");
        gl.uniform_1_i32(current.as_ref(), 0);
        let size = gl.get_uniform_location(program, "u_size");
        gl.uniform_2_i32(size.as_ref(), side as i32, side as i32);
        gl.viewport(0, 0, side as i32, side as i32);
        // endregion
        ex.in_use(3, program)?;
        ex.uniform_i32(3, "u_current", &[0])?;
        ex.uniform_i32(3, "u_size", &[side as i32, side as i32])?;
        ex.viewport_covers(3, a)?;

        // The pairs (texture, framebuffer): `read` holds iterate k, `write` receives k + 1.
        let (mut read, mut write) = ((a, fb_a), (b, fb_b));
        for _ in 0..ping_pong::STEP_COUNT {
            // Gap 4. One step: draw into write's framebuffer with read's texture on unit 0.
            // region: gap-4
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(write.1));
            gl.active_texture(glow::TEXTURE0);
            gl.bind_texture(glow::TEXTURE_2D, Some(read.0));
            gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4);
            // endregion
            ex.drew_into(4, write.1)?;

            // Gap 5. The swap: the iterate just drawn is the one the next step reads.
            // region: gap-5
            (read, write) = (write, read);
            // endregion
            ex.reads_what_was_drawn(5, read.0)?;
        }

        // Gap 6. The last iterate, side x side floats, read back into `last`.
        // region: gap-6
        let mut last = vec![0f32; start.len()];
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(read.1));
        let into = glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut last)));
        let side = side as i32;
        gl.read_pixels(0, 0, side, side, glow::RED, glow::FLOAT, into);
        // endregion
        ex.reading_from(6, read.1)?;
        Ok(last)
    }
}
