//! The CULLIDE baseline (the paper's reference 4, Govindaraju, Redon, Lin & Manocha 2003;
//! Sec. 7.4.2): image-space culling with occlusion queries, then the exact triangle test on what is left.
//!
//! A sub-object is *fully visible* with respect to a set when none of its fragments lies at
//! or behind the set's depth: render the set into the depth buffer, then draw the sub-object
//! with depth test GEQUAL and no depth writes inside an occlusion query; zero samples means
//! fully visible, and a fully visible sub-object cannot touch the set (CULLIDE's lemma).
//! Per orthographic view along x, y and z, two passes: X's candidates against Y's (Y drawn
//! first), then Y's against X's (the reverse order); what is fully visible is pruned from
//! the potentially colliding set (PCS). Pruning runs at object level, then at sub-object
//! level (the AABB-tree leaves, i.e. triangle groups), then per triangle; the survivors of
//! X and Y are then tested pair by pair with the pipeline's triangle test.
//!
//! The views sample the scene at pixel centres, so a collision that covers no pixel centre
//! in some view is pruned by mistake: CULLIDE misses pairs, which [`CullideResult`] counts
//! against the exact answer. The view volume is the overlap of the two global boxes.

use super::aabb::Aabb;
use super::stream_setup::AabbStream;
use super::tri_test::{triangles_intersect, Predicate};
use crate::gl::{
    Compare, Context, DrawState, Framebuffer, GlError, MeshBuffers, OcclusionQuery, Primitive,
    Program, Texture, TextureFormat,
};
use crate::mesh::Mesh;
use crate::shader;
use glam::{Mat4, Vec3, Vec4};
use std::ops::Range;
use std::time::Instant;

/// The paper's CULLIDE resolution.
pub const PAPER_RESOLUTION: u32 = 512;

/// One model on the GPU, its triangles reordered so that each leaf is one index range.
struct CullideModel {
    buffers: MeshBuffers,
    /// Triangle index (in the mesh) at each position of the index buffer.
    order: Vec<u32>,
    /// Leaf `l` covers positions `groups[l]`.
    groups: Vec<Range<usize>>,
}

impl CullideModel {
    fn new(ctx: &Context, mesh: &Mesh, stream: &AabbStream) -> Result<CullideModel, GlError> {
        let mut order = Vec::with_capacity(mesh.triangles.len());
        let mut groups = Vec::with_capacity(stream.leaves.len());
        for leaf in &stream.leaves {
            let start = order.len();
            order.extend(&leaf.triangles);
            groups.push(start..order.len());
        }
        let triangles: Vec<[u32; 3]> = order.iter().map(|&t| mesh.triangles[t as usize]).collect();
        let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.to_array()).collect();
        Ok(CullideModel {
            buffers: MeshBuffers::new(ctx, &positions, &triangles)?,
            order,
            groups,
        })
    }
}

/// What one CULLIDE frame did.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct CullideResult {
    /// Surviving triangles of X and Y after the three pruning levels.
    pub survivors: [usize; 2],
    /// Triangle pairs given to the exact test: survivors of X times survivors of Y.
    pub pctps: u64,
    /// Pairs found, `(triangle of X, triangle of Y)`, sorted.
    #[serde(skip)]
    pub pairs: Vec<(u32, u32)>,
    pub ctps: usize,
    /// Wall time of the pruning (vertex upload, visibility passes, query results), ms.
    pub pruning_ms: f64,
    pub tri_test_ms: f64,
    pub queries: usize,
}

/// What is left of X and Y: index ranges of their potentially colliding sets.
type PcsPair = (Vec<Range<usize>>, Vec<Range<usize>>);

/// CULLIDE between two deforming meshes.
pub struct Cullide {
    ctx: Context,
    target: Framebuffer,
    program: Program,
    x: CullideModel,
    y: CullideModel,
    triangles: [Vec<[u32; 3]>; 2],
    queries: Vec<OcclusionQuery>,
    pub resolution: u32,
}

