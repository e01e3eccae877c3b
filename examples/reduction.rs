//! Host exercise 3: the sum and the maximum of an array by a ladder of 2x2 passes down to
//! one texel, every pass yours (lesson 3, reduction: `classic-gpgpu learn reduction`). What
//! saxpy taught is given in `examples/common/given.rs`: do saxpy first.
//!
//! Run it from the repository: `cargo run --release --example reduction` (only this file
//! compiles). Each gap, a line `ex.gap(N)?` or `ex.gap_value(N)?`, stops the run naming the
//! GL step it stands for: replace the line with your GL calls, made on `gl` with glow's names
//! (`gl.bind_texture(glow::TEXTURE_2D, Some(t))`). The lines after a gap check your step; the
//! result is checked against the CPU texel by texel, and your GL calls are set beside the
//! solution's, the first difference marked.
//!
//! Hints: `cargo run --release --example reduction -- --hint N.1` (the idea), `N.2` (the call),
//! `N.3` (the solution's lines). The solution: `examples/reduction-solution.rs`.

use classic_gpgpu::learn::host::{self, reduction, Exercise};
use std::process::ExitCode;

#[path = "common/given.rs"]
mod given;

/// The shipped solution, run beside yours so that the two traces can be compared (it
/// includes `given` too, hence the second allow).
#[allow(dead_code, clippy::duplicate_mod)]
#[path = "reduction-solution.rs"]
mod solution;

fn main() -> ExitCode {
    host::main(&reduction::CARD, exercise, solution::exercise)
}

/// The sum and the maximum of `reduction::values()`, from the one texel left.
pub fn exercise(ex: &Exercise) -> anyhow::Result<Vec<f32>> {
    let gl = ex.gl();
    let first = (reduction::WIDTH, reduction::HEIGHT);
    // SAFETY: every call is made on the exercise's context, current on this thread, with
    // objects made on it; every array handed to GL has room for what GL writes into it.
    unsafe {
        let program = given::program(gl, reduction::VERTEX, reduction::FRAGMENT)?;
        given::vertex_array(gl)?;
        gl.use_program(Some(program));
        let level = gl.get_uniform_location(program, "u_level");
        gl.uniform_1_i32(level.as_ref(), 0);
        // The level below (a texture) and its size: first the array, red = green = value.
        let input = reduction::first_level();
        let mut below = given::float_texture(gl, first.0, first.1, 4, Some(&input))?;
        let mut size = first;

        // Gap 1. The ladder goes on while the level below is more than one texel.
        while ex.gap_value(1)? {
            // Gap 2. The next level: `next_size`, its size (each of its texels takes a 2x2
            // block of the level below); `next`, an RGBA float texture of that size; `fb`
            // drawing into it.
            let (next_size, next, fb): ((u32, u32), glow::Texture, glow::Framebuffer) =
                ex.gap_value(2)?;
            ex.next_level(2, size, next_size, next, fb)?;

            // Gap 3. The loop's range: the next level's texels.
            ex.gap(3)?;
            ex.viewport_covers(3, next)?;

            // Gap 4. The pass: draw into `fb`, the level below on unit 0, u_size its size.
            ex.gap(4)?;
            ex.drew_reading(4, "u_level", below)?;
            ex.uniform_i32(4, "u_size", &[size.0 as i32, size.1 as i32])?;
            if size == first {
                ex.level_one(4, next)?;
            }

            // Gap 5. The level drawn becomes the level below, with its size.
            (below, size) = ex.gap_value(5)?;
        }

        // Gap 6. The one texel left, four floats: red the sum, green the maximum.
        let texel: [f32; 4] = ex.gap_value(6)?;
        ex.no_errors(6)?;
        Ok(texel[..2].to_vec())
    }
}
