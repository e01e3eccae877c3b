//! Self-collision of a deforming mesh with paper 1's streaming AABBs (a reconstruction: the
//! lecture names the problem, the pipeline is paper 1's with one model against itself).
//!
//! Stream setup, texture download, stream update and the streaming AABB test are paper 1's
//! ([`crate::collide`]), with one stream instead of two. The tree is tested against itself
//! without its diagonal: only tiles on or above the diagonal are drawn, and on a diagonal
//! tile a second stencil pass (`glsl/lecture1/diagonal_mask.frag`) clears the pairs on and
//! below it, so every pair of distinct leaves is tested once. The diagonal itself (each leaf
//! against itself, whose boxes always overlap) goes straight to the primitive test. The
//! primitive test is paper 1's exact predicate on the CPU, skipping pairs of triangles that
//! share a vertex (the model welded by position first, [`super::weld`]).

use super::weld::{share_vertex, weld};
use crate::collide::aabb_textures::AabbTextures;
use crate::collide::reduction::Scheme;
use crate::collide::reduction_gpu::{paper_switch, ReadbackMode, Reduction};
use crate::collide::stream_setup::{validate_mesh, AabbStream};
use crate::collide::stream_update::StreamUpdate;
use crate::collide::streaming_test::{PairTarget, StreamingTest};
use crate::collide::tiles::TileLayout;
use crate::collide::vertex_textures::VertexTexture;
use crate::collide::{triangles_intersect, Predicate};
use crate::gl::{Context, DrawState, GlError, Program, StencilTest};
use crate::mesh::Mesh;
use crate::shader;
use glam::Vec3;
use serde::Serialize;

/// The user's choices.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// `n`: the most triangles per leaf.
    pub leaf_size: usize,
    /// Any readback mode but `auto` (which needs paper 1's calibration).
    pub readback: ReadbackMode,
    /// Largest tile side (slots), at most the texture limit.
    pub max_tile: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            leaf_size: crate::collide::stream_setup::DEFAULT_LEAF_SIZE,
            readback: ReadbackMode::PaperSwitch,
            max_tile: crate::collide::pipeline::DEFAULT_MAX_TILE,
        }
    }
}

/// What one frame found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct SelfFrame {
    /// Colliding AABB pairs of distinct leaves (from the GPU).
    pub caps: usize,
    /// Triangle pairs given to the primitive test (CAPs and the diagonal), neighbours
    /// included.
    pub pctps: u64,
    /// Tiles drawn (those on or above the diagonal).
    pub tiles: usize,
    /// Intersecting triangle pairs `(i, j)`, `i < j`, that share no vertex, sorted.
    pub pairs: Vec<(u32, u32)>,
}

/// One model's stream on the GPU, tested against itself.
pub struct SelfCollider {
    ctx: Context,
    options: Options,
    /// The welded model (triangle order kept).
    pub mesh: Mesh,
    pub stream: AabbStream,
    pub layout: TileLayout,
    segments: Vec<(AabbTextures, VertexTexture)>,
    pub target: PairTarget,
    pub reduction: Reduction,
    test: StreamingTest,
    update: StreamUpdate,
    diagonal_mask: Program,
}