impl Cullide {
    /// `x`, `y` with their AABB streams (whose leaves are CULLIDE's sub-objects).
    pub fn new(
        ctx: &Context,
        x: (&Mesh, &AabbStream),
        y: (&Mesh, &AabbStream),
        resolution: u32,
    ) -> Result<Cullide, GlError> {
        // Depth only: the passes write no colour, so the target has no colour attachment.
        let depth = Texture::new_2d(ctx, resolution, resolution, TextureFormat::Depth32F)?;
        let target = Framebuffer::new(ctx, "CULLIDE view", &[], Some(&depth))?;
        let program = Program::new(
            ctx,
            &[shader!("glsl/collide/cullide.vert")],
            &[shader!("glsl/collide/cullide.frag")],
        )?;
        Ok(Cullide {
            ctx: ctx.clone(),
            target,
            program,
            x: CullideModel::new(ctx, x.0, x.1)?,
            y: CullideModel::new(ctx, y.0, y.1)?,
            triangles: [x.0.triangles.clone(), y.0.triangles.clone()],
            queries: Vec::new(),
            resolution,
        })
    }

    /// A warm-up before timed frames: the object level's passes only (the same program,
    /// states and target as every level, so the shader variants are compiled and the target
    /// touched), and an occlusion query for every triangle, the most any level can ask for.
    /// A whole frame would do the leaf and triangle levels too, for nothing.
    pub fn warm_up(&mut self, positions_x: &[Vec3], positions_y: &[Vec3]) -> Result<(), GlError> {
        let most = self.x.order.len().max(self.y.order.len());
        while self.queries.len() < most {
            self.queries.push(OcclusionQuery::new(&self.ctx)?);
        }
        let mut queries = 0;
        self.prune_levels(positions_x, positions_y, 1, &mut queries)?;
        Ok(())
    }

    /// One frame: prune, then test the surviving triangle pairs.
    pub fn frame(
        &mut self,
        positions_x: &[Vec3],
        positions_y: &[Vec3],
        predicate: Predicate,
    ) -> Result<CullideResult, GlError> {
        let start = Instant::now();
        let mut out = CullideResult::default();
        let Some((pcs_x, pcs_y)) =
            self.prune_levels(positions_x, positions_y, 3, &mut out.queries)?
        else {
            out.pruning_ms = start.elapsed().as_secs_f64() * 1e3;
            return Ok(out);
        };
        out.pruning_ms = start.elapsed().as_secs_f64() * 1e3;
        // The exact test on every pair of surviving triangles.
        let t = Instant::now();
        let tris = |m: &CullideModel, pcs: &[Range<usize>]| -> Vec<u32> {
            pcs.iter()
                .flat_map(|r| m.order[r.clone()].iter().copied())
                .collect()
        };
        let (sx, sy) = (tris(&self.x, &pcs_x), tris(&self.y, &pcs_y));
        out.survivors = [sx.len(), sy.len()];
        out.pctps = (sx.len() * sy.len()) as u64;
        let corners = |tri: [u32; 3], p: &[Vec3]| tri.map(|v| p[v as usize]);
        let cy: Vec<[Vec3; 3]> = sy
            .iter()
            .map(|&b| corners(self.triangles[1][b as usize], positions_y))
            .collect();
        for &a in &sx {
            let ta = corners(self.triangles[0][a as usize], positions_x);
            for (k, tb) in cy.iter().enumerate() {
                if triangles_intersect(&ta, tb, predicate) {
                    out.pairs.push((a, sy[k]));
                }
            }
        }
        out.pairs.sort_unstable();
        out.ctps = out.pairs.len();
        out.tri_test_ms = t.elapsed().as_secs_f64() * 1e3;
        Ok(out)
    }

    /// The pruning of the first `levels` levels (object, sub-object, triangle): the
    /// potentially colliding sets of X and Y left, or `None` when the global boxes do not
    /// overlap (nothing is drawn then).
    fn prune_levels(
        &mut self,
        positions_x: &[Vec3],
        positions_y: &[Vec3],
        levels: usize,
        queries: &mut usize,
    ) -> Result<Option<PcsPair>, GlError> {
        let gx = Aabb::from_points(positions_x.iter().copied());
        let gy = Aabb::from_points(positions_y.iter().copied());
        if !gx.overlaps(&gy) {
            return Ok(None);
        }
        let view_box = Aabb {
            min: gx.min.max(gy.min),
            max: gx.max.min(gy.max),
        };
        let flat = |p: &[Vec3]| p.iter().map(|v| v.to_array()).collect::<Vec<_>>();
        self.x.buffers.update_positions(&flat(positions_x))?;
        self.y.buffers.update_positions(&flat(positions_y))?;
        // Object level, sub-object (leaf) level, triangle level.
        // Object level: each model is one sub-object.
        let whole = |n: usize| -> Vec<Range<usize>> { std::iter::once(0..n).collect() };
        let mut pcs_x = whole(self.x.order.len());
        let mut pcs_y = whole(self.y.order.len());
        for level in 0..levels {
            if level > 0 {
                pcs_x = refine(&pcs_x, &self.x.groups, level);
                pcs_y = refine(&pcs_y, &self.y.groups, level);
            }
            let most = pcs_x.len().max(pcs_y.len());
            while self.queries.len() < most {
                self.queries.push(OcclusionQuery::new(&self.ctx)?);
            }
            for axis in 0..3 {
                let mvp = axis_view(&view_box, axis);
                pcs_x = self.prune(&self.x, &pcs_x, &self.y, &pcs_y, mvp, queries)?;
                pcs_y = self.prune(&self.y, &pcs_y, &self.x, &pcs_x, mvp, queries)?;
                if pcs_x.is_empty() || pcs_y.is_empty() {
                    break;
                }
            }
        }
        if pcs_x.is_empty() || pcs_y.is_empty() {
            pcs_x.clear();
            pcs_y.clear();
        }
        Ok(Some((pcs_x, pcs_y)))
    }

