//! Two-dimensional integrals by buffer reduction [section 3.3, Fig. 2]. By default each
//! peel's three integrand targets are added into running sums (one blended pass) and the
//! sums are reduced once; in the paper's order (`PeelOrder::KeepLayers`) every kept layer
//! `T_k` and `T_w` is reduced on its own. Either way the reduction is ping-pong 2x2 sums,
//! the three targets at once (MRT), to one texel per body (per tile). (The GL layer's `Reducer` does the same for one texture at a time; doing
//! the three together saves two thirds of the passes of every buoyancy step.)

use super::integrands::TARGETS;
use crate::gl::reduce::passes_for;
use crate::gl::{
    Blend, Context, DrawState, Framebuffer, GlError, Program, Rect, Texture, TextureFormat,
};
use crate::shader;
use glam::IVec2;

/// The name of the reduction pass, whose sums are what the GPU path reads back.
pub const REDUCTION_PASS: &str = "mass: sum reduction";

/// The running sums over peels, and the reduction.
pub struct Accumulator {
    program: Program,
    /// sum0..2.
    target: Framebuffer,
    reduce_program: Program,
    /// Half-size targets for the reduction's ping-pong (three RGBA32F each).
    ping_pong: [Framebuffer; 2],
}

impl Accumulator {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<Accumulator, GlError> {
        let sums: Vec<Texture> = (0..TARGETS)
            .map(|_| Texture::new_2d(ctx, width, height, TextureFormat::Rgba32F))
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
    /// accumulator's size): 2x2 ping-pong passes that reduce the three targets at once
    /// (MRT), then one small read per target.
    pub fn reduce_from(
        &self,
        source_target: &Framebuffer,
        block: Option<u32>,
    ) -> Result<Vec<[[f64; 4]; TARGETS]>, GlError> {
        let (mut w, mut h) = (source_target.width(), source_target.height());
        let levels = match block {
            Some(b) => b.trailing_zeros(),
            None => passes_for(w, h),
        };
        let mut index = 0;
        for level in 0..levels {
            let (out_w, out_h) = (w.div_ceil(2), h.div_ceil(2));
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
                .uniform("u_source_size", IVec2::new(w as i32, h as i32));
            pass.draw_full()?;
            (w, h) = (out_w, out_h);
            index = 1 - index;
        }
        let result = if levels == 0 {
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
