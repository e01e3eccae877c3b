//! Host exercise of lesson 8 (readback and upload): the readbacks written by the learner: the
//! whole array into client memory, the same through a pixel pack buffer (the read queued, the
//! CPU waiting only when it copies the buffer out), and a reduced readback that reads the
//! block flags, then only the blocks that hold data (`examples/readback.rs`).

use super::{Exercise, Gap, HostExercise};
use crate::gl::trace::Id;
use crate::learn::kit;
use crate::learn::{Grid, LessonRun};
use crate::shader;

/// The array's side (RGBA floats) and the block side of the flags, the lesson's.
pub const SIDE: u32 = 128;
pub const BLOCK: u32 = 8;
/// The share of texels that hold data.
const DENSITY: f32 = 0.01;

pub const VERTEX: &str = super::saxpy::VERTEX;
/// One flag per block: 1 where any texel of the block is not zero; the lesson's shader.
pub const FLAGS: &str = shader!("glsl/learn/readback-and-upload/block_flags.frag").source;

/// The array: `SIDE x SIDE` RGBA texels, about 1% of them holding data, the rest zero.
pub fn data() -> Vec<f32> {
    let n = (SIDE * SIDE) as usize;
    let pick = kit::values(n, 21);
    let value = kit::values(3 * n, 22);
    (0..n)
        .flat_map(|k| {
            if pick[k] < DENSITY {
                [value[3 * k], value[3 * k + 1], value[3 * k + 2], 1.0]
            } else {
                [0.0; 4]
            }
        })
        .collect()
}

fn check(run: &mut LessonRun, read: &[f32]) {
    let data = data();
    run.check_texels(
        "reduced readback: the flagged blocks, each in its place, = the array (exact)",
        Grid::new(SIDE, SIDE, 4),
        read,
        &data,
        0.0,
    );
    run.check(
        "reduced readback: bytes differing from the array (exact)",
        kit::bytes_differing(read, &data),
        0.0,
    );
}

impl Exercise {
    /// Readback, gap `gap`: `buffer` is bound as the pixel pack buffer, with room for `bytes`.
    pub fn pack_buffer(&self, gap: u32, buffer: glow::Buffer, bytes: usize) -> anyhow::Result<()> {
        self.check_step(gap, || match self.door().pack_buffer() {
            Some((id, size)) if id == buffer.id() && size == bytes as i64 => Ok(()),
            Some((id, size)) if id == buffer.id() => Err(format!(
                "buffer {id} has {size} bytes; the array needs {bytes} (glBufferData)"
            )),
            Some((id, _)) => Err(format!(
                "buffer {id} is bound as GL_PIXEL_PACK_BUFFER, not buffer {}",
                buffer.id()
            )),
            None => Err(format!(
                "no buffer is bound as GL_PIXEL_PACK_BUFFER: bind buffer {} there \
                 (glBindBuffer)",
                buffer.id()
            )),
        })
    }

    /// Readback, gap `gap`: no pixel pack buffer is bound (a glReadPixels into client memory
    /// would otherwise take its pointer for an offset into the buffer).
    pub fn no_pack_buffer(&self, gap: u32) -> anyhow::Result<()> {
        self.check_step(gap, || match self.door().pack_buffer() {
            None => Ok(()),
            Some((id, _)) => Err(format!(
                "buffer {id} is still bound as GL_PIXEL_PACK_BUFFER: every later glReadPixels \
                 would write into it instead of your array; unbind it (glBindBuffer with 0)"
            )),
        })
    }

