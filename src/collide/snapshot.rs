//! A picture of a frame, as in the paper's Fig. 1 and Fig. 6(a): the two models (blue and
//! cyan), their colliding triangles (red, drawn over the surfaces that would hide them), and
//! the boxes of the colliding AABB pairs (orange for X, yellow for Y), from an oblique
//! orthographic view. For `collide --dump`.

use super::aabb::Aabb;
use super::pipeline::{FrameResult, StreamingCollider};
use crate::gl::{
    dump, Buffer, BufferUsage, Compare, Context, DepthTest, DrawState, Framebuffer, GlError,
    Primitive, Program, Texture, TextureFormat, VertexArray,
};
use crate::mesh::Mesh;
use crate::shader;
use glam::{Mat4, Quat, Vec3};
use std::path::Path;

const BLUE: Vec3 = Vec3::new(0.35, 0.45, 0.95);
const CYAN: Vec3 = Vec3::new(0.3, 0.85, 0.85);
const RED: Vec3 = Vec3::new(0.95, 0.15, 0.1);
const ORANGE: Vec3 = Vec3::new(1.0, 0.55, 0.1);
const YELLOW: Vec3 = Vec3::new(1.0, 0.95, 0.2);

/// One model of the picture: its triangles (corners), and which of them collide.
pub struct SnapshotModel<'a> {
    pub triangles: Vec<[Vec3; 3]>,
    pub colliding: &'a [u32],
    /// Boxes of this model's leaves that are in some CAP.
    pub cap_boxes: Vec<Aabb>,
}

/// Render `x` and `y` into a `size x size` PNG at `path`.
pub fn write_png(
    ctx: &Context,
    x: &SnapshotModel,
    y: &SnapshotModel,
    size: u32,
    path: &Path,
) -> Result<(), GlError> {
    let colour = Texture::new_2d(ctx, size, size, TextureFormat::Rgba8)?;
    let depth = Texture::new_2d(ctx, size, size, ctx.z_buffer_format())?;
    let target = Framebuffer::new(ctx, "snapshot", &[&colour], Some(&depth))?;
    target.clear_color(0, [0.05, 0.05, 0.07, 1.0])?;
    target.clear_depth_stencil(1.0, 0)?;
    draw(x, y, &target, Orbit::default())?;
    dump::texture_png(&colour, path, dump::DumpRange::Auto)
}

/// A turn of the oblique view (the viewer's mouse): extra yaw and pitch in radians, and a zoom
/// factor (2 shows the models twice as large).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    pub yaw: f32,
    pub pitch: f32,
    pub zoom: f32,
}

impl Default for Orbit {
    fn default() -> Self {
        Orbit {
            yaw: 0.0,
            pitch: 0.0,
            zoom: 1.0,
        }
    }
}

