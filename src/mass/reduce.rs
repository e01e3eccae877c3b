//! Two-dimensional integrals by buffer reduction [section 3.3, Fig. 2]. By default each
//! peel's three integrand targets are added into running sums (one blended pass) and the
//! sums are reduced once; in the paper's order (`PeelOrder::KeepLayers`) every kept layer
//! `T_k` and `T_w` is reduced on its own. Either way the reduction is ping-pong block sums,
//! the three targets at once (MRT), to one texel per body (per tile). (The GL layer's
//! `Reducer` does the same for one texture at a time; doing the three together saves two
//! thirds of the passes of every buoyancy step.)
//!
//! Each pass reads "two or more values" per output [3.3]: here blocks of up to 8 x 8, so a
//! 32 x 32 tile is one texel after two passes (8 x 8, then 4 x 4) instead of five 2 x 2
//! ones. The sums are the same up to fp32 rounding; the passes are fewer, and each pass
//! has a fixed cost that a software rasterizer pays in full (its scene is binned,
//! rasterized and waited for before the next pass may read it).

use super::integrands::TARGETS;
use crate::gl::reduce::passes_for;
use crate::gl::{
    Blend, Context, DrawState, Framebuffer, GlError, Program, Rect, ShaderSource, Texture,
    TextureFormat,
};
use crate::shader;
use glam::IVec2;
use std::cell::RefCell;
use std::collections::BTreeMap;

/// The name of the reduction pass, whose sums are what the GPU path reads back.
pub const REDUCTION_PASS: &str = "mass: sum reduction";

/// The widest block one reduction pass sums: 2^3 = 8 texels a side.
const MAX_FAN_IN_LOG2: u32 = 3;

/// The side of the blocks each pass sums, to reduce a side of `2^bits` texels: as few
/// passes as `MAX_FAN_IN_LOG2` allows, the bits shared evenly (32: 8 then 4; 64: 8 then
/// 8), and at least one pass.
pub fn fan_ins(bits: u32) -> Vec<u32> {
    let passes = bits.div_ceil(MAX_FAN_IN_LOG2).max(1);
    (0..passes)
        .map(|i| 1 << (bits / passes + u32::from(i < bits % passes)).max(1))
        .collect()
}

/// The running sums over peels, and the reduction.
pub struct Accumulator {
    ctx: Context,
    /// How many integrand targets (3: eq. 4 and 6; 1: eq. 4).
    targets: usize,
    program: Program,
    /// sum0..2 (or sum0 alone).
    target: Framebuffer,
    /// The reduction program of each fan-in used so far (compiled in: made on first use).
    reduce_programs: RefCell<BTreeMap<u32, Program>>,
    /// Half-size targets for the reduction's ping-pong (three RGBA32F each; every pass at
    /// least halves).
    ping_pong: [Framebuffer; 2],
}

/// The generated `#define` lines the accumulation and reduction shaders are compiled after.
fn defines(targets: usize, fan_in: Option<u32>) -> String {
    let mut s = format!("#define TARGETS {targets}\n");
    if let Some(k) = fan_in {
        s += &format!("#define FAN_IN {k}\n");
    }
    s
}

/// A rectangle program of `file` compiled after `defines`.
fn program_with(ctx: &Context, defines: &str, file: ShaderSource) -> Result<Program, GlError> {
    let header = ShaderSource {
        name: "mass: target count and fan-in (generated)",
        source: defines,
    };
    Program::rect(ctx, &[header, file])
}

impl Accumulator {
    /// Running sums of the three targets of eq. 4 and 6.
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<Accumulator, GlError> {
        Accumulator::with(ctx, width, height, TARGETS, TextureFormat::Rgba32F)
    }

    /// Running sums stored as `format`: RGBA16F is what a GeForce 7800 could blend into
    /// (it blended no 32-bit float target), each addition rounded to half precision. The
    /// reduction's ping-pong stays RGBA32F (it draws without blending).
    pub fn with_format(
        ctx: &Context,
        width: u32,
        height: u32,
        format: TextureFormat,
    ) -> Result<Accumulator, GlError> {
        Accumulator::with(ctx, width, height, TARGETS, format)
    }

    /// Running sums of `targets` (1 or 3) integrand targets.
    pub fn with_targets(
        ctx: &Context,
        width: u32,
        height: u32,
        targets: usize,
    ) -> Result<Accumulator, GlError> {
        Accumulator::with(ctx, width, height, targets, TextureFormat::Rgba32F)
    }

    /// Running sums of `targets` (1 or 3) integrand targets, stored as `format`.
    pub fn with(
        ctx: &Context,
        width: u32,
        height: u32,
        targets: usize,
        format: TextureFormat,
    ) -> Result<Accumulator, GlError> {
        if targets != 1 && targets != TARGETS {
            return Err(GlError::Invalid(format!(
                "mass: {targets} integrand targets (1 or {TARGETS})"
            )));
        }
        let sums: Vec<Texture> = (0..targets)
            .map(|_| Texture::new_2d(ctx, width, height, format))
            .collect::<Result<_, _>>()?;
        let all: Vec<&Texture> = sums.iter().collect();
        let half = |name| -> Result<Framebuffer, GlError> {
            let (w, h) = (width.div_ceil(2).max(1), height.div_ceil(2).max(1));
            let t: Vec<Texture> = (0..targets)
                .map(|_| Texture::new_2d(ctx, w, h, TextureFormat::Rgba32F))
                .collect::<Result<_, _>>()?;
            Framebuffer::new(ctx, name, &t.iter().collect::<Vec<_>>(), None)
        };
        Ok(Accumulator {
            ctx: ctx.clone(),
            targets,
            program: program_with(
                ctx,
                &defines(targets, None),
                shader!("glsl/mass/accumulate.frag"),
            )?,
            target: Framebuffer::new(ctx, "mass: sums over peels", &all, None)?,
            reduce_programs: RefCell::new(BTreeMap::new()),
            ping_pong: [half("mass: reduction ping")?, half("mass: reduction pong")?],
        })
    }