    /// Readback, gap `gap`: `buffer` holds `values` (`grid`'s), exactly.
    pub fn buffer_holds(
        &self,
        gap: u32,
        buffer: glow::Buffer,
        grid: Grid,
        values: &[f32],
    ) -> anyhow::Result<()> {
        let bytes = self
            .door()
            .buffer_bytes(buffer)
            .map_err(|problem| super::Stop::Step { gap, problem })?;
        let held: Vec<f32> = bytes
            .chunks_exact(4)
            .map(|b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        self.same_values(
            gap,
            &format!("buffer {} after glReadPixels into it", buffer.id()),
            grid,
            &held,
            values,
        )
    }
}

pub static CARD: HostExercise = HostExercise {
    example: "readback",
    lesson: "readback-and-upload",
    title: "readback: client memory, a pixel pack buffer, and reading less",
    gaps: &[
        Gap {
            number: 1,
            step: "read the whole array into client memory: the data's framebuffer bound for \
                   reading, SIDE x SIDE RGBA floats (glBindFramebuffer with \
                   GL_READ_FRAMEBUFFER, glReadPixels)",
            hints: [
                "glReadPixels copies from the framebuffer bound for reading into your array, \
                 and returns only when the copy is done: every pass queued before it must \
                 finish first. The array needs room for 4 floats a texel.",
                "gl.bind_framebuffer(glow::READ_FRAMEBUFFER, Some(fb)); gl.read_pixels(0, 0, \
                 side, side, glow::RGBA, glow::FLOAT, \
                 glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut whole)))).",
            ],
        },
        Gap {
            number: 2,
            step: "make a pixel pack buffer with room for the whole array, bound as \
                   GL_PIXEL_PACK_BUFFER (glGenBuffers, glBindBuffer, glBufferData)",
            hints: [
                "A buffer object bound as the pixel pack buffer turns glReadPixels into a copy \
                 on the GPU's side: the call is queued like a draw, and the CPU waits only \
                 when it takes the bytes out. Its storage is made once, as large as the read.",
                "gl.create_buffer(); gl.bind_buffer(glow::PIXEL_PACK_BUFFER, Some(pbo)); \
                 gl.buffer_data_size(glow::PIXEL_PACK_BUFFER, bytes as i32, \
                 glow::STREAM_READ).",
            ],
        },
        Gap {
            number: 3,
            step: "read the array into the pack buffer (an offset, not a pointer), then unbind \
                   the buffer (glReadPixels, glBindBuffer)",
            hints: [
                "With a pack buffer bound, glReadPixels's last argument is an offset into the \
                 buffer. Leave the buffer bound and every later glReadPixels writes into it \
                 too, whatever array you pass.",
                "gl.read_pixels(0, 0, side, side, glow::RGBA, glow::FLOAT, \
                 glow::PixelPackData::BufferOffset(0)); gl.bind_buffer(glow::PIXEL_PACK_BUFFER, \
                 None).",
            ],
        },
        Gap {
            number: 4,
            step: "copy the pack buffer into client memory: here the CPU waits for the read \
                   (glBindBuffer, glGetBufferSubData)",
            hints: [
                "The bytes are on the GPU's side until you ask for them; asking waits for the \
                 queued read to finish. Bind the buffer, copy it out, unbind it.",
                "gl.bind_buffer(glow::PIXEL_PACK_BUFFER, Some(pbo)); \
                 gl.get_buffer_sub_data(glow::PIXEL_PACK_BUFFER, 0, \
                 bytemuck::cast_slice_mut(&mut from_pbo)); gl.bind_buffer(.., None).",
            ],
        },
        Gap {
            number: 5,
            step: "draw the flags pass: the viewport the flags' size (one texel per BLOCK x \
                   BLOCK block), then the rectangle (glViewport, glDrawArrays)",
            hints: [
                "Reading less starts on the GPU: one pass writes a flag per block, 1 where the \
                 block holds data. Its target is SIDE / BLOCK texels a side, and the viewport \
                 must say so.",
                "gl.viewport(0, 0, flags_side as i32, flags_side as i32); \
                 gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4).",
            ],
        },
        Gap {
            number: 6,
            step: "read the flags, then only the flagged blocks, each BLOCK x BLOCK block into \
                   its place in an array of zeros (glBindFramebuffer, glReadPixels with an \
                   origin and a size)",
            hints: [
                "The flags are small: read them all (from the flags' framebuffer). Then, for \
                 each flag set, read the block it stands for from the data's framebuffer: \
                 glReadPixels takes the rectangle's corner and size, and writes its rows one \
                 after another; copy each row of the block to its row in the array.",
                "gl.read_pixels((bx * block) as i32, (by * block) as i32, block as i32, block \
                 as i32, glow::RGBA, glow::FLOAT, ..Slice(Some(cast_slice_mut(&mut texels)))), \
                 then row r of the block goes to texel ((by * block + r) * side + bx * block) \
                 of the array, 4 floats a texel.",
            ],
        },
    ],
    faults: &[],
    solution_file: "examples/readback-solution.rs",
    solution_text: include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/readback-solution.rs"
    )),
    check,
};

#[cfg(test)]
mod tests {
    #[test]
    fn the_data_is_sparse_but_not_empty() {
        let data = super::data();
        let set = data.chunks_exact(4).filter(|t| t[3] == 1.0).count();
        let n = (super::SIDE * super::SIDE) as usize;
        assert!(set > n / 200 && set < n / 50, "{set} of {n}");
    }
}