/// Draw `x` and `y`, their colliding triangles and CAP boxes into `target` (which has colour
/// and depth; the caller clears them), fitted to its aspect ratio.
pub fn draw(
    x: &SnapshotModel,
    y: &SnapshotModel,
    target: &Framebuffer,
    orbit: Orbit,
) -> Result<(), GlError> {
    let ctx = target.context();
    let mut tri_vertices: Vec<[f32; 6]> = Vec::new();
    // The colliding triangles lie where the models pass through each other, mostly hidden by
    // the surfaces in front: drawn a second time over everything, so that every one shows.
    let mut hit_vertices: Vec<[f32; 6]> = Vec::new();
    for (model, base) in [(x, BLUE), (y, CYAN)] {
        let mut colliding = vec![false; model.triangles.len()];
        for &t in model.colliding {
            colliding[t as usize] = true;
        }
        for (t, corners) in model.triangles.iter().enumerate() {
            let c = if colliding[t] { RED } else { base };
            tri_vertices.extend(corners.iter().map(|p| vertex(*p, c)));
            if colliding[t] {
                hit_vertices.extend(corners.iter().map(|p| vertex(*p, RED)));
            }
        }
    }
    let mut line_vertices: Vec<[f32; 6]> = Vec::new();
    for (model, c) in [(x, ORANGE), (y, YELLOW)] {
        for b in &model.cap_boxes {
            line_vertices.extend(box_edges(b).iter().map(|p| vertex(*p, c)));
        }
    }
    let bounds = Aabb::from_points(x.triangles.iter().chain(&y.triangles).flatten().copied());
    let aspect = target.width() as f32 / target.height().max(1) as f32;
    let fit = Mat4::from_scale(Vec3::new(
        orbit.zoom / aspect.max(1.0),
        orbit.zoom * aspect.min(1.0),
        1.0,
    ));
    let mvp = fit * oblique_view(&bounds, orbit);
    let program = Program::new(
        ctx,
        &[shader!("glsl/collide/snapshot.vert")],
        &[shader!("glsl/collide/snapshot.frag")],
    )?;
    let state = DrawState {
        depth: Some(DepthTest {
            func: Compare::LessEqual,
            write: true,
        }),
        ..DrawState::default()
    };
    let on_top = DrawState::default();
    for (vertices, primitive, lit, state) in [
        (&tri_vertices, Primitive::Triangles, true, state),
        (&hit_vertices, Primitive::Triangles, false, on_top),
        (&line_vertices, Primitive::Lines, false, state),
    ] {
        if vertices.is_empty() {
            continue;
        }
        let buffer = Buffer::from_slice(ctx, vertices, BufferUsage::Static)?;
        let mut vao = VertexArray::new(ctx)?;
        vao.float_attribute(0, &buffer, 3, 24, 0, 0)?;
        vao.float_attribute(1, &buffer, 3, 24, 12, 0)?;
        let mut pass = target.pass(&program, "snapshot")?;
        pass.state(state)
            .uniform("u_mvp", mvp)
            .uniform("u_lit", lit)
            .uniform("u_light", Vec3::new(0.4, 0.6, 0.7).normalize());
        pass.draw_arrays(&vao, primitive, 0, vertices.len())?;
    }
    Ok(())
}

fn vertex(p: Vec3, c: Vec3) -> [f32; 6] {
    [p.x, p.y, p.z, c.x, c.y, c.z]
}

/// The 12 edges of a box as 24 line end points.
fn box_edges(b: &Aabb) -> Vec<Vec3> {
    let corner = |i: usize| {
        Vec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        )
    };
    let mut out = Vec::with_capacity(24);
    for i in 0..8 {
        for bit in [1, 2, 4] {
            if i & bit == 0 {
                out.push(corner(i));
                out.push(corner(i | bit));
            }
        }
    }
    out
}

/// Orthographic view of `b` turned 35 degrees about y and 25 about x (plus the orbit), fitted
/// to the image.
fn oblique_view(b: &Aabb, orbit: Orbit) -> Mat4 {
    let centre = (b.min + b.max) * 0.5;
    let radius = (b.max - b.min).length().max(1e-6) * 0.5;
    let turn = Quat::from_rotation_x(0.45 + orbit.pitch) * Quat::from_rotation_y(-0.6 + orbit.yaw);
    let scale = Mat4::from_scale(Vec3::new(1.0, 1.0, -1.0) / radius);
    scale * Mat4::from_quat(turn) * Mat4::from_translation(-centre)
}

/// Paper Fig. 1 / 6(a): the models, their colliding triangles and the boxes of the CAPs.
pub fn frame_png(
    collider: &StreamingCollider,
    frame: &FrameResult,
    (x, y): (&Mesh, &Mesh),
    path: &Path,
) -> anyhow::Result<()> {
    let (cx, cy) = frame_colliding(frame);
    let (mx, my) = frame_models(collider, frame, (x, y), (&cx, &cy));
    write_png(collider.context(), &mx, &my, 800, path)?;
    Ok(())
}

/// The triangles of X and of Y that are in some colliding pair of `frame`, sorted.
pub fn frame_colliding(frame: &FrameResult) -> (Vec<u32>, Vec<u32>) {
    let side = |s: usize| {
        let mut t: Vec<u32> = frame
            .pairs
            .iter()
            .map(|p| if s == 0 { p.0 } else { p.1 })
            .collect();
        t.sort_unstable();
        t.dedup();
        t
    };
    (side(0), side(1))
}

