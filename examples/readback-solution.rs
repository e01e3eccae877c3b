//! Host exercise 4, the solution: an array read back three ways, every GL call written out
//! (lesson 8, readback and upload): into client memory, through a pixel pack buffer, and
//! reading less (the block flags, then only the blocks that hold data). Each gap of the
//! template `examples/readback.rs` is filled here between `// region: gap-N` and
//! `// endregion`; those lines are the third hint of the gap. What saxpy taught is in
//! `examples/common/given.rs`.
//!
//! Run it from the repository: `cargo run --release --example readback-solution`.

use classic_gpgpu::learn::host::{self, readback, Exercise};
use classic_gpgpu::learn::Grid;
use std::process::ExitCode;

#[path = "common/given.rs"]
mod given;

fn main() -> ExitCode {
    host::solution_main(&readback::CARD, exercise)
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
        // region: gap-1
        let mut whole = vec![0f32; data.len()];
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(fb));
        let into = glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut whole)));
        gl.read_pixels(
            0,
            0,
            side as i32,
            side as i32,
            glow::RGBA,
            glow::FLOAT,
            into,
        );
        // endregion
        ex.reading_from(1, fb)?;
        ex.same_values(1, "the whole array read back", grid, &whole, &data)?;

        // Gap 2. `pbo`, a buffer with room for the array, bound as the pixel pack buffer.
        // region: gap-2
        let pbo = gl.create_buffer().map_err(anyhow::Error::msg)?;
        gl.bind_buffer(glow::PIXEL_PACK_BUFFER, Some(pbo));
        gl.buffer_data_size(glow::PIXEL_PACK_BUFFER, bytes as i32, glow::STREAM_READ);
        // endregion
        ex.pack_buffer(2, pbo, bytes)?;

        // Gap 3. The array read into the buffer (queued, the CPU does not wait), the buffer
        // then unbound.
        // region: gap-3
        let at_start = glow::PixelPackData::BufferOffset(0);
        gl.read_pixels(
            0,
            0,
            side as i32,
            side as i32,
            glow::RGBA,
            glow::FLOAT,
            at_start,
        );
        gl.bind_buffer(glow::PIXEL_PACK_BUFFER, None);
        // endregion
        ex.no_pack_buffer(3)?;
        ex.buffer_holds(3, pbo, grid, &data)?;

        // Gap 4. The buffer copied into `from_pbo`, in client memory: here the CPU waits.
        // region: gap-4
        let mut from_pbo = vec![0f32; data.len()];
        gl.bind_buffer(glow::PIXEL_PACK_BUFFER, Some(pbo));
        let out = bytemuck::cast_slice_mut(&mut from_pbo);
        gl.get_buffer_sub_data(glow::PIXEL_PACK_BUFFER, 0, out);
        gl.bind_buffer(glow::PIXEL_PACK_BUFFER, None);
        // endregion
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
        // region: gap-5
        gl.viewport(0, 0, flags_side as i32, flags_side as i32);
        gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4);
        // endregion
        ex.drew_reading(5, "u_data", texture)?;
        ex.framebuffer_on(5, flags_fb, flags)?;

        // Gap 6. `sparse`: the flags read, then each flagged block read into its place in an
        // array of zeros; the blocks without data are never read.
        // region: gap-6
        let (fs, b) = (flags_side as usize, readback::BLOCK as usize);
        let mut flag_texels = vec![0f32; fs * fs * 4];
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(flags_fb));
        let into = glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut flag_texels)));
        gl.read_pixels(0, 0, fs as i32, fs as i32, glow::RGBA, glow::FLOAT, into);
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(fb));
        let mut sparse = vec![0f32; data.len()];
        let mut texels = vec![0f32; b * b * 4];
        for (k, flag) in flag_texels.chunks_exact(4).enumerate() {
            if flag[0] == 0.0 {
                continue;
            }
            let (x, y) = ((k % fs) * b, (k / fs) * b);
            let into = glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut texels)));
            let (xi, yi, bi) = (x as i32, y as i32, b as i32);
            gl.read_pixels(xi, yi, bi, bi, glow::RGBA, glow::FLOAT, into);
            for row in 0..b {
                let at = ((y + row) * side as usize + x) * 4;
                sparse[at..at + b * 4].copy_from_slice(&texels[row * b * 4..(row + 1) * b * 4]);
            }
        }
        // endregion
        ex.no_errors(6)?;
        Ok(sparse)
    }
}
