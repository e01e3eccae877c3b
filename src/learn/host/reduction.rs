//! Host exercise of lesson 3 (reduction, level by level): the 2x2 ladder down to one texel,
//! written by the learner: each level's texture and framebuffer, its viewport (smaller every
//! pass), the pass that reads the level below, the loop's end, the next level taking the
//! place of the one below, and the readback of the one texel left (`examples/reduction.rs`).

use super::{Exercise, Gap, HostExercise};
use crate::gl::trace::Id;
use crate::learn::reduction::{blocks_cpu, H, UNIT_ROUNDOFF, W};
use crate::learn::{random_values, Grid, LessonRun};
use crate::shader;

/// The array's size, the lesson's (not powers of two: the edges take the identities).
pub const WIDTH: u32 = W;
pub const HEIGHT: u32 = H;

pub const VERTEX: &str = super::saxpy::VERTEX;
/// One 2x2 level: red the sums, green the maxima; the lesson's own shader.
pub const FRAGMENT: &str = shader!("glsl/learn/reduce_2x2.frag").source;

/// The values, the lesson's: `W x H` in [0, 1).
pub fn values() -> Vec<f32> {
    random_values((W * H) as usize, 4, 0.0, 1.0)
}

/// The values as the first level's texels: red = green = the value (RGBA).
pub fn first_level() -> Vec<f32> {
    values().iter().flat_map(|&v| [v, v, 0.0, 0.0]).collect()
}

/// The levels a 2x2 ladder draws from `W x H` to one texel.
fn levels() -> u32 {
    let (mut w, mut h, mut n) = (W, H, 0);
    while w > 1 || h > 1 {
        (w, h, n) = (w.div_ceil(2), h.div_ceil(2), n + 1);
    }
    n
}

/// The lesson's checks of the one texel read back: the sum within the fp32 rounding of the
/// additions each value goes through (3 a level), the maximum exact.
fn check(run: &mut LessonRun, texel: &[f32]) {
    let values = values();
    let sum: f64 = values.iter().map(|&v| v as f64).sum();
    let max = values.iter().fold(f32::MIN, |m, &v| m.max(v));
    let (gpu_sum, gpu_max) = match texel {
        [s, m, ..] => (*s as f64, *m),
        _ => (f64::NAN, f32::NAN),
    };
    let path = levels() * 3;
    run.check(
        &format!("2x2: sum = the CPU's (f64) sum, within {path} additions' fp32 rounding"),
        (gpu_sum - sum).abs(),
        path as f64 * UNIT_ROUNDOFF * sum,
    );
    run.check(
        "2x2: maximum = the CPU's (exact)",
        (gpu_max as f64 - max as f64).abs(),
        0.0,
    );
}

impl Exercise {
    /// Reduction, gap `gap`: `next` is `below`'s next level (`ceil(side / 2)` each way,
    /// `next_size`), a float RGBA texture, and `framebuffer` draws into it.
    pub fn next_level(
        &self,
        gap: u32,
        below: (u32, u32),
        next_size: (u32, u32),
        next: glow::Texture,
        framebuffer: glow::Framebuffer,
    ) -> anyhow::Result<()> {
        let wanted = (below.0.div_ceil(2), below.1.div_ceil(2));
        self.check_step(gap, || {
            if next_size == wanted {
                Ok(())
            } else {
                Err(format!(
                    "the level after {} x {} is {} x {}, not {} x {}: each texel takes a 2x2 \
                     block, and a block cut by the edge still needs its texel",
                    below.0, below.1, wanted.0, wanted.1, next_size.0, next_size.1
                ))
            }
        })?;
        self.float_texture(gap, next, Grid::new(wanted.0, wanted.1, 4))?;
        self.framebuffer_on(gap, framebuffer, next)
    }

