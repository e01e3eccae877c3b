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
    Blend, Context, DrawState, Framebuffer, GlError, Program, Rect, Texture, TextureFormat,
};
use crate::shader;
use glam::IVec2;

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
    program: Program,
    /// sum0..2.
    target: Framebuffer,
    reduce_program: Program,
    /// Half-size targets for the reduction's ping-pong (three RGBA32F each; every pass at
    /// least halves).
    ping_pong: [Framebuffer; 2],
}

impl Accumulator {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<Accumulator, GlError> {
        Self::with_format(ctx, width, height, TextureFormat::Rgba32F)
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
        let sums: Vec<Texture> = (0..TARGETS)
            .map(|_| Texture::new_2d(ctx, width, height, format))
            .collect::<Result<_, _>>()?;
        let all: Vec<&Texture> = sums.iter().collect();
        let half = |name| -> Result<Framebuffer, GlError> {
            let (w, h) = (width.div_ceil(2).max(1), height.div_ceil(2).max(1));
            let t: Vec<Texture> = (0..TARGETS)
                .map(|_| Texture::new_2d(ctx, w, h, TextureFormat::Rgba32F))
                .collect::<Result<_, _>>()?;
            Framebuffer::new(ctx, name, &t.iter().collect::<Vec<_>>(), None)
        };
        Ok(Accumulator {
            program: Program::rect(ctx, &[shader!("glsl/mass/accumulate.frag")])?,
            target: Framebuffer::new(ctx, "mass: sums over peels", &all, None)?,
            reduce_program: Program::rect(ctx, &[shader!("glsl/mass/reduce_sum.frag")])?,
            ping_pong: [half("mass: reduction ping")?, half("mass: reduction pong")?],
        })
    }

    pub fn clear(&self) -> Result<(), GlError> {
        self.target.clear_colors([0.0; 4])
    }

    /// Adds one peel (`peel[0..3]` integrands) over the given tiles (the bodies that drew
    /// something in this peel; the rest of the target is left alone, which is most of it
    /// in the deep peels).
    pub fn add_peel(
        &self,
        peel: &[Texture],
        depth: &Texture,
        tiles: &[Rect],
    ) -> Result<(), GlError> {
        let mut pass = self.target.pass(&self.program, "mass: accumulate a peel")?;
        pass.state(DrawState {
            blend: Some(Blend::Add),
            ..DrawState::default()
        })
        .texture("u_peel_depth", depth)
        .texture("u_peel0", &peel[0])
        .texture("u_peel1", &peel[1])
        .texture("u_peel2", &peel[2]);
        for &tile in tiles {
            pass.draw_rect(tile)?;
        }
        Ok(())
    }

    /// The running sums' three textures (the water patch adds into them).
    pub fn sums(&self) -> &[Texture] {
        self.target.colors()
    }

    /// The running sums, reduced ([`Accumulator::reduce_from`]).
    pub fn reduce(&self, block: Option<u32>) -> Result<Vec<[[f64; 4]; TARGETS]>, GlError> {
        self.reduce_from(&self.target, block)
    }

    /// The three sums of every `block x block` tile (row by row from the bottom), or of the
    /// whole target when `block` is `None`, of `source` (three RGBA32F targets of the
    /// accumulator's size): ping-pong passes of [`fan_ins`] that reduce the three targets
    /// at once (MRT), then one small read per target.
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
        for (level, &fan_in) in levels.iter().enumerate() {
            let (out_w, out_h) = (w.div_ceil(fan_in), h.div_ceil(fan_in));
            let source = if level == 0 {
                source_target
            } else {
                &self.ping_pong[1 - index]
            };
            let mut pass = self.ping_pong[index].pass(&self.reduce_program, REDUCTION_PASS)?;
            pass.viewport(Rect::sized(out_w, out_h))
                .texture("u_source0", source.color(0))
                .texture("u_source1", source.color(1))
                .texture("u_source2", source.color(2))
                .uniform("u_source_size", IVec2::new(w as i32, h as i32))
                .uniform("u_fan_in", fan_in as i32);
            pass.draw_full()?;
            (w, h) = (out_w, out_h);
            index = 1 - index;
        }
        let result = if levels.is_empty() {
            source_target
        } else {
            &self.ping_pong[1 - index]
        };
        let per_target: Vec<Vec<f32>> = (0..TARGETS)
            .map(|i| result.read_f32(i, Rect::sized(w, h)))
            .collect::<Result<_, _>>()?;
        let texel = |t: usize, k: usize| -> [f64; 4] {
            std::array::from_fn(|c| per_target[t][4 * k + c] as f64)
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
