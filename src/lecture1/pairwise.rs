//! Pairwise triangle tests with the triangles in textures: a reconstruction of Choi, Kim &
//! Kim, "Rapid pairwise intersection tests using programmable GPUs", The Visual Computer
//! 22(2), 2006 (`lecture1-sources.md`, section 3; only its bibliographic record and paper 1's
//! description of it are public).
//!
//! Every triangle is three RGBA32F texels ([`TriangleTexture`]). A quad whose fragment
//! `(column j, row i)` tests triangle `i` of A against triangle `j` of B
//! (`glsl/lecture1/pair_test.frag`: box reject, then paper 1's exact test with each sign
//! filtered in fp32, discarding only pairs that are certainly disjoint) writes 1 to the pair
//! texture `P0`. Large counts are cut into tiles no larger than the texture limit; an
//! occlusion query counts each tile's reported pairs, and a tile with any is read back with
//! paper 1's hierarchical 4x4 encoding ([`crate::collide::reduction_gpu`]). The CPU then
//! confirms each reported pair with the exact predicate, which decides the pairs the fp32
//! filter could not (touching and coplanar ones). With one model, the quad is the `i < j`
//! half and triangles that share a (welded) vertex are skipped, as in [`super::self_collision`].

use super::weld::{share_vertex, weld};
use crate::collide::reduction::Scheme;
use crate::collide::reduction_gpu::Reduction;
use crate::collide::stream_setup::validate_mesh;
use crate::collide::streaming_test::PairTarget;
use crate::collide::{triangles_intersect, Predicate};
use crate::gl::{
    query::time_gpu, Context, GlError, OcclusionQuery, Program, Texture, TextureFormat,
};
use crate::mesh::Mesh;
use crate::shader;
use glam::{IVec2, Vec3};
use serde::Serialize;

/// Default tile side (pairs per side of `P0`): small enough for a software renderer's memory
/// and time, large enough that a thousand-triangle model is one tile.
pub const DEFAULT_TILE: usize = 1024;

/// Vertex ids travel as floats in the texels' w: exact below 2^24.
const MAX_VERTICES: usize = 1 << 24;

/// One model's triangles as texels: triangle `t` is texels `3 (t % per_row) + c`, `c = 0..3`,
/// of row `t / per_row`; xyz its corner `c`, w the corner's (welded) vertex id.
pub struct TriangleTexture {
    pub texture: Texture,
    pub per_row: usize,
    pub count: usize,
}

impl TriangleTexture {
    pub fn new(ctx: &Context, mesh: &Mesh) -> anyhow::Result<TriangleTexture> {
        anyhow::ensure!(
            mesh.positions.len() <= MAX_VERTICES,
            "{} vertices: the triangle texture holds vertex ids below 2^24",
            mesh.positions.len()
        );
        let limit = ctx.info().limits.max_texture_size as usize;
        let count = mesh.triangles.len();
        let per_row = count.min(limit / 3).max(1);
        let rows = count.div_ceil(per_row);
        if rows > limit {
            return Err(GlError::Limit(format!(
                "{count} triangles need a {} x {rows} triangle texture, larger than this \
                 renderer's {limit} x {limit}",
                3 * per_row
            ))
            .into());
        }
        // region: triangle-texture
        let mut texels = vec![0.0f32; 4 * 3 * per_row * rows];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for (c, &v) in tri.iter().enumerate() {
                let p = mesh.positions[v as usize];
                let at = 4 * ((t / per_row) * 3 * per_row + 3 * (t % per_row) + c);
                texels[at..at + 4].copy_from_slice(&[p.x, p.y, p.z, v as f32]);
            }
        }
        // endregion
        let texture = Texture::from_f32(
            ctx,
            (3 * per_row) as u32,
            rows as u32,
            TextureFormat::Rgba32F,
            &texels,
        )?;
        Ok(TriangleTexture {
            texture,
            per_row,
            count,
        })
    }
}

/// What one run found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct PairwiseResult {
    /// Pairs the GPU reported (may intersect), before the CPU's exact confirmation.
    pub candidates: usize,
    /// Tiles drawn.
    pub tiles: usize,
    /// Bytes read back by the hierarchical readback, all tiles.
    pub readback_bytes: u64,
    /// GPU time of the pair passes (timer queries), ms.
    pub test_ms: f64,
    /// Intersecting pairs `(i, j)` (i in A, j in B; with one model `i < j`, no neighbours),
    /// sorted.
    pub pairs: Vec<(u32, u32)>,
}

