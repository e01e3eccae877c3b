//! The diagram on the GPU (OpenGL 3.3), by either method:
//! - exact: one instanced draw, instance `i` covering the domain for site `i`; each
//!   fragment's exact distance to its site goes to `gl_FragDepth` (scaled into [0, 1] by the
//!   depth range);
//! - mesh: Hoff's distance meshes ([`super::mesh`]), one draw of every site's triangles, the
//!   depth interpolated from the vertices' distances.
//!
//! Either way the depth test (LESS, sites in id order) keeps the nearest, and the colour
//! target (RGBA32F) holds the site id and the distance.

use super::mesh::{self, DistanceMeshes};
use super::{Diagram, Domain, Site};
use crate::gl::{
    query::time_gpu, Buffer, BufferUsage, Compare, Context, DepthTest, DrawState, Framebuffer,
    GlError, Primitive, Program, Rect, Texture, TextureFormat, VertexArray,
};
use crate::shader;
use glam::DVec2;
use std::time::Instant;

/// Where the time went.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct VoronoiTimings {
    /// GPU time of the site pass (timer query), ms.
    pub pass_ms: f64,
    /// Wall-clock time of the readback, ms.
    pub readback_ms: f64,
    /// Triangles drawn: two per site's rectangle, or the distance meshes' triangles.
    pub triangles: usize,
    /// Wall-clock time of building and uploading the sites' texture or meshes, the targets'
    /// creation included, ms.
    pub upload_ms: f64,
}

/// How each site's distance reaches the depth buffer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// The exact distance per fragment, written to `gl_FragDepth`.
    Exact,
    /// Hoff's distance meshes within this many pixels of the distance.
    Mesh { error_pixels: f64 },
}

/// The site programs of one context.
pub struct VoronoiRasterizer {
    ctx: Context,
    program: Program,
    mesh_program: Program,
}

impl VoronoiRasterizer {
    pub fn new(ctx: &Context) -> Result<VoronoiRasterizer, GlError> {
        Ok(VoronoiRasterizer {
            ctx: ctx.clone(),
            program: Program::new(
                ctx,
                &[shader!("glsl/lecture1/voronoi_site.vert")],
                &[shader!("glsl/lecture1/voronoi_site.frag")],
            )?,
            mesh_program: Program::new(
                ctx,
                &[shader!("glsl/lecture1/voronoi_mesh.vert")],
                &[shader!("glsl/lecture1/voronoi_mesh.frag")],
            )?,
        })
    }

    /// The diagram of `sites` over `domain` at `n x n` pixels, exact per fragment.
    pub fn diagram(
        &self,
        sites: &[Site],
        domain: Domain,
        n: usize,
    ) -> anyhow::Result<(Diagram, VoronoiTimings)> {
        self.diagram_by(sites, domain, n, Method::Exact)
    }

    /// The diagram of `sites` over `domain` at `n x n` pixels by `method`.
    pub fn diagram_by(
        &self,
        sites: &[Site],
        domain: Domain,
        n: usize,
        method: Method,
    ) -> anyhow::Result<(Diagram, VoronoiTimings)> {
        anyhow::ensure!(!sites.is_empty(), "no site given");
        let limits = &self.ctx.info().limits;
        let side = (limits.max_texture_size as usize)
            .min(limits.max_viewport_dims[0] as usize)
            .min(limits.max_viewport_dims[1] as usize);
        anyhow::ensure!(
            (1..=side).contains(&n),
            "the resolution must be 1 to {side} on this renderer, not {n}"
        );
        let pixel = domain.pixel(n);
        let reach = depth_range(sites, domain);
        let upload = Instant::now();
        let meshes = match method {
            Method::Exact => None,
            Method::Mesh { error_pixels } => {
                Some(mesh::build(sites, domain, n, reach, error_pixels)?)
            }
        };
        // The mesh's rim lies beyond the reach: its depth must stay below the cleared 1.
        let depth_range = meshes
            .as_ref()
            .map_or(reach, |m| m.rim * pixel * (1.0 + 1e-6));
        let colour = Texture::new_2d(&self.ctx, n as u32, n as u32, TextureFormat::Rgba32F)?;
        let depth = Texture::new_2d(&self.ctx, n as u32, n as u32, TextureFormat::Depth32F)?;
        let framebuffer = Framebuffer::new(&self.ctx, "voronoi", &[&colour], Some(&depth))?;
        let mut timings = VoronoiTimings::default();
        let depth_test = DrawState {
            depth: Some(DepthTest {
                func: Compare::Less,
                write: true,
            }),
            ..DrawState::default()
        };
        let ((), ms) = match &meshes {
            None => {
                let texture = site_texture(&self.ctx, sites, domain, pixel)?;
                timings.upload_ms = upload.elapsed().as_secs_f64() * 1e3;
                time_gpu(&self.ctx, || {
                    framebuffer.clear_color(0, [-1.0, 0.0, 0.0, 0.0])?;
                    framebuffer.clear_depth_stencil(1.0, 0)?;
                    let mut pass = framebuffer.pass(&self.program, "voronoi sites")?;
                    pass.state(depth_test)
                        .texture("u_sites", &texture.texture)
                        .uniform("u_per_row", texture.per_row as i32)
                        .uniform("u_depth_scale", (pixel / depth_range) as f32)
                        .uniform("u_pixel", pixel as f32);
                    pass.draw_attributeless(Primitive::TriangleStrip, 4, sites.len())
                })?
            }
            Some(m) => {
                let vertices = mesh_vertices(&self.ctx, m)?;
                timings.upload_ms = upload.elapsed().as_secs_f64() * 1e3;
                time_gpu(&self.ctx, || {
                    framebuffer.clear_color(0, [-1.0, 0.0, 0.0, 0.0])?;
                    framebuffer.clear_depth_stencil(1.0, 0)?;
                    let mut pass = framebuffer.pass(&self.mesh_program, "voronoi meshes")?;
                    pass.state(depth_test)
                        .uniform("u_size", glam::Vec2::splat(n as f32))
                        .uniform("u_depth_scale", (pixel / depth_range) as f32)
                        .uniform("u_pixel", pixel as f32);
                    pass.draw_arrays(&vertices, Primitive::Triangles, 0, m.vertices.len())
                })?
            }
        };
        timings.pass_ms = ms;
        timings.triangles = meshes
            .as_ref()
            .map_or(2 * sites.len(), |m| m.vertices.len() / 3);
        let start = Instant::now();
        let texels = framebuffer.read_f32(0, Rect::sized(n as u32, n as u32))?;
        timings.readback_ms = start.elapsed().as_secs_f64() * 1e3;
        let mut site = Vec::with_capacity(n * n);
        let mut distance = Vec::with_capacity(n * n);
        for (i, t) in texels.chunks_exact(4).enumerate() {
            anyhow::ensure!(
                t[0] >= 0.0 && (t[0] as usize) < sites.len() && t[1].is_finite(),
                "pixel {i}: the GPU gave site {} at distance {}; no site won it",
                t[0],
                t[1]
            );
            site.push(t[0] as u32);
            distance.push(t[1]);
        }
        Ok((
            Diagram {
                n,
                domain,
                site,
                distance,
                depth_range,
                mesh_error: meshes.as_ref().map_or(0.0, |m| m.error_bound * pixel),
                coverage_error: match meshes {
                    Some(_) => super::coverage_error(self.ctx.subpixel_bits(), pixel),
                    None => 0.0,
                },
            },
            timings,
        ))
    }
}