    /// One pass: draw `occluder`'s candidates into depth, then keep the candidates of
    /// `tested` that are not fully visible with respect to them.
    fn prune(
        &self,
        tested: &CullideModel,
        candidates: &[Range<usize>],
        occluder: &CullideModel,
        occluders: &[Range<usize>],
        mvp: Mat4,
        queries: &mut usize,
    ) -> Result<Vec<Range<usize>>, GlError> {
        self.target.clear_depth_stencil(1.0, 0)?;
        {
            let mut pass = self.target.pass(&self.program, "CULLIDE occluders")?;
            pass.uniform("u_mvp", mvp)
                .state(DrawState::depth_only(Compare::Less, true));
            pass.draw_element_ranges(
                occluder.buffers.vertex_array(),
                Primitive::Triangles,
                &index_ranges(&merge_ranges(occluders)),
            )?;
        }
        let mut pass = self
            .target
            .pass(&self.program, "CULLIDE visibility queries")?;
        pass.uniform("u_mvp", mvp)
            .state(DrawState::depth_only(Compare::GreaterEqual, false));
        // One query per candidate, all issued before any is read.
        pass.draw_elements_counted(
            tested.buffers.vertex_array(),
            Primitive::Triangles,
            &index_ranges(candidates),
            &self.queries,
        )?;
        drop(pass);
        *queries += candidates.len();
        let samples = OcclusionQuery::samples_of(&self.queries[..candidates.len()])?;
        Ok(candidates
            .iter()
            .zip(samples)
            .filter(|&(_, s)| s > 0)
            .map(|(r, _)| r.clone())
            .collect())
    }
}

/// Triangle ranges as (first index, index count) of a triangle list.
fn index_ranges(triangles: &[Range<usize>]) -> Vec<(usize, usize)> {
    triangles
        .iter()
        .map(|r| (3 * r.start, 3 * r.len()))
        .collect()
}

/// Split each surviving range into the next level's sub-objects: leaves (level 1) or single
/// triangles (level 2).
fn refine(pcs: &[Range<usize>], groups: &[Range<usize>], level: usize) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    for r in pcs {
        if level == 1 {
            out.extend(
                groups
                    .iter()
                    .filter(|g| g.start >= r.start && g.end <= r.end)
                    .cloned(),
            );
        } else {
            out.extend(r.clone().map(|p| p..p + 1));
        }
    }
    out
}

/// Adjacent ranges drawn as one call.
fn merge_ranges(ranges: &[Range<usize>]) -> Vec<Range<usize>> {
    let mut out: Vec<Range<usize>> = Vec::new();
    for r in ranges {
        match out.last_mut() {
            Some(last) if last.end == r.start => last.end = r.end,
            _ => out.push(r.clone()),
        }
    }
    out
}

/// Orthographic view along `axis`: the other two axes span the image, `axis` is the depth,
/// and `b` (slightly enlarged so touching models are not clipped) fills the view volume.
fn axis_view(b: &Aabb, axis: usize) -> Mat4 {
    let pad = (b.extent().max_element() * 1e-3).max(1e-6);
    let (lo, hi) = (b.min - Vec3::splat(pad), b.max + Vec3::splat(pad));
    let row = |k: usize| {
        let mut r = Vec4::ZERO;
        let s = 2.0 / (hi[k] - lo[k]);
        r[k] = s;
        r.w = -lo[k] * s - 1.0;
        r
    };
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    Mat4::from_cols(row(u), row(v), row(axis), Vec4::W).transpose()
}