/// One tile's buffers after its pass and readback ([`PairwiseTester::first_tile`]).
pub struct TileBuffers {
    /// `P0`: texel (column j, row i) is 1 when pair (i, j) may intersect.
    pub target: PairTarget,
    /// `P1..P3`, the hierarchical 4x4 encoding of `P0`.
    pub reduction: Reduction,
    /// Pairs the occlusion query counted.
    pub reported: u64,
    /// The pairs the readback decoded, `(row i, column j)`, before the CPU's confirmation.
    pub candidates: Vec<(u32, u32)>,
}

/// The two sides of a pairwise query: models A and B, or one model against itself, welded
/// so that split copies of a vertex make neighbours.
pub(crate) enum Sides<'m> {
    Two(&'m Mesh, &'m Mesh),
    One(Mesh),
}

impl<'m> Sides<'m> {
    /// A against B, or (`b` = `None`) A welded against itself.
    pub(crate) fn of(a: &'m Mesh, b: Option<&'m Mesh>) -> Sides<'m> {
        match b {
            Some(b) => Sides::Two(a, b),
            None => Sides::One(weld(a)),
        }
    }

    /// A, B, and whether it is the self test (then A and B are the same model).
    pub(crate) fn pair(&self) -> (&Mesh, &Mesh, bool) {
        match self {
            Sides::Two(a, b) => (a, b, std::ptr::eq(*a, *b)),
            Sides::One(m) => (m, m, true),
        }
    }
}

/// The pair test: the program, `P0` with its reduction levels, and an occlusion query.
pub struct PairwiseTester {
    ctx: Context,
    program: Program,
    pub tile: usize,
    query: OcclusionQuery,
}

impl PairwiseTester {
    /// Tiles of at most `tile` x `tile` pairs (never above the texture or viewport limit).
    pub fn new(ctx: &Context, tile: usize) -> anyhow::Result<PairwiseTester> {
        anyhow::ensure!(tile > 0, "the tile side must be at least 1");
        let limits = &ctx.info().limits;
        let limit = (limits.max_texture_size as usize)
            .min(limits.max_viewport_dims[0] as usize)
            .min(limits.max_viewport_dims[1] as usize);
        Ok(PairwiseTester {
            ctx: ctx.clone(),
            program: Program::rect(
                ctx,
                &[
                    shader!("glsl/lecture1/pair_filter.glsl"),
                    shader!("glsl/lecture1/pair_test.frag"),
                ],
            )?,
            tile: tile.min(limit),
            query: OcclusionQuery::new(ctx)?,
        })
    }

    /// Every intersecting pair between A and B, or (`b` = `None`) within A.
    pub fn run(&self, a: &Mesh, b: Option<&Mesh>) -> anyhow::Result<PairwiseResult> {
        validate_mesh(a).map_err(|e| anyhow::anyhow!("model A: {e}"))?;
        if let Some(b) = b {
            validate_mesh(b).map_err(|e| anyhow::anyhow!("model B: {e}"))?;
        }
        let sides = Sides::of(a, b);
        let (a, b, self_test) = sides.pair();
        let tex_a = TriangleTexture::new(&self.ctx, a)?;
        let tex_b = if self_test {
            None
        } else {
            Some(TriangleTexture::new(&self.ctx, b)?)
        };
        let tex_b = tex_b.as_ref().unwrap_or(&tex_a);
        let (na, nb) = (tex_a.count, tex_b.count);
        let (h, w) = (na.min(self.tile), nb.min(self.tile));
        let target = PairTarget::new(&self.ctx, w, h)?;
        let reduction = Reduction::new(&self.ctx, w, h)?;
        let mut out = PairwiseResult::default();
        let mut candidates = Vec::new();
        for i0 in (0..na).step_by(h) {
            for j0 in (0..nb).step_by(w) {
                // One model: tiles wholly on or below the diagonal hold no pair i < j.
                if self_test && j0 + w <= i0 + 1 {
                    continue;
                }
                let (count, ms) = time_gpu(&self.ctx, || {
                    self.draw_tile(
                        &target,
                        (&tex_a, tex_b),
                        IVec2::new(i0 as i32, j0 as i32),
                        self_test,
                    )
                })?;
                out.tiles += 1;
                out.test_ms += ms;
                if count == 0 {
                    continue;
                }
                let readback = reduction.read(&self.ctx, &target, Scheme::Hierarchical)?;
                anyhow::ensure!(
                    readback.decoded.caps.len() as u64 == count,
                    "tile at ({i0}, {j0}): the readback decoded {} pairs, the occlusion query \
                     counted {count}",
                    readback.decoded.caps.len()
                );
                out.readback_bytes += readback.decoded.bytes;
                candidates.extend(
                    readback
                        .decoded
                        .caps
                        .iter()
                        .map(|&(row, col)| (i0 as u32 + row, j0 as u32 + col)),
                );
            }
        }
        out.candidates = candidates.len();
        out.pairs = confirm(a, b, self_test, &candidates);
        Ok(out)
    }