/// The meshes' vertices in a vertex array (attribute 0, four floats).
fn mesh_vertices(ctx: &Context, meshes: &DistanceMeshes) -> anyhow::Result<VertexArray> {
    let buffer = Buffer::from_slice(ctx, &meshes.vertices, BufferUsage::Static)?;
    let mut vertices = VertexArray::new(ctx)?;
    vertices.float_attribute(0, &buffer, 4, 16, 0, 0)?;
    Ok(vertices)
}

/// The largest distance from the domain to a site (input units): no site is farther from a
/// domain point than from the farthest corner pair, so depth = distance / range is in [0, 1].
pub fn depth_range(sites: &[Site], domain: Domain) -> f64 {
    let min = DVec2::from(domain.min);
    let corners = [
        min,
        min + DVec2::new(domain.size, 0.0),
        min + DVec2::new(0.0, domain.size),
        min + DVec2::splat(domain.size),
    ];
    let far = sites
        .iter()
        .flat_map(|s| s.corners())
        .flat_map(|s| corners.map(|c| (c - s).length()))
        .fold(0.0, f64::max);
    // A little beyond, so that the farthest point stays below the cleared depth 1.
    far * (1.0 + 1e-6) + domain.size * 1e-6
}

struct SiteTexture {
    texture: Texture,
    per_row: usize,
}

/// Two texels per site, coordinates in pixels from the domain's corner: (ax, ay, bx, by),
/// (cx, cy, kind, 0); unused corners repeat the first.
fn site_texture(
    ctx: &Context,
    sites: &[Site],
    domain: Domain,
    pixel: f64,
) -> anyhow::Result<SiteTexture> {
    let limit = ctx.info().limits.max_texture_size as usize;
    let per_row = sites.len().min(limit / 2).max(1);
    let rows = sites.len().div_ceil(per_row);
    anyhow::ensure!(
        rows <= limit,
        "{} sites need a texture larger than this renderer's {limit} x {limit}",
        sites.len()
    );
    let min = DVec2::from(domain.min);
    let mut texels = vec![0.0f32; 8 * per_row * rows];
    for (i, s) in sites.iter().enumerate() {
        let c = s.corners();
        let at = |k: usize| {
            let p = (c[k.min(c.len() - 1)] - min) / pixel;
            [p.x as f32, p.y as f32]
        };
        let (a, b, cc) = (at(0), at(1), at(2));
        let base = 4 * ((i / per_row) * 2 * per_row + 2 * (i % per_row));
        texels[base..base + 8].copy_from_slice(&[
            a[0],
            a[1],
            b[0],
            b[1],
            cc[0],
            cc[1],
            s.kind() as f32,
            0.0,
        ]);
    }
    if texels.iter().any(|v| !v.is_finite()) {
        anyhow::bail!("a site's coordinates in pixels are not finite in fp32");
    }
    Ok(SiteTexture {
        texture: Texture::from_f32(
            ctx,
            (2 * per_row) as u32,
            rows as u32,
            TextureFormat::Rgba32F,
            &texels,
        )?,
        per_row,
    })
}
