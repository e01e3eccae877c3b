//! Host exercise 3, the solution: the sum and the maximum of an array by a ladder of 2x2
//! passes down to one texel, every pass's GL calls written out (lesson 3, reduction, level by
//! level). Each gap of the template `examples/reduction.rs` is filled here between
//! `// region: gap-N` and `// endregion`; those lines are the third hint of the gap. What
//! saxpy taught is in `examples/common/given.rs`.
//!
//! Run it from the repository: `cargo run --release --example reduction-solution`.

use classic_gpgpu::learn::host::{self, reduction, Exercise};
use std::process::ExitCode;

#[path = "common/given.rs"]
mod given;

fn main() -> ExitCode {
    host::solution_main(&reduction::CARD, exercise)
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
        // region: gap-1
        while size.0 > 1 || size.1 > 1 {
            // endregion
            // Gap 2. The next level: `next_size`, its size (each of its texels takes a 2x2
            // block of the level below); `next`, an RGBA float texture of that size; `fb`
            // drawing into it.
            // region: gap-2
            let next_size = (size.0.div_ceil(2), size.1.div_ceil(2));
            let next = given::float_texture(gl, next_size.0, next_size.1, 4, None)?;
            let fb = given::framebuffer_on(gl, next)?;
            // endregion
            ex.next_level(2, size, next_size, next, fb)?;

            // Gap 3. The loop's range: the next level's texels.
            // region: gap-3
            gl.viewport(0, 0, next_size.0 as i32, next_size.1 as i32);
            // endregion
            ex.viewport_covers(3, next)?;

            // Gap 4. The pass: draw into `fb`, the level below on unit 0, u_size its size.
            // region: gap-4
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fb));
            gl.active_texture(glow::TEXTURE0);
            gl.bind_texture(glow::TEXTURE_2D, Some(below));
            let u_size = gl.get_uniform_location(program, "u_size");
            gl.uniform_2_i32(u_size.as_ref(), size.0 as i32, size.1 as i32);
            gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4);
            // endregion
            ex.drew_reading(4, "u_level", below)?;
            ex.uniform_i32(4, "u_size", &[size.0 as i32, size.1 as i32])?;
            if size == first {
                ex.level_one(4, next)?;
            }

            // Gap 5. The level drawn becomes the level below, with its size.
            // region: gap-5
            (below, size) = (next, next_size);
            // endregion
        }

        // Gap 6. The one texel left, four floats: red the sum, green the maximum.
        // region: gap-6
        let mut texel = [0f32; 4];
        let into = glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut texel)));
        gl.read_pixels(0, 0, 1, 1, glow::RGBA, glow::FLOAT, into);
        // endregion
        ex.no_errors(6)?;
        Ok(texel[..2].to_vec())
    }
}
