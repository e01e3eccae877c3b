//! Two-dimensional integrals by buffer reduction [section 3.3, Fig. 2]: each peel's three
//! integrand targets are added into running sums (one blended pass), and the sums are then
//! reduced by the GL layer's ping-pong reduction, to one texel per body (per tile).

use super::integrands::TARGETS;
use crate::gl::reduce::{ReduceOp, Reducer};
use crate::gl::{Blend, Context, DrawState, Framebuffer, GlError, Program, Texture, TextureFormat};
use crate::shader;

/// The running sums over peels, and the faces-down mark of the first peel.
pub struct Accumulator {
    program: Program,
    /// sum0..2 and the first peel's faces-down mark.
    target: Framebuffer,
    /// sum0..2 alone, for the water patch (which reads the mark).
    sums_only: Framebuffer,
    reducer: Reducer,
}

impl Accumulator {
    pub fn new(ctx: &Context, width: u32, height: u32) -> Result<Accumulator, GlError> {
        let sums: Vec<Texture> = (0..TARGETS)
            .map(|_| Texture::new_2d(ctx, width, height, TextureFormat::Rgba32F))
            .collect::<Result<_, _>>()?;
        let mark = Texture::new_2d(ctx, width, height, TextureFormat::R32F)?;
        let all: Vec<&Texture> = sums.iter().chain([&mark]).collect();
        Ok(Accumulator {
            program: Program::rect(ctx, &[shader!("glsl/mass/accumulate.frag")])?,
            target: Framebuffer::new(ctx, "mass: sums over peels", &all, None)?,
            sums_only: Framebuffer::new(
                ctx,
                "mass: sums (water patch)",
                &sums.iter().collect::<Vec<_>>(),
                None,
            )?,
            reducer: Reducer::new(ctx, width, height)?,
        })
    }

    pub fn clear(&self) -> Result<(), GlError> {
        self.target.clear_colors([0.0; 4])
    }

    /// Adds one peel (`peel[0..3]` integrands, `peel[3]` faces-down mark).
    pub fn add_peel(&self, peel: &[Texture], first: bool) -> Result<(), GlError> {
        let mut pass = self.target.pass(&self.program, "mass: accumulate a peel")?;
        pass.state(DrawState {
            blend: Some(Blend::Add),
            ..DrawState::default()
        })
        .texture("peel0", &peel[0])
        .texture("peel1", &peel[1])
        .texture("peel2", &peel[2])
        .texture("peel_faces_down", &peel[3])
        .uniform("first_peel", first);
        pass.draw_full()
    }

    /// Where the water patch adds its integrands.
    pub fn sums_target(&self) -> &Framebuffer {
        &self.sums_only
    }

    /// The first peel's faces-down mark (the paper's stencil bit).
    pub fn first_peel_faces_down(&self) -> &Texture {
        self.target.color(TARGETS)
    }

    /// The three sums of every `block x block` tile (row by row from the bottom), or of the
    /// whole target when `block` is `None`.
    pub fn reduce(&self, block: Option<u32>) -> Result<Vec<[[f64; 4]; TARGETS]>, GlError> {
        let mut per_target = Vec::with_capacity(TARGETS);
        for i in 0..TARGETS {
            let texture = self.target.color(i);
            per_target.push(match block {
                Some(b) => self.reducer.reduce_blocks(texture, ReduceOp::Sum, b)?,
                None => vec![self.reducer.reduce(texture, ReduceOp::Sum)?],
            });
        }
        let widen = |v: [f32; 4]| v.map(|c| c as f64);
        Ok((0..per_target[0].len())
            .map(|k| {
                [
                    widen(per_target[0][k]),
                    widen(per_target[1][k]),
                    widen(per_target[2][k]),
                ]
            })
            .collect())
    }
}
