//! Step 4, "graphics hardware speeds up the queries on the swept surfaces" (which query is not
//! public; CULLIDE, by a co-author of the same years, is the likely one, and is what runs
//! here, a reconstruction). The swept capsule bounds of the links the BVH kept are one set,
//! the environment triangles near them the other. Per orthographic view along x, y and z, one
//! set is drawn into the depth buffer and each member of the other is drawn with the depth
//! test GEQUAL inside an occlusion query: a member none of whose fragments lies at or behind
//! the set is fully visible and cannot touch it, and is pruned; then the roles swap.
//!
//! Pixel sampling makes plain CULLIDE miss contacts; as in R-CULLIDE, both sets are drawn
//! grown by ε, at least half a pixel's diagonal: a capsule's radius grows by ε and its hull
//! is an octagonal prism around it; a triangle becomes the prism of its ε-offset (or its box
//! grown by ε when it is a sliver). If a link's bound and a triangle meet at q, the ray
//! through the pixel centre nearest q's image passes within ε of q, inside both grown
//! hulls, and the link's hull leaves that ball behind the triangle's nearest depth: a
//! fragment the query counts. So nothing in contact is pruned.

use super::body::Capsule;
use super::sweep_bound::capsule_box;
use crate::gl::{
    query::time_gpu, Compare, Context, DrawState, Framebuffer, GlError, MeshBuffers,
    OcclusionQuery, Primitive, Program, Texture, TextureFormat,
};
use crate::shader;
use glam::{DVec3, Mat4, Vec4};
use std::ops::Range;

/// Default pixels per side of the views.
pub const DEFAULT_RESOLUTION: u32 = 64;

/// What the visibility passes left.
#[derive(Clone, Debug, Default)]
pub struct Survivors {
    /// Positions (in the input list) of the links not pruned.
    pub links: Vec<usize>,
    /// Positions (in the input list) of the triangles not pruned.
    pub triangles: Vec<usize>,
    /// Occlusion queries issued.
    pub queries: usize,
    /// The growth ε of both sets (half a pixel's diagonal or more).
    pub epsilon: f64,
    /// GPU time of the passes (timer queries), ms.
    pub gpu_ms: f64,
}

/// The depth target, program and queries of the visibility passes.
pub struct VisibilityCuller {
    ctx: Context,
    target: Framebuffer,
    program: Program,
    queries: Vec<OcclusionQuery>,
    pub resolution: u32,
}

/// Hulls of both sets in one mesh: object `k` of a set is the triangle range `ranges[k]`.
struct Hulls {
    positions: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    links: Vec<Range<usize>>,
    environment: Vec<Range<usize>>,
}

impl VisibilityCuller {
    pub fn new(ctx: &Context, resolution: u32) -> Result<VisibilityCuller, GlError> {
        if !(8..=ctx.info().limits.max_texture_size).contains(&resolution) {
            return Err(GlError::Limit(format!(
                "a visibility resolution of {resolution}: it must be at least 8 and at most \
                 the renderer's texture size {}",
                ctx.info().limits.max_texture_size
            )));
        }
        let depth = Texture::new_2d(ctx, resolution, resolution, TextureFormat::Depth32F)?;
        Ok(VisibilityCuller {
            ctx: ctx.clone(),
            target: Framebuffer::new(ctx, "avatar visibility view", &[], Some(&depth))?,
            program: Program::new(
                ctx,
                &[shader!("glsl/lecture1/avatar_visibility.vert")],
                &[shader!("glsl/lecture1/avatar_visibility.frag")],
            )?,
            queries: Vec::new(),
            resolution,
        })
    }