    /// How many integrand targets it sums.
    pub fn targets(&self) -> usize {
        self.targets
    }

    /// The reduction program summing `fan_in x fan_in` blocks, compiled on first use.
    fn reduce_program(&self, fan_in: u32) -> Result<std::cell::Ref<'_, Program>, GlError> {
        if !self.reduce_programs.borrow().contains_key(&fan_in) {
            let program = program_with(
                &self.ctx,
                &defines(self.targets, Some(fan_in)),
                shader!("glsl/mass/reduce_sum.frag"),
            )?;
            self.reduce_programs.borrow_mut().insert(fan_in, program);
        }
        Ok(std::cell::Ref::map(self.reduce_programs.borrow(), |m| {
            &m[&fan_in]
        }))
    }

    pub fn clear(&self) -> Result<(), GlError> {
        self.target.clear_colors([0.0; 4])
    }

    /// Adds one peel (`peel[0..targets]` integrands) over the given tiles (the bodies that drew
    /// something in this peel; the rest of the target is left alone, which is most of it
    /// in the deep peels).
    pub fn add_peel(
        &self,
        peel: &[Texture],
        depth: &Texture,
        tiles: &[Rect],
    ) -> Result<(), GlError> {
        // region: add-peel
        let mut pass = self.target.pass(&self.program, "mass: accumulate a peel")?;
        pass.state(DrawState {
            blend: Some(Blend::Add),
            ..DrawState::default()
        })
        .texture("u_peel_depth", depth);
        for (k, texture) in peel.iter().take(self.targets).enumerate() {
            pass.texture(&format!("u_peel{k}"), texture);
        }
        for &tile in tiles {
            pass.draw_rect(tile)?;
        }
        Ok(())
        // endregion
    }

    /// The running sums' textures (the water patch adds into them).
    pub fn sums(&self) -> &[Texture] {
        self.target.colors()
    }

    /// The running sums, reduced ([`Accumulator::reduce_from`]).
    pub fn reduce(&self, block: Option<u32>) -> Result<Vec<[[f64; 4]; TARGETS]>, GlError> {
        self.reduce_from(&self.target, block)
    }

    /// The sums of every `block x block` tile (row by row from the bottom), or of the
    /// whole target when `block` is `None`, of `source` (the accumulator's count of RGBA32F
    /// targets, of its size): ping-pong passes of [`fan_ins`] that reduce the targets at
    /// once (MRT), then one small read per target. Targets the accumulator does not sum
    /// (eq. 6's, with one target) read as zero.
    pub fn reduce_from(
        &self,
        source_target: &Framebuffer,
        block: Option<u32>,
    ) -> Result<Vec<[[f64; 4]; TARGETS]>, GlError> {
        let (mut w, mut h) = (source_target.width(), source_target.height());
        let levels = match block {
            Some(b) if b <= 1 => Vec::new(),
            Some(b) => fan_ins(b.trailing_zeros()),
            None => fan_ins(passes_for(w, h)),
        };
        let mut index = 0;
        // region: reduce-passes
        for (level, &fan_in) in levels.iter().enumerate() {
            let (out_w, out_h) = (w.div_ceil(fan_in), h.div_ceil(fan_in));
            let source = if level == 0 {
                source_target
            } else {
                &self.ping_pong[1 - index]
            };
            let program = self.reduce_program(fan_in)?;
            let mut pass = self.ping_pong[index].pass(&program, REDUCTION_PASS)?;
            pass.viewport(Rect::sized(out_w, out_h))
                .uniform("u_source_size", IVec2::new(w as i32, h as i32));
            for k in 0..self.targets {
                pass.texture(&format!("u_source{k}"), source.color(k));
            }
            pass.draw_full()?;
            (w, h) = (out_w, out_h);
            index = 1 - index;
        }
        // endregion
        let result = if levels.is_empty() {
            source_target
        } else {
            &self.ping_pong[1 - index]
        };
        let per_target: Vec<Vec<f32>> = (0..self.targets)
            .map(|i| result.read_f32(i, Rect::sized(w, h)))
            .collect::<Result<_, _>>()?;
        let texel = |t: usize, k: usize| -> [f64; 4] {
            per_target.get(t).map_or([0.0; 4], |sums| {
                std::array::from_fn(|c| sums[4 * k + c] as f64)
            })
        };
        Ok((0..(w * h) as usize)
            .map(|k| [texel(0, k), texel(1, k), texel(2, k)])
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each pass sums 2..=8 texels a side, the passes together exactly 2^bits, in as few
    /// passes as 8 x 8 blocks allow.
    #[test]
    fn fan_ins_cover_the_side_in_the_fewest_passes() {
        assert_eq!(fan_ins(5), [8, 4]);
        assert_eq!(fan_ins(1), [2]);
        assert_eq!(fan_ins(0), [2]);
        for bits in 1..=16 {
            let f = fan_ins(bits);
            assert!(f.iter().all(|&k| (2..=8).contains(&k)), "{bits}: {f:?}");
            assert_eq!(f.iter().product::<u32>(), 1 << bits, "{bits}: {f:?}");
            assert_eq!(f.len() as u32, bits.div_ceil(3), "{bits}: {f:?}");
        }
    }
}