    /// The first tile's buffers, for pictures: `P0` of the tile of pairs starting at triangle
    /// 0 of A and of B (the whole pair quad when the models fit one tile), and its
    /// hierarchical levels after the readback.
    pub fn first_tile(&self, a: &Mesh, b: Option<&Mesh>) -> anyhow::Result<TileBuffers> {
        let sides = Sides::of(a, b);
        let (a, b, self_test) = sides.pair();
        let tex_a = TriangleTexture::new(&self.ctx, a)?;
        let tex_b = if self_test {
            None
        } else {
            Some(TriangleTexture::new(&self.ctx, b)?)
        };
        let tex_b = tex_b.as_ref().unwrap_or(&tex_a);
        let (h, w) = (tex_a.count.min(self.tile), tex_b.count.min(self.tile));
        let target = PairTarget::new(&self.ctx, w, h)?;
        let reduction = Reduction::new(&self.ctx, w, h)?;
        let count = self.draw_tile(&target, (&tex_a, tex_b), IVec2::ZERO, self_test)?;
        let readback = reduction.read(&self.ctx, &target, Scheme::Hierarchical)?;
        Ok(TileBuffers {
            target,
            reduction,
            reported: count,
            candidates: readback.decoded.caps,
        })
    }

    /// The pair quad over one tile; returns the number of pairs it reported.
    fn draw_tile(
        &self,
        target: &PairTarget,
        (a, b): (&TriangleTexture, &TriangleTexture),
        first: IVec2,
        self_test: bool,
    ) -> Result<u64, GlError> {
        // region: pair-test
        target.framebuffer.clear_color(0, [0.0; 4])?;
        let mut pass = target
            .framebuffer
            .pass(&self.program, "pairwise triangle test")?;
        pass.texture("u_tri_a", &a.texture)
            .texture("u_tri_b", &b.texture)
            .uniform("u_per_row_a", a.per_row as i32)
            .uniform("u_per_row_b", b.per_row as i32)
            .uniform("u_first", first)
            .uniform("u_count", IVec2::new(a.count as i32, b.count as i32))
            .uniform("u_self", self_test as i32);
        self.query.begin();
        let drawn = pass.draw_full();
        self.query.end();
        drawn?;
        self.query.samples()
        // endregion
    }
}

/// The exact predicate on every reported pair (the GPU's filter leaves touching and coplanar
/// pairs to it); sorted.
pub(super) fn confirm(
    a: &Mesh,
    b: &Mesh,
    self_test: bool,
    candidates: &[(u32, u32)],
) -> Vec<(u32, u32)> {
    // region: confirm
    let corners = |m: &Mesh, t: u32| -> [Vec3; 3] { m.triangle(t as usize) };
    let mut pairs: Vec<(u32, u32)> = candidates
        .iter()
        .copied()
        .filter(|&(i, j)| {
            !(self_test && share_vertex(&a.triangles[i as usize], &b.triangles[j as usize]))
                && triangles_intersect(&corners(a, i), &corners(b, j), Predicate::Exact)
        })
        .collect();
    pairs.sort_unstable();
    pairs
    // endregion
}