    /// Prune the links' swept bounds and the triangles against each other.
    pub fn cull(
        &mut self,
        links: &[Capsule],
        triangles: &[[DVec3; 3]],
    ) -> Result<Survivors, GlError> {
        let mut out = Survivors::default();
        let box_of = |boxes: &mut dyn Iterator<Item = (DVec3, DVec3)>| {
            boxes.fold(
                (DVec3::INFINITY, DVec3::NEG_INFINITY),
                |(lo, hi), (a, b)| (lo.min(a), hi.max(b)),
            )
        };
        let links_box = box_of(&mut links.iter().map(capsule_box));
        let triangles_box = box_of(
            &mut triangles
                .iter()
                .map(|t| (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]))),
        );
        let (lo, hi) = (
            links_box.0.max(triangles_box.0),
            links_box.1.min(triangles_box.1),
        );
        if links.is_empty() || triangles.is_empty() || lo.cmpgt(hi).any() {
            return Ok(out);
        }
        // ε: a pixel's diagonal over the overlap box (at least half the diagonal of the
        // views' pixels, which cover that box grown by ε, for 8 or more pixels a side), plus
        // room for the hulls' rounding to f32.
        let n = self.resolution as f64;
        let extent = hi - lo;
        let across = (0..3)
            .map(|k| {
                let (u, v) = ((k + 1) % 3, (k + 2) % 3);
                extent[u].hypot(extent[v])
            })
            .fold(0.0, f64::max);
        let scale = lo.abs().max(hi.abs()).max_element().max(1e-30);
        let epsilon = across / n + 1e-5 * scale;
        out.epsilon = epsilon;
        let hulls = hulls(links, triangles, epsilon);
        let buffers = MeshBuffers::new(&self.ctx, &hulls.positions, &hulls.triangles)?;
        let (depth_lo, depth_hi) =
            hulls
                .positions
                .iter()
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), p| {
                    let p = DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64);
                    (a.min(p), b.max(p))
                });
        let most = links.len().max(triangles.len());
        while self.queries.len() < most {
            self.queries.push(OcclusionQuery::new(&self.ctx)?);
        }
        let mut pcs_links: Vec<usize> = (0..links.len()).collect();
        let mut pcs_triangles: Vec<usize> = (0..triangles.len()).collect();
        let ((), ms) = time_gpu(&self.ctx, || {
            for axis in 0..3 {
                let mvp = axis_view(
                    lo - DVec3::splat(epsilon),
                    hi + DVec3::splat(epsilon),
                    (depth_lo[axis], depth_hi[axis]),
                    axis,
                );
                pcs_links = self.prune(
                    &buffers,
                    (&hulls.links, &pcs_links),
                    (&hulls.environment, &pcs_triangles),
                    mvp,
                    &mut out.queries,
                )?;
                pcs_triangles = self.prune(
                    &buffers,
                    (&hulls.environment, &pcs_triangles),
                    (&hulls.links, &pcs_links),
                    mvp,
                    &mut out.queries,
                )?;
                if pcs_links.is_empty() || pcs_triangles.is_empty() {
                    pcs_links.clear();
                    pcs_triangles.clear();
                    break;
                }
            }
            Ok(())
        })?;
        out.gpu_ms = ms;
        out.links = pcs_links;
        out.triangles = pcs_triangles;
        Ok(out)
    }

    /// One pass: the occluders' hulls into depth, then keep the tested objects with a
    /// fragment at or behind them.
    fn prune(
        &self,
        buffers: &MeshBuffers,
        (tested, candidates): (&[Range<usize>], &[usize]),
        (occluder, occluders): (&[Range<usize>], &[usize]),
        mvp: Mat4,
        queries: &mut usize,
    ) -> Result<Vec<usize>, GlError> {
        self.target.clear_depth_stencil(1.0, 0)?;
        {
            let mut pass = self
                .target
                .pass(&self.program, "avatar visibility occluders")?;
            pass.uniform("u_mvp", mvp)
                .state(DrawState::depth_only(Compare::Less, true));
            let ranges: Vec<(usize, usize)> = occluders
                .iter()
                .map(|&k| index_range(&occluder[k]))
                .collect();
            pass.draw_element_ranges(buffers.vertex_array(), Primitive::Triangles, &ranges)?;
        }
        let mut pass = self
            .target
            .pass(&self.program, "avatar visibility queries")?;
        pass.uniform("u_mvp", mvp)
            .state(DrawState::depth_only(Compare::GreaterEqual, false));
        let ranges: Vec<(usize, usize)> = candidates
            .iter()
            .map(|&k| index_range(&tested[k]))
            .collect();
        pass.draw_elements_counted(
            buffers.vertex_array(),
            Primitive::Triangles,
            &ranges,
            &self.queries,
        )?;
        drop(pass);
        *queries += candidates.len();
        let samples = OcclusionQuery::samples_of(&self.queries[..candidates.len()])?;
        Ok(candidates
            .iter()
            .zip(samples)
            .filter(|&(_, s)| s > 0)
            .map(|(&k, _)| k)
            .collect())
    }
}

/// A triangle range as (first index, index count).
fn index_range(r: &Range<usize>) -> (usize, usize) {
    (3 * r.start, 3 * r.len())
}

/// The orthographic view along `axis`: the image over `[lo, hi]`'s other two axes, the depth
/// over `depth`.
fn axis_view(lo: DVec3, hi: DVec3, depth: (f64, f64), axis: usize) -> Mat4 {
    let pad = ((depth.1 - depth.0).abs() * 1e-3).max(1e-6);
    let (mut lo, mut hi) = (lo, hi);
    lo[axis] = depth.0 - pad;
    hi[axis] = depth.1 + pad;
    let row = |k: usize| {
        let mut r = Vec4::ZERO;
        let s = 2.0 / (hi[k] - lo[k]);
        r[k] = s as f32;
        r.w = (-lo[k] * s - 1.0) as f32;
        r
    };
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    Mat4::from_cols(row(u), row(v), row(axis), Vec4::W).transpose()
}

