//! The debug hunt, the solution: lesson 2's Jacobi steps, and one step timed, with the four
//! faults of `examples/debug-hunt.rs` fixed, each between `// region: fault-N` and
//! `// endregion` (those lines are the third hint of the fault). Do not read it before the
//! hunt.
//!
//! Run it from the repository: `cargo run --release --example debug-hunt-solution`.

use classic_gpgpu::learn::host::{self, hunt, Exercise};
use std::process::ExitCode;

#[path = "common/given.rs"]
mod given;

fn main() -> ExitCode {
    host::hunt_main(&hunt::CARD, exercise)
}

/// `hunt::STEP_COUNT` Jacobi steps, then one step timed: the last iterate, read back.
pub fn exercise(ex: &Exercise) -> anyhow::Result<Vec<f32>> {
    let gl = ex.gl();
    let side = hunt::SIDE;
    let n = side as i32;
    let start = hunt::start();
    // SAFETY: every call is made on the exercise's context, current on this thread, with
    // objects made on it; every array handed to GL has room for what GL writes into it.
    unsafe {
        let program = given::program(gl, hunt::VERTEX, hunt::FRAGMENT)?;
        given::vertex_array(gl)?;

        // The two iterates, A holding the start grid, and their framebuffers.
        let a = given::float_texture(gl, side, side, 1, Some(&start))?;
        let b = gl.create_texture().map_err(anyhow::Error::msg)?;
        gl.bind_texture(glow::TEXTURE_2D, Some(b));
        for filter in [glow::TEXTURE_MIN_FILTER, glow::TEXTURE_MAG_FILTER] {
            gl.tex_parameter_i32(glow::TEXTURE_2D, filter, glow::NEAREST as i32);
        }
        let empty = glow::PixelUnpackData::Slice(None);
        // region: fault-3
        let (format, layout, kind) = (glow::R32F as i32, glow::RED, glow::FLOAT);
        // endregion
        gl.tex_image_2d(glow::TEXTURE_2D, 0, format, n, n, 0, layout, kind, empty);
        let fb_a = given::framebuffer_on(gl, a)?;
        let fb_b = given::framebuffer_on(gl, b)?;

        // The program, its uniforms and the viewport, the same for every step.
        let u_size = gl.get_uniform_location(program, "u_size");
        let u_current = gl.get_uniform_location(program, "u_current");
        // region: fault-4
        gl.use_program(Some(program));
        gl.uniform_2_i32(u_size.as_ref(), n, n);
        // endregion
        gl.uniform_1_i32(u_current.as_ref(), 0);
        gl.viewport(0, 0, n, n);

        // The steps, A into B, then B into A, and so on.
        for k in 0..hunt::STEP_COUNT {
            // Even steps read A and draw into B, odd steps the other way round.
            // region: fault-2
            let (read, write) = if k % 2 == 0 { (a, fb_b) } else { (b, fb_a) };
            // endregion
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(write));
            gl.active_texture(glow::TEXTURE0);
            gl.bind_texture(glow::TEXTURE_2D, Some(read));
            gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4);
        }
        let steps = hunt::STEP_COUNT;

        // The speed of one step, as a benchmark measures it: the same step (the start grid
        // into B) made many times over from an idle GPU, the time divided by their number.
        gl.finish();
        gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fb_b));
        gl.bind_texture(glow::TEXTURE_2D, Some(a));
        let clock = ex.start_clock();
        for _ in 0..hunt::REPEATS {
            gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4);
        }
        // region: fault-1
        gl.finish();
        let ms = ex.read_clock(&clock) / hunt::REPEATS as f64;
        // endregion
        println!("one Jacobi step on a {side} x {side} grid takes {ms:.4} ms");

        // The last iterate: the step count is even, so the last step drew into A (the
        // benchmark drew into B only).
        let last = if steps.is_multiple_of(2) { fb_a } else { fb_b };
        let mut grid = vec![0f32; start.len()];
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(last));
        let into = glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut grid)));
        gl.read_pixels(0, 0, n, n, glow::RED, glow::FLOAT, into);
        Ok(grid)
    }
}
