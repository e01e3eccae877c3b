//! The tutorial's lecture 1 live ([`crate::lecture1`]), one demo per technique (one file
//! each): the models with their colliding triangles in red, the pair texture and its
//! hierarchical levels as insets, each level's texel probed against the CPU encoding.

mod avatar_ccd;
mod pairwise;
mod penetration;
mod self_collision;

use crate::collide::snapshot::{self, Orbit, SnapshotModel};
use crate::gl::{Context, Framebuffer, Rect, Texture, TextureFormat};
use crate::lecture1::pictures::BufferPanel;
use crate::mesh::Mesh;
use crate::view::inset::{self, Shown};
use crate::view::{overlay, Canvas, Demo, ViewState};
use glam::Vec3;

/// The techniques, named as `classic-gpgpu lecture1` names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Technique {
    /// Self-collision of the swelling knotted tube with streaming AABBs.
    SelfCollision,
    /// Pairwise triangle tests in textures between two deforming tori.
    Pairwise,
    /// Penetration depth by rasterized Minkowski sums: a cube circling in the corner of an L
    /// of two boxes, the six cube faces of the T buffer.
    Penetration,
    /// Continuous collision for an avatar: a walking figure of capsule links stopping at its
    /// first contact with the room's wall.
    AvatarCcd,
}

impl Technique {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Technique::SelfCollision => "self-collision",
            Technique::Pairwise => "pairwise",
            Technique::Penetration => "penetration",
            Technique::AvatarCcd => "avatar-ccd",
        }
    }

    /// Build the technique's demo on `ctx`.
    pub fn build(self, ctx: &Context) -> anyhow::Result<Box<dyn Demo>> {
        Ok(match self {
            Technique::SelfCollision => Box::new(self_collision::SelfCollisionDemo::new(ctx)?),
            Technique::Pairwise => Box::new(pairwise::PairwiseDemo::new(ctx)?),
            Technique::Penetration => Box::new(penetration::PenetrationDemo::new(ctx)?),
            Technique::AvatarCcd => Box::new(avatar_ccd::AvatarCcdDemo::new(ctx)?),
        })
    }
}

/// A buffer panel as the viewer's inset shows it: the probe reads the raw masks where the
/// colours show their set bits, beside the CPU's values.
fn shown(buffer: BufferPanel) -> Shown {
    Shown {
        panel: buffer.panel,
        probe_values: buffer.raw,
        reference: buffer.reference,
    }
}

/// A model of the snapshot picture at `positions`, with `colliding` triangles red.
fn snapshot_model<'a>(mesh: &Mesh, positions: &[Vec3], colliding: &'a [u32]) -> SnapshotModel<'a> {
    SnapshotModel {
        triangles: mesh
            .triangles
            .iter()
            .map(|t| t.map(|v| positions[v as usize]))
            .collect(),
        colliding,
        cap_boxes: Vec::new(),
    }
}

/// The distinct triangles of a side of `pairs` (`first`: the i's, else the j's), sorted.
fn sides(pairs: &[(u32, u32)], first: bool) -> Vec<u32> {
    let mut out: Vec<u32> = pairs
        .iter()
        .map(|&(i, j)| if first { i } else { j })
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// The scene frame: the models between the overlay text and the strip of buffer insets (so
/// that neither covers them), the insets along the bottom.
fn draw_scene(
    canvas: &Canvas,
    (x, y): (&SnapshotModel, &SnapshotModel),
    insets: Vec<Shown>,
    view: &ViewState,
) -> anyhow::Result<()> {
    let strip = inset::strip_rect(canvas, insets.len());
    let free = canvas.below_text();
    let rect = Rect::new(0, strip.h, free.w, free.h.saturating_sub(strip.h));
    draw_models(canvas, (x, y), rect, view)?;
    inset::draw_picture(canvas, insets, strip)?;
    Ok(())
}

/// The two models drawn into `rect` of the canvas, orbited as the view says (nothing where
/// the rectangle is too small to show them).
pub(super) fn draw_models(
    canvas: &Canvas,
    (x, y): (&SnapshotModel, &SnapshotModel),
    rect: Rect,
    view: &ViewState,
) -> anyhow::Result<()> {
    if rect.w < 16 || rect.h < 16 {
        return Ok(());
    }
    let ctx = canvas.context();
    let colour = Texture::new_2d(ctx, rect.w, rect.h, TextureFormat::Rgba8)?;
    let depth = Texture::new_2d(ctx, rect.w, rect.h, TextureFormat::Depth32F)?;
    let target = Framebuffer::new(ctx, "lecture 1 scene", &[&colour], Some(&depth))?;
    target.clear_color(0, [0.05, 0.05, 0.07, 1.0])?;
    target.clear_depth_stencil(1.0, 0)?;
    let orbit = Orbit {
        yaw: view.yaw,
        pitch: view.pitch,
        zoom: view.zoom * 0.9,
    };
    snapshot::draw(x, y, &target, orbit)?;
    let mut pixels = target.read_u8(0, Rect::sized(rect.w, rect.h))?;
    for px in pixels.chunks_exact_mut(4) {
        px[3] = 255;
    }
    overlay::draw_image(canvas, &pixels, rect.w, rect.h, (rect.x, rect.y))?;
    Ok(())
}
