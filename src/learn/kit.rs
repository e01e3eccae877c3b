//! What the lessons of the second half share: the pictures of their buffers, the notes of
//! their passes, the exercise's verdict, and test data the CPU makes.

use super::{LessonInfo, LessonOptions, LessonRun, PassNote};
use crate::gl::dump::{self, DumpRange};
use crate::gl::{Context, Texture};
use anyhow::bail;

/// Write `texture` as `NAME.png` into the lesson's picture folder, if it has one; returns the
/// file name for the pass note. Floats map as [`crate::gl::dump`] says.
pub fn picture(
    opts: &LessonOptions,
    name: &str,
    texture: &Texture,
    range: DumpRange,
) -> anyhow::Result<Option<String>> {
    let Some(dir) = &opts.png_dir else {
        return Ok(None);
    };
    let rgba = dump::to_rgba8(texture, range)?;
    let file = format!("{name}.png");
    let top_first = flip_rows(&rgba, texture.width() as usize * 4);
    crate::files::write_png(
        &dir.join(&file),
        &top_first,
        texture.width(),
        texture.height(),
    )?;
    Ok(Some(file))
}

/// Write `values` (`channels` per texel, `width x height`, rows from the bottom) as
/// `NAME.png`, mapped like a float texture.
pub fn picture_of_values(
    opts: &LessonOptions,
    name: &str,
    values: &[f32],
    (width, height, channels): (u32, u32, usize),
    range: DumpRange,
) -> anyhow::Result<Option<String>> {
    let Some(dir) = &opts.png_dir else {
        return Ok(None);
    };
    let rgba = dump::map_floats(values, channels, range);
    let file = format!("{name}.png");
    let top_first = flip_rows(&rgba, width as usize * 4);
    crate::files::write_png(&dir.join(&file), &top_first, width, height)?;
    Ok(Some(file))
}

fn flip_rows(rgba: &[u8], row: usize) -> Vec<u8> {
    rgba.chunks_exact(row).rev().flatten().copied().collect()
}

/// Record a pass: its name, shader file (empty for a copy or readback), what it does, and
/// the picture of its output.
pub fn pass(run: &mut LessonRun, name: &str, shader: &str, what: &str, picture: Option<String>) {
    if !shader.is_empty() && !run.shaders.iter().any(|s| s == shader) {
        run.shaders.push(shader.into());
    }
    run.passes.push(PassNote {
        name: name.into(),
        shader: shader.into(),
        what: what.into(),
        picture,
    });
}

/// The exercise `opts` asks for, checked to exist before anything runs.
pub fn exercise_asked(info: &LessonInfo, opts: &LessonOptions) -> anyhow::Result<()> {
    if let Some(n) = opts.exercise {
        if !info.exercises.iter().any(|e| e.number == n) {
            let numbers: Vec<String> = info
                .exercises
                .iter()
                .map(|e| e.number.to_string())
                .collect();
            bail!(
                "lesson {} has no exercise {n}; its exercises are: {}",
                info.id,
                numbers.join(", ")
            );
        }
    }
    Ok(())
}

/// The end of a run: the hint of the exercise that was run when a check failed, and a run
/// with no check at all is not a pass.
pub fn finish(mut run: LessonRun, info: &LessonInfo, opts: &LessonOptions) -> LessonRun {
    if run.checks.is_empty() {
        run.passed = false;
    }
    if let Some(n) = opts.exercise {
        if !run.passed {
            run.hint = info
                .exercises
                .iter()
                .find(|e| e.number == n)
                .map(|e| e.hint.to_string());
        }
    }
    run
}

/// Why the compute counterpart did not run on `ctx`, or `None` when it can.
pub fn compute_missing(ctx: &Context, what: &str) -> Option<String> {
    ctx.require_compute(what)
        .err()
        .map(|e| format!("not run: {e}"))
}

/// `n` pseudo-random values in [0, 1) from `seed` (a 32-bit xorshift): test data the CPU
/// makes, the same on every machine.
pub fn values(n: usize, seed: u32) -> Vec<f32> {
    let mut state = seed.max(1);
    (0..n)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state >> 8) as f32 / (1u32 << 24) as f32
        })
        .collect()
}

/// The largest absolute difference of two equally long arrays (infinite if the lengths
/// differ or a value is not finite).
pub fn max_abs_diff(a: &[f32], b: &[f32]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    a.iter().zip(b).fold(0.0, |m: f64, (&x, &y)| {
        let d = (x as f64 - y as f64).abs();
        if d.is_finite() {
            m.max(d)
        } else {
            f64::INFINITY
        }
    })
}

/// How many of the bytes of two float arrays differ (all of them if the lengths differ).
pub fn bytes_differing(a: &[f32], b: &[f32]) -> f64 {
    let (a, b): (&[u8], &[u8]) = (bytemuck::cast_slice(a), bytemuck::cast_slice(b));
    if a.len() != b.len() {
        return a.len().max(b.len()) as f64;
    }
    a.iter().zip(b).filter(|(x, y)| x != y).count() as f64
}