impl SelfCollider {
    /// Stream setup (paper 1's preprocess) for `mesh`, welded by position first.
    pub fn new(ctx: &Context, mesh: &Mesh, options: Options) -> anyhow::Result<SelfCollider> {
        validate_mesh(mesh)?;
        anyhow::ensure!(
            options.readback != ReadbackMode::Auto,
            "self-collision: readback 'auto' needs paper 1's calibration; choose \
             hierarchical, reduced, full or paper-switch"
        );
        let mesh = weld(mesh);
        let stream = AabbStream::build(&mesh, options.leaf_size)?;
        let limit = ctx.info().limits.max_texture_size as usize;
        let layout = TileLayout::new(stream.len(), stream.len(), options.max_tile.min(limit))?;
        let segments = (0..layout.segments[0])
            .map(|s| {
                let range = layout.segment(s, stream.len());
                Ok((
                    AabbTextures::new(ctx, &stream, range.clone())?,
                    VertexTexture::new(ctx, &stream, range)?,
                ))
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        let side = segments[0].0.t_min.width() as usize;
        Ok(SelfCollider {
            ctx: ctx.clone(),
            options,
            target: PairTarget::new(ctx, side, side)?,
            reduction: Reduction::new(ctx, side, side)?,
            mesh,
            stream,
            layout,
            segments,
            test: StreamingTest::new(ctx)?,
            update: StreamUpdate::new(ctx)?,
            diagonal_mask: Program::rect(ctx, &[shader!("glsl/lecture1/diagonal_mask.frag")])?,
        })
    }

    /// One frame: the deformed vertices in, every intersecting pair of non-neighbours out.
    pub fn frame(&mut self, positions: &[Vec3]) -> anyhow::Result<SelfFrame> {
        check_positions(positions, self.mesh.positions.len())?;
        // Texture download, then stream update.
        for (aabb, vertices) in &mut self.segments {
            vertices.upload(positions)?;
            self.update.run(vertices, aabb)?;
        }
        // Streaming AABB test over the tiles on and above the diagonal.
        let mut out = SelfFrame::default();
        let mut caps = Vec::new();
        let n = self.layout.segments[0];
        for a in 0..n {
            for b in a..n {
                self.tile(a, b, &mut caps)?;
                out.tiles += 1;
            }
        }
        out.caps = caps.len();
        // Primitive-level test: the CAPs, then every leaf against itself.
        let corners: Vec<[Vec3; 3]> = self
            .mesh
            .triangles
            .iter()
            .map(|t| t.map(|v| positions[v as usize]))
            .collect();
        let leaves = &self.stream.leaves;
        let mut pairs = Vec::new();
        for &(la, lb) in &caps {
            let (ta, tb) = (
                &leaves[la as usize].triangles,
                &leaves[lb as usize].triangles,
            );
            out.pctps += (ta.len() * tb.len()) as u64;
            for &i in ta {
                for &j in tb {
                    self.test_pair(&corners, i, j, &mut pairs);
                }
            }
        }
        for leaf in leaves {
            let t = &leaf.triangles;
            out.pctps += (t.len() * t.len().saturating_sub(1) / 2) as u64;
            for (k, &i) in t.iter().enumerate() {
                for &j in &t[k + 1..] {
                    self.test_pair(&corners, i, j, &mut pairs);
                }
            }
        }
        pairs.sort_unstable();
        out.pairs = pairs;
        Ok(out)
    }

    fn test_pair(&self, corners: &[[Vec3; 3]], i: u32, j: u32, pairs: &mut Vec<(u32, u32)>) {
        let t = &self.mesh.triangles;
        if !share_vertex(&t[i as usize], &t[j as usize])
            && triangles_intersect(&corners[i as usize], &corners[j as usize], Predicate::Exact)
        {
            pairs.push((i.min(j), i.max(j)));
        }
    }

    /// Tile `(a, b)`, `a <= b`: segment `a` of the stream (rows) against segment `b`
    /// (columns); the CAPs as leaf pairs.
    fn tile(&self, a: usize, b: usize, caps: &mut Vec<(u32, u32)>) -> anyhow::Result<()> {
        let (rows, _) = &self.segments[a];
        let (columns, _) = &self.segments[b];
        self.test.set_stencil(&self.target, rows, columns)?;
        if a == b {
            self.mask_diagonal()?;
        }
        let count = self.test.run(&self.target, rows, columns)?;
        if count == 0 {
            return Ok(());
        }
        let side = self.target.width();
        let scheme = self.scheme(count as f64 / (side * side) as f64);
        let readback = self.reduction.read(&self.ctx, &self.target, scheme)?;
        anyhow::ensure!(
            readback.decoded.caps.len() as u64 == count,
            "tile ({a}, {b}): the {scheme:?} readback decoded {} CAPs, the occlusion query \
             counted {count}",
            readback.decoded.caps.len()
        );
        let (row0, col0) = (a * self.layout.tile, b * self.layout.tile);
        for &(row, col) in &readback.decoded.caps {
            let la = self.stream.slot_leaf[row0 + row as usize];
            let lb = self.stream.slot_leaf[col0 + col as usize];
            caps.push((la, lb));
        }
        Ok(())
    }

    /// Clear the stencil on and below the diagonal of a diagonal tile.
    fn mask_diagonal(&self) -> Result<(), GlError> {
        let mut pass = self
            .target
            .framebuffer
            .pass(&self.diagonal_mask, "diagonal mask (self-collision)")?;
        pass.state(DrawState {
            stencil: Some(StencilTest::write(0)),
            color_write: false,
            ..DrawState::default()
        });
        pass.draw_full()
    }

    fn scheme(&self, eta: f64) -> Scheme {
        match self.options.readback {
            ReadbackMode::Hierarchical => Scheme::Hierarchical,
            ReadbackMode::Reduced => Scheme::Reduced,
            ReadbackMode::Full => Scheme::Full,
            ReadbackMode::PaperSwitch | ReadbackMode::Auto => paper_switch(eta),
        }
    }

    pub fn context(&self) -> &Context {
        &self.ctx
    }
}

/// The positions must match the model and be finite.
pub fn check_positions(positions: &[Vec3], expected: usize) -> anyhow::Result<()> {
    anyhow::ensure!(
        positions.len() == expected,
        "{} positions given, the model has {expected} vertices",
        positions.len()
    );
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        anyhow::bail!("vertex {i} is not finite ({:?})", positions[i]);
    }
    Ok(())
}
