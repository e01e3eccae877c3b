//! When peeling ends [section 3.2: the passes repeat until every surface fragment has been
//! found]. A peel that draws nothing shows that the one before was the last, but it costs
//! a whole draw of the body. Instead, each peel after the first counts in the stencil
//! every fragment that passes the peel and water tests at its pixel, the nearest and the
//! ones behind it alike (increment on depth pass and on depth fail). Where a pixel met
//! two or more, a layer lies behind the one just peeled; where none did, the body is
//! peeled through. A quad over each body's tile, drawn where the stencil is at least 2
//! inside its own occlusion query, says which bodies need another peel, in the same
//! scene as the peel itself, read with the peel's own queries.
//!
//! The test can only err towards one more peel (two fragments at exactly the same depth
//! count twice, and the next peel, which keeps strictly deeper fragments, draws
//! nothing); it never stops a body that still has a layer. Pass 1 keeps the paper's
//! faces-down bit in the stencil, so it does not count: a body that draws in pass 1 is
//! always peeled once more.

use crate::gl::{
    Buffer, BufferUsage, Compare, Context, DrawState, Framebuffer, GlError, OcclusionQuery,
    Primitive, Program, Rect, StencilOp, StencilTest, VertexArray,
};
use crate::shader;
use std::cell::RefCell;

/// The name of the test's pass (errors and the profile).
const PEEL_END_PASS: &str = "mass: another layer? (stencil count)";

/// Every fragment that reaches the stencil stage adds one to its pixel's count, whether it
/// then wins the depth test (the layer) or loses it (a layer behind).
pub fn counting() -> StencilTest {
    StencilTest {
        func: Compare::Always,
        reference: 0,
        read_mask: 0xff,
        fail: StencilOp::Keep,
        depth_fail: StencilOp::Increment,
        pass: StencilOp::Increment,
        write_mask: 0xff,
    }
}

/// Pixels whose count is at least 2: `2 <= stored`.
fn two_or_more() -> StencilTest {
    StencilTest {
        func: Compare::LessEqual,
        reference: 2,
        read_mask: 0xff,
        fail: StencilOp::Keep,
        depth_fail: StencilOp::Keep,
        pass: StencilOp::Keep,
        write_mask: 0,
    }
}

/// The tile quads of a batch's groups, and a query per group.
pub struct PeelEnd {
    ctx: Context,
    program: Program,
    quads: VertexArray,
    corners: Buffer,
    indices: Buffer,
    /// Per group, its range of `indices` (six per tile).
    ranges: RefCell<Vec<(usize, usize)>>,
    queries: RefCell<Vec<OcclusionQuery>>,
}

impl PeelEnd {
    pub fn new(ctx: &Context) -> Result<PeelEnd, GlError> {
        let program = Program::new(
            ctx,
            &[shader!("glsl/mass/peel_end.vert")],
            &[shader!("glsl/mass/peel_end.frag")],
        )?;
        let corners = Buffer::from_slice(ctx, &[0f32; 8], BufferUsage::Dynamic)?;
        let indices = Buffer::from_slice(ctx, &[0u32; 6], BufferUsage::Dynamic)?;
        let mut quads = VertexArray::new(ctx)?;
        quads.float_attribute(0, &corners, 2, 8, 0, 0)?;
        quads.set_index_buffer(&indices)?;
        Ok(PeelEnd {
            ctx: ctx.clone(),
            program,
            quads,
            corners,
            indices,
            ranges: RefCell::default(),
            queries: RefCell::default(),
        })
    }

    /// The tiles of each group (`tiles[g]`), in a target of `size` pixels.
    pub fn set_tiles(&self, tiles: &[Vec<Rect>], size: (u32, u32)) -> Result<(), GlError> {
        let (w, h) = (size.0 as f32, size.1 as f32);
        let (mut corners, mut indices, mut ranges) = (Vec::new(), Vec::new(), Vec::new());
        for group in tiles {
            let first = indices.len();
            for t in group {
                let base = (corners.len() / 2) as u32;
                let (x0, y0) = (2.0 * t.x as f32 / w - 1.0, 2.0 * t.y as f32 / h - 1.0);
                let (x1, y1) = (
                    2.0 * (t.x + t.w) as f32 / w - 1.0,
                    2.0 * (t.y + t.h) as f32 / h - 1.0,
                );
                corners.extend([x0, y0, x1, y0, x0, y1, x1, y1]);
                indices.extend([0, 1, 2, 2, 1, 3].map(|i| base + i));
            }
            ranges.push((first, indices.len() - first));
        }
        if !indices.is_empty() {
            self.corners.replace(&corners)?;
            self.indices.replace(&indices)?;
        }
        let mut queries = self.queries.borrow_mut();
        while queries.len() < tiles.len() {
            queries.push(OcclusionQuery::new(&self.ctx)?);
        }
        *self.ranges.borrow_mut() = ranges;
        Ok(())
    }

    /// After a counting peel into `target`: for each of `groups`, count the pixels of its
    /// tiles that met two or more fragments (read with [`PeelEnd::another_layer`]).
    pub fn test(&self, target: &Framebuffer, groups: &[usize]) -> Result<(), GlError> {
        let ranges = self.ranges.borrow();
        let picked: Vec<(usize, usize)> = groups.iter().map(|&g| ranges[g]).collect();
        let queries = self.queries.borrow();
        let mut pass = target.pass(&self.program, PEEL_END_PASS)?;
        pass.state(DrawState {
            stencil: Some(two_or_more()),
            color_write: false,
            ..DrawState::default()
        });
        pass.draw_elements_counted(&self.quads, Primitive::Triangles, &picked, &queries)
    }

    /// Whether each of the `groups` last tested has a layer behind the peel just drawn.
    pub fn another_layer(&self, groups: usize) -> Result<Vec<bool>, GlError> {
        let queries = self.queries.borrow();
        Ok(OcclusionQuery::samples_of(&queries[..groups])?
            .into_iter()
            .map(|pixels| pixels > 0)
            .collect())
    }
}
