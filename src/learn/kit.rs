//! What the lessons share beside [`super::LessonRun`]: a texture read back for its pass's
//! picture, the exercise asked for, the compute counterpart's absence, and test data the CPU
//! makes.

use super::{LessonInfo, LessonOptions, PassBuffer};
use crate::gl::{Context, Texture, TextureFormat, TimerQuery};
use crate::timing::{Runs, Spread};
use anyhow::bail;
use serde::Serialize;
use std::time::Instant;

/// What `texture` holds, read back for its pass's picture: floats as they are, a byte format
/// as 0..1, a packed depth-stencil texture as its depth in 0..1, integers as their values.
pub fn buffer(texture: &Texture) -> anyhow::Result<PassBuffer> {
    let (width, height) = (texture.width(), texture.height());
    let channels = texture.format().components();
    Ok(match texture.format() {
        TextureFormat::R8 | TextureFormat::Rgba8 => {
            PassBuffer::bytes(width, height, channels, &texture.download_u8()?)
        }
        TextureFormat::Depth24Stencil8 => {
            let depth = texture.download_u32()?;
            let depth = depth.into_iter().map(|v| (v >> 8) as f32 / 16_777_215.0);
            PassBuffer::floats(width, height, 1, depth.collect())
        }
        TextureFormat::Rgba32Ui => {
            let values = texture.download_u32()?.into_iter().map(|v| v as f32);
            PassBuffer::floats(width, height, channels, values.collect())
        }
        _ => PassBuffer::floats(width, height, channels, texture.download_f32()?),
    })
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

/// How a time was taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Clock {
    /// A GL timer query (TIME_ELAPSED) around the passes.
    TimerQuery,
    /// Wall clock between two glFinish calls: used where the renderer's timer query reads
    /// under a tenth of it (llvmpipe answers about zero around a compute dispatch).
    FinishedWall,
}

impl Clock {
    pub fn in_words(&self) -> &'static str {
        match self {
            Clock::TimerQuery => "timer query",
            Clock::FinishedWall => "glFinish wall clock",
        }
    }
}

/// Time `work` (GPU passes, nothing read back) as `runs` says: a timer query and the wall
/// clock between two glFinish calls around each run; the timer query's times unless they read
/// under a tenth of the wall clock's (llvmpipe answers about zero around a compute dispatch).
pub fn time_passes(
    ctx: &Context,
    runs: Runs,
    mut work: impl FnMut() -> anyhow::Result<()>,
) -> anyhow::Result<(Spread, Clock)> {
    let pairs = runs.run(|_| -> anyhow::Result<(f64, f64)> {
        let query = TimerQuery::new(ctx)?;
        ctx.finish_all();
        let start = Instant::now();
        query.begin();
        let done = work();
        query.end();
        ctx.finish_all();
        let wall = start.elapsed().as_secs_f64() * 1e3;
        done?;
        Ok((query.milliseconds()?, wall))
    })?;
    let (queried, wall): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
    let (queried, wall) = (Spread::of(&queried), Spread::of(&wall));
    Ok(if queried.median >= 0.1 * wall.median {
        (queried, Clock::TimerQuery)
    } else {
        (wall, Clock::FinishedWall)
    })
}

/// Wall-clock milliseconds of `work` between two glFinish calls, as `runs` says (a path that
/// reads back: the CPU's wait is part of it).
pub fn time_finished(
    ctx: &Context,
    runs: Runs,
    mut work: impl FnMut() -> anyhow::Result<()>,
) -> anyhow::Result<Spread> {
    let times = runs.run(|_| -> anyhow::Result<f64> {
        ctx.finish_all();
        let start = Instant::now();
        work()?;
        ctx.finish_all();
        Ok(start.elapsed().as_secs_f64() * 1e3)
    })?;
    Ok(Spread::of(&times))
}