    /// Reduction, gap `gap`: the first level drawn, `level`, texel by texel against the
    /// lesson's block sums and maxima (within 4 x 4 additions' fp32 rounding), also kept as
    /// one of the run's checks.
    pub fn level_one(&self, gap: u32, level: glow::Texture) -> anyhow::Result<()> {
        let (w, h) = (W.div_ceil(2), H.div_ceil(2));
        self.check_step(gap, || {
            let facts = self.door().texture(level)?;
            let rg: Vec<f32> = facts
                .values
                .chunks_exact(4)
                .flat_map(|t| [t[0], t[1]])
                .collect();
            let mut run = self.run_mut();
            run.check_texels(
                "2x2 level 1 = the CPU's block sums and maxima",
                Grid::new(w, h, 2),
                &rg,
                &blocks_cpu(&values(), 2),
                16.0 * UNIT_ROUNDOFF,
            );
            let check = run.checks.last().expect("just recorded");
            if check.passed {
                Ok(())
            } else {
                Err(format!(
                    "the first level (texture {}, red the sums, green the maxima) is not the \
                     CPU's: {}",
                    level.id(),
                    check.where_wrong().join("; ")
                ))
            }
        })
    }
}

pub static CARD: HostExercise = HostExercise {
    example: "reduction",
    lesson: "reduction",
    title: "reduction, level by level, every pass yours",
    gaps: &[
        Gap {
            number: 1,
            step: "the loop's condition: go on while the level below is larger than one texel \
                   (no GL call)",
            hints: [
                "The ladder ends when the level below is a single texel: it holds the sum and \
                 the maximum of everything.",
                "while size.0 > 1 || size.1 > 1 { ... }",
            ],
        },
        Gap {
            number: 2,
            step: "make the next level: its size (each of its texels takes a 2x2 block of the \
                   level below), an RGBA float texture of that size and a framebuffer that \
                   draws into it (glTexImage2D, glFramebufferTexture2D: given::float_texture, \
                   given::framebuffer_on)",
            hints: [
                "Each texel of the next level combines a 2x2 block of the level below, so the \
                 next level is half as wide and half as high; a side of odd length leaves a \
                 block cut by the edge, which still needs its texel.",
                "next_size = (size.0.div_ceil(2), size.1.div_ceil(2)); then \
                 given::float_texture(gl, next_size.0, next_size.1, 4, None) and \
                 given::framebuffer_on(gl, next).",
            ],
        },
        Gap {
            number: 3,
            step: "make the viewport the next level's size (glViewport)",
            hints: [
                "The viewport is the loop's range, and the loop shrinks with every level: a \
                 viewport left at the first level's size draws texels the level does not have, \
                 and the pass covers the wrong fragments.",
                "gl.viewport(0, 0, next_size.0 as i32, next_size.1 as i32).",
            ],
        },
        Gap {
            number: 4,
            step: "draw the level: into the next level's framebuffer, with the level below on \
                   unit 0 and u_size set to its size (glBindFramebuffer, glActiveTexture, \
                   glBindTexture, glUniform2i, glDrawArrays)",
            hints: [
                "A pass reads the level below (u_level, on unit 0) and writes the next; the \
                 shader needs the size of the level below to give the texels past its edge \
                 the identities (0 for the sum, the lowest float for the maximum).",
                "gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fb)); \
                 gl.active_texture(glow::TEXTURE0); gl.bind_texture(glow::TEXTURE_2D, \
                 Some(below)); gl.uniform_2_i32(gl.get_uniform_location(program, \
                 \"u_size\").as_ref(), size.0 as i32, size.1 as i32); \
                 gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4).",
            ],
        },
        Gap {
            number: 5,
            step: "the level just drawn becomes the level below, with its size (no GL call)",
            hints: [
                "The next pass reads what this one wrote: the new level takes the place of the \
                 one below, and its size the size.",
                "(below, size) = (next, next_size);",
            ],
        },
        Gap {
            number: 6,
            step: "read the one texel left: four floats, red the sum, green the maximum \
                   (glReadPixels)",
            hints: [
                "The last framebuffer drawn holds the last level, one texel; it is still bound \
                 for reading. Read it as RGBA floats.",
                "gl.read_pixels(0, 0, 1, 1, glow::RGBA, glow::FLOAT, \
                 glow::PixelPackData::Slice(Some(bytemuck::cast_slice_mut(&mut texel)))) with \
                 texel a [f32; 4].",
            ],
        },
    ],
    faults: &[],
    solution_file: "examples/reduction-solution.rs",
    solution_text: include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/reduction-solution.rs"
    )),
    check,
};

#[cfg(test)]
mod tests {
    #[test]
    fn the_ladder_of_48_x_40_has_six_levels() {
        assert_eq!(super::levels(), 6);
    }
}
