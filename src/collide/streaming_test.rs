//! Streaming AABB overlap test [Sec. 5.2]: a `2^dX x 2^dY` rectangle (one tile of it) whose
//! pixel (j, i) pairs slot i of `S^X` with slot j of `S^Y`. The stencil buffer, filled from
//! the two stencil arrays, masks the virtual pairs (PAPs); the fragment program of paper
//! Table I (`cg_ports/collide_table1_streaming_aabb_test.frag`) does the interval test and
//! leaves 1 in `P0` for every colliding AABB pair (CAP). An occlusion query counts the CAPs.

use super::aabb_textures::AabbTextures;
use crate::gl::{
    Context, DrawState, Framebuffer, GlError, OcclusionQuery, Program, Rect, StencilTest, Texture,
    TextureFormat,
};
use crate::shader;

/// The pass that writes `P0` (named in errors).
pub const OVERLAP_PASS: &str = "streaming AABB test (Table I)";

/// The render target `P0` (R32F: one float per pair) with its depth-stencil buffer, reused
/// by every tile [Sec. 5.5].
pub struct PairTarget {
    pub p0: Texture,
    pub depth_stencil: Texture,
    pub framebuffer: Framebuffer,
}

impl PairTarget {
    /// `width` slots of Y (columns) by `height` slots of X (rows).
    pub fn new(ctx: &Context, width: usize, height: usize) -> Result<PairTarget, GlError> {
        let (w, h) = (width as u32, height as u32);
        let p0 = Texture::new_2d(ctx, w, h, TextureFormat::R32F)?;
        let depth_stencil = Texture::new_2d(ctx, w, h, TextureFormat::Depth24Stencil8)?;
        let framebuffer = Framebuffer::new(ctx, "P0", &[&p0], Some(&depth_stencil))?;
        Ok(PairTarget {
            p0,
            depth_stencil,
            framebuffer,
        })
    }

    pub fn width(&self) -> usize {
        self.p0.width() as usize
    }

    pub fn height(&self) -> usize {
        self.p0.height() as usize
    }
}

pub struct StreamingTest {
    overlap: Program,
    mask: Program,
    query: OcclusionQuery,
}

impl StreamingTest {
    pub fn new(ctx: &Context) -> Result<StreamingTest, GlError> {
        let overlap = Program::new(
            ctx,
            &[shader!("glsl/collide/aabb_pairs.vert")],
            &[shader!("cg_ports/collide_table1_streaming_aabb_test.frag")],
        )?;
        let mask = Program::rect(ctx, &[shader!("glsl/collide/stencil_mask.frag")])?;
        Ok(StreamingTest {
            overlap,
            mask,
            query: OcclusionQuery::new(ctx)?,
        })
    }

    /// Fill the stencil buffer of `target` from the stencil arrays of X (rows) and Y
    /// (columns): 1 where both slots take part, 0 elsewhere.
    pub fn set_stencil(
        &self,
        target: &PairTarget,
        x: &AabbTextures,
        y: &AabbTextures,
    ) -> Result<(), GlError> {
        // region: stencil-arrays
        target.framebuffer.clear_depth_stencil(1.0, 0)?;
        let mut pass = target.framebuffer.pass(&self.mask, "stencil arrays")?;
        pass.state(DrawState {
            stencil: Some(StencilTest::write(1)),
            color_write: false,
            ..DrawState::default()
        })
        .texture("u_stencil_a", &x.stencil)
        .texture("u_stencil_b", &y.stencil);
        pass.draw_full()
        // endregion
    }

    /// The overlap pass (Table I) over the stencil set by [`StreamingTest::set_stencil`];
    /// returns the number of CAPs.
    pub fn run(
        &self,
        target: &PairTarget,
        x: &AabbTextures,
        y: &AabbTextures,
    ) -> Result<u64, GlError> {
        self.run_on(target, x, y, None)
    }

    /// [`StreamingTest::run`] drawn over `rect` of `P0` only (all of it for `None`), after
    /// clearing the whole of `P0`.
    pub fn run_on(
        &self,
        target: &PairTarget,
        x: &AabbTextures,
        y: &AabbTextures,
        rect: Option<Rect>,
    ) -> Result<u64, GlError> {
        // region: overlap-pass
        target.framebuffer.clear_color(0, [0.0; 4])?;
        let mut pass = target.framebuffer.pass(&self.overlap, OVERLAP_PASS)?;
        pass.state(DrawState {
            stencil: Some(StencilTest::equal(1)),
            ..DrawState::default()
        })
        .texture("minTextureA", &x.t_min)
        .texture("maxTextureA", &x.t_max)
        .texture("minTextureB", &y.t_min)
        .texture("maxTextureB", &y.t_max);
        self.query.begin();
        let drawn = match rect {
            Some(rect) => pass.draw_rect(rect),
            None => pass.draw_full(),
        };
        self.query.end();
        drawn?;
        self.query.samples()
        // endregion
    }
}