/// The closed hulls: an octagonal prism around each capsule grown by ε, the prism of each
/// triangle's ε-offset (its box grown by ε for slivers).
fn hulls(links: &[Capsule], triangles: &[[DVec3; 3]], epsilon: f64) -> Hulls {
    let mut h = Hulls {
        positions: Vec::new(),
        triangles: Vec::new(),
        links: Vec::new(),
        environment: Vec::new(),
    };
    for c in links {
        let start = h.triangles.len();
        capsule_prism(&mut h, c, epsilon);
        h.links.push(start..h.triangles.len());
    }
    for t in triangles {
        let start = h.triangles.len();
        triangle_prism(&mut h, t, epsilon);
        h.environment.push(start..h.triangles.len());
    }
    h
}

/// Sides around the capsule's axis.
const SIDES: usize = 8;

/// An octagonal prism holding the capsule of radius `radius + ε`: the octagon circumscribes
/// the circle, and the ends stand that radius beyond the segment's ends.
fn capsule_prism(h: &mut Hulls, c: &Capsule, epsilon: f64) {
    let r = c.radius + epsilon;
    let axis = c.b - c.a;
    let d = if axis.length() > 0.0 {
        axis.normalize()
    } else {
        DVec3::Y
    };
    let u = d.any_orthonormal_vector();
    let w = d.cross(u);
    let ring = r / (std::f64::consts::PI / SIDES as f64).cos();
    let base = h.positions.len() as u32;
    for end in [c.a - d * r, c.b + d * r] {
        for k in 0..SIDES {
            let angle = std::f64::consts::TAU * k as f64 / SIDES as f64;
            push(h, end + (u * angle.cos() + w * angle.sin()) * ring);
        }
    }
    let s = SIDES as u32;
    for k in 0..s {
        let (k1, k2) = (k, (k + 1) % s);
        h.triangles.push([base + k1, base + k2, base + s + k2]);
        h.triangles.push([base + k1, base + s + k2, base + s + k1]);
    }
    for k in 1..s - 1 {
        h.triangles.push([base, base + k + 1, base + k]);
        h.triangles.push([base + s, base + s + k, base + s + k + 1]);
    }
}

/// The prism of the triangle's ε-offset (its edges moved out by ε in its plane, then ±ε
/// along its normal): it holds every point within ε of the triangle.
fn triangle_prism(h: &mut Hulls, t: &[DVec3; 3], epsilon: f64) {
    let [a, b, c] = *t;
    let n = (b - a).cross(c - a);
    let (la, lb, lc) = ((c - b).length(), (a - c).length(), (b - a).length());
    let perimeter = la + lb + lc;
    let inradius = if perimeter > 0.0 {
        n.length() / perimeter
    } else {
        0.0
    };
    // A sliver's offset corners run far out: its box is the tighter hull then.
    if inradius < 0.25 * epsilon {
        let lo = a.min(b).min(c) - DVec3::splat(epsilon);
        let hi = a.max(b).max(c) + DVec3::splat(epsilon);
        return box_hull(h, lo, hi);
    }
    let centre = (a * la + b * lb + c * lc) / perimeter;
    let grow = (inradius + epsilon) / inradius;
    let lift = n.normalize() * epsilon;
    let base = h.positions.len() as u32;
    for side in [-1.0, 1.0] {
        for v in [a, b, c] {
            push(h, centre + (v - centre) * grow + lift * side);
        }
    }
    h.triangles.push([base, base + 2, base + 1]);
    h.triangles.push([base + 3, base + 4, base + 5]);
    for k in 0..3 {
        let (k1, k2) = (k, (k + 1) % 3);
        h.triangles.push([base + k1, base + k2, base + 3 + k2]);
        h.triangles.push([base + k1, base + 3 + k2, base + 3 + k1]);
    }
}

/// The closed box `[lo, hi]`.
fn box_hull(h: &mut Hulls, lo: DVec3, hi: DVec3) {
    let base = h.positions.len() as u32;
    for k in 0..8 {
        let pick = |bit: usize, axis: usize| {
            if k & (1 << bit) != 0 {
                hi[axis]
            } else {
                lo[axis]
            }
        };
        push(h, DVec3::new(pick(0, 0), pick(1, 1), pick(2, 2)));
    }
    const FACES: [[u32; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    for f in FACES {
        h.triangles.push([base + f[0], base + f[1], base + f[2]]);
        h.triangles.push([base + f[0], base + f[2], base + f[3]]);
    }
}

/// A hull corner, rounded outward would be the strict choice; ε's f32 room covers it.
fn push(h: &mut Hulls, p: DVec3) {
    h.positions.push([p.x as f32, p.y as f32, p.z as f32]);
}