/// The two models of `frame` as the picture draws them; `colliding` from [`frame_colliding`].
pub fn frame_models<'a>(
    collider: &StreamingCollider,
    frame: &FrameResult,
    (x, y): (&Mesh, &Mesh),
    (cx, cy): (&'a [u32], &'a [u32]),
) -> (SnapshotModel<'a>, SnapshotModel<'a>) {
    let model = |m: &Mesh, stream: &super::AabbStream, side: usize, colliding: &'a [u32]| {
        let boxes = stream.leaf_boxes(&m.positions);
        let mut leaves: Vec<u32> = frame
            .cap_leaves
            .iter()
            .map(|c| if side == 0 { c.0 } else { c.1 })
            .collect();
        leaves.sort_unstable();
        leaves.dedup();
        SnapshotModel {
            triangles: (0..m.triangles.len()).map(|t| m.triangle(t)).collect(),
            colliding,
            cap_boxes: leaves.iter().map(|&l| boxes[l as usize]).collect(),
        }
    };
    (
        model(x, &collider.x.stream, 0, cx),
        model(y, &collider.y.stream, 1, cy),
    )
}

/// Paper Fig. 6: P0, the hierarchy P1..P3, the reduced P1', and the AABB textures.
pub fn dump_buffers(collider: &StreamingCollider, dir: &Path) -> anyhow::Result<()> {
    use super::reduction::Scheme;
    let ctx = collider.context();
    // Fill both encodings from the last P0.
    collider
        .reduction
        .read(ctx, &collider.target, Scheme::Hierarchical)?;
    collider
        .reduction
        .read(ctx, &collider.target, Scheme::Reduced)?;
    let range = dump::DumpRange::Auto;
    dump::texture_png(
        &collider.target.p0,
        &dir.join("P0.png"),
        dump::DumpRange::Fixed(0.0, 1.0),
    )?;
    for (i, t) in collider.reduction.level_textures().into_iter().enumerate() {
        dump::texture_png(t, &dir.join(format!("P{}.png", i + 1)), range)?;
    }
    dump::texture_png(
        collider.reduction.reduced_texture(),
        &dir.join("P1_reduced.png"),
        range,
    )?;
    for (name, stream) in [("X", &collider.x), ("Y", &collider.y)] {
        for (s, (aabb, vertices)) in stream.segments.iter().enumerate() {
            dump::texture_png(
                &aabb.t_min,
                &dir.join(format!("T_min_{name}_{s}.png")),
                range,
            )?;
            dump::texture_png(
                &aabb.t_max,
                &dir.join(format!("T_max_{name}_{s}.png")),
                range,
            )?;
            dump::texture_png(
                &vertices.texture,
                &dir.join(format!("vertices_{name}_{s}.png")),
                range,
            )?;
        }
    }
    dump_npy(collider, dir)
}

/// The float buffers of [`dump_buffers`] by the names of their files (without extension).
pub fn dumped_textures(collider: &StreamingCollider) -> Vec<(String, &crate::gl::Texture)> {
    let mut out = vec![("P0".to_string(), &collider.target.p0)];
    for (i, t) in collider.reduction.level_textures().into_iter().enumerate() {
        out.push((format!("P{}", i + 1), t));
    }
    out.push(("P1_reduced".into(), collider.reduction.reduced_texture()));
    for (name, stream) in [("X", &collider.x), ("Y", &collider.y)] {
        for (s, (aabb, vertices)) in stream.segments.iter().enumerate() {
            out.push((format!("T_min_{name}_{s}"), &aabb.t_min));
            out.push((format!("T_max_{name}_{s}"), &aabb.t_max));
            out.push((format!("vertices_{name}_{s}"), &vertices.texture));
        }
    }
    out
}

/// Beside each PNG, the exact values as `.npy` ([`crate::gl::npy`]: rows from GL's bottom).
fn dump_npy(collider: &StreamingCollider, dir: &Path) -> anyhow::Result<()> {
    for (name, texture) in dumped_textures(collider) {
        crate::gl::npy::texture_npy(texture, &dir.join(format!("{name}.npy")))?;
    }
    Ok(())
}
