//! Host exercise 4: an array read back three ways, every readback yours (lesson 8,
//! readback and upload: `classic-gpgpu learn readback-and-upload`): into client memory,
//! through a pixel pack buffer, and reading less (the block flags, then only the blocks that
//! hold data). What saxpy taught is given in `examples/common/given.rs`: do saxpy first.
//!
//! Run it from the repository: `cargo run --release --example readback` (only this file
//! compiles). Each gap, a line `ex.gap(N)?` or `ex.gap_value(N)?`, stops the run naming the
//! GL step it stands for: replace the line with your GL calls, made on `gl` with glow's names
//! (`gl.bind_texture(glow::TEXTURE_2D, Some(t))`). The lines after a gap check your step; the
//! result is checked against the CPU texel by texel, and your GL calls are set beside the
//! solution's, the first difference marked.
//!
//! Hints: `cargo run --release --example readback -- --hint N.1` (the idea), `N.2` (the call),
//! `N.3` (the solution's lines). The solution: `examples/readback-solution.rs`.

use classic_gpgpu::learn::host::{self, readback, Exercise};
use classic_gpgpu::learn::Grid;
use std::process::ExitCode;

#[path = "common/given.rs"]
mod given;

/// The shipped solution, run beside yours so that the two traces can be compared (it
/// includes `given` too, hence the second allow).
#[allow(dead_code, clippy::duplicate_mod)]
#[path = "readback-solution.rs"]
mod solution;

fn main() -> ExitCode {
    host::main(&readback::CARD, exercise, solution::exercise)
}

/// The array read back block by block, only the blocks that hold data, each in its place.
pub fn exercise(ex: &Exercise) -> anyhow::Result<Vec<f32>> {
    let gl = ex.gl();
    let side = readback::SIDE;
    let data = readback::data();
    let grid = Grid::new(side, side, 4);
    let bytes = data.len() * 4;
    // SAFETY: every call is made on the exercise's context, current on this thread, with
    // objects made on it; every array handed to GL has room for what GL writes into it.
    unsafe {
        // The data on the GPU, and the framebuffer that reads it.
        let texture = given::float_texture(gl, side, side, 4, Some(&data))?;
        let fb = given::framebuffer_on(gl, texture)?;

        // Gap 1. The whole array into `whole`, in client memory: the CPU waits for it.
        let whole: Vec<f32> = ex.gap_value(1)?;
        ex.reading_from(1, fb)?;
        ex.same_values(1, "the whole array read back", grid, &whole, &data)?;

        // Gap 2. `pbo`, a buffer with room for the array, bound as the pixel pack buffer.
        let pbo: glow::Buffer = ex.gap_value(2)?;
        ex.pack_buffer(2, pbo, bytes)?;

        // Gap 3. The array read into the buffer (queued, the CPU does not wait), the buffer
        // then unbound.
        ex.gap(3)?;
        ex.no_pack_buffer(3)?;
        ex.buffer_holds(3, pbo, grid, &data)?;

        // Gap 4. The buffer copied into `from_pbo`, in client memory: here the CPU waits.
        let from_pbo: Vec<f32> = ex.gap_value(4)?;
        ex.no_pack_buffer(4)?;
        ex.same_values(
            4,
            "the array read through the buffer",
            grid,
            &from_pbo,
            &data,
        )?;

        // Reading less. The flags: one texel per BLOCK x BLOCK block, 1 where it holds data.
        let program = given::program(gl, readback::VERTEX, readback::FLAGS)?;
        given::vertex_array(gl)?;
        let flags_side = side / readback::BLOCK;
        let flags = given::float_texture(gl, flags_side, flags_side, 4, None)?;
        let flags_fb = given::framebuffer_on(gl, flags)?;
        gl.use_program(Some(program));
        gl.uniform_1_i32(gl.get_uniform_location(program, "u_data").as_ref(), 0);
        let block = gl.get_uniform_location(program, "u_block");
        gl.uniform_1_i32(block.as_ref(), readback::BLOCK as i32);
        gl.active_texture(glow::TEXTURE0);
        gl.bind_texture(glow::TEXTURE_2D, Some(texture));

        // Gap 5. The flags pass: its viewport, then the rectangle.
        ex.gap(5)?;
        ex.drew_reading(5, "u_data", texture)?;
        ex.framebuffer_on(5, flags_fb, flags)?;

        // Gap 6. `sparse`: the flags read, then each flagged block read into its place in an
        // array of zeros; the blocks without data are never read.
        let sparse: Vec<f32> = ex.gap_value(6)?;
        ex.no_errors(6)?;
        Ok(sparse)
    }
}
