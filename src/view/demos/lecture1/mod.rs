//! The tutorial's lecture 1 live ([`crate::lecture1`]), one demo per technique (one file
//! each): the models with their colliding triangles in red, the pair texture and its
//! hierarchical levels as insets, each level's texel probed against the CPU encoding.

mod pairwise;
mod self_collision;

use crate::collide::snapshot::SnapshotModel;
use crate::gl::Context;
use crate::lecture1::pictures::BufferPanel;
use crate::mesh::Mesh;
use crate::view::inset::Shown;
use crate::view::Demo;
use glam::Vec3;

/// The techniques, named as `classic-gpgpu lecture1` names them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Technique {
    /// Self-collision of the swelling knotted tube with streaming AABBs.
    SelfCollision,
    /// Pairwise triangle tests in textures between two deforming tori.
    Pairwise,
}

impl Technique {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Technique::SelfCollision => "self-collision",
            Technique::Pairwise => "pairwise",
        }
    }

    /// Build the technique's demo on `ctx`.
    pub fn build(self, ctx: &Context) -> anyhow::Result<Box<dyn Demo>> {
        Ok(match self {
            Technique::SelfCollision => Box::new(self_collision::SelfCollisionDemo::new(ctx)?),
            Technique::Pairwise => Box::new(pairwise::PairwiseDemo::new(ctx)?),
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
