//! Self-collision live: the knotted tube swelling until its strands press through each other,
//! the triangles of intersecting pairs (no shared vertex) red, and the leaf-pair texture P0
//! of the self test with its hierarchical levels as insets.

use super::{draw_scene, shown, sides, snapshot_model};
use crate::collide::reduction::Scheme;
use crate::collide::snapshot::SnapshotModel;
use crate::collide::stream_setup::{auto_leaf_size, max_slots};
use crate::gl::Context;
use crate::lecture1::knotted_tube::KnottedTube;
use crate::lecture1::pictures::pair_buffers;
use crate::lecture1::self_collision::{Options, SelfCollider, SelfFrame};
use crate::view::inset::{self, Shown};
use crate::view::{Canvas, Demo, ViewState};
use glam::Vec3;

/// Triangles of the tube: enough to show the knot, few enough for a software renderer.
const TRIANGLES: usize = 1200;
/// Seconds of the swelling per frame.
const DT: f32 = 0.25;

pub struct SelfCollisionDemo {
    tube: KnottedTube,
    collider: SelfCollider,
    frame: usize,
    positions: Vec<Vec3>,
    result: Option<SelfFrame>,
    wall_ms: f64,
}

impl SelfCollisionDemo {
    pub fn new(ctx: &Context) -> anyhow::Result<Self> {
        let tube = KnottedTube::with_triangles(TRIANGLES);
        let options = Options {
            leaf_size: auto_leaf_size(&tube.mesh, max_slots(ctx.info().is_software()))?,
            ..Options::default()
        };
        let collider = SelfCollider::new(ctx, &tube.mesh, options)?;
        Ok(SelfCollisionDemo {
            positions: tube.mesh.positions.clone(),
            tube,
            collider,
            frame: 0,
            result: None,
            wall_ms: 0.0,
        })
    }

    fn pictures(&self, short: bool) -> anyhow::Result<Vec<Shown>> {
        Ok(pair_buffers(
            &self.collider.target.p0,
            &self.collider.reduction,
            "of leaves (row, column; only above the diagonal)",
            short,
        )?
        .into_iter()
        .map(shown)
        .collect())
    }
}

impl Demo for SelfCollisionDemo {
    fn step(&mut self) -> anyhow::Result<()> {
        self.positions = self.tube.positions(self.frame as f32 * DT);
        self.frame += 1;
        let start = std::time::Instant::now();
        let result = self.collider.frame(&self.positions)?;
        self.wall_ms = start.elapsed().as_secs_f64() * 1e3;
        // The levels of this frame's P0, whichever readback the frame chose.
        let ctx = self.collider.context().clone();
        self.collider
            .reduction
            .read(&ctx, &self.collider.target, Scheme::Hierarchical)?;
        self.result = Some(result);
        Ok(())
    }

    fn render(&mut self, canvas: &Canvas, view: &ViewState) -> anyhow::Result<()> {
        canvas.clear([0.05, 0.05, 0.07, 1.0])?;
        if view.shown > 0 {
            let mut pictures = self.pictures(false)?;
            if view.shown - 1 < pictures.len() {
                let picture = pictures.swap_remove(view.shown - 1);
                inset::draw_picture(canvas, vec![picture], canvas.below_text())?;
            }
            return Ok(());
        }
        let pairs = self.result.as_ref().map_or(&[][..], |r| &r.pairs[..]);
        let mut colliding = sides(pairs, true);
        colliding.extend(sides(pairs, false));
        colliding.sort_unstable();
        colliding.dedup();
        let model = snapshot_model(&self.collider.mesh, &self.positions, &colliding);
        let none = SnapshotModel {
            triangles: Vec::new(),
            colliding: &[],
            cap_boxes: Vec::new(),
        };
        draw_scene(canvas, (&model, &none), self.pictures(true)?, view)
    }

    fn buffers(&self) -> Vec<String> {
        ["tube", "P0", "P1", "P2", "P3"].map(String::from).to_vec()
    }

    fn overlay(&self) -> Vec<String> {
        let mut lines = vec![
            format!(
                "lecture 1, self-collision: knotted tube, {} triangles, radius {:.2}",
                self.collider.mesh.triangles.len(),
                KnottedTube::radius(self.frame.saturating_sub(1) as f32 * DT)
            ),
            "triangles of intersecting pairs (no shared vertex) red".into(),
        ];
        if let Some(r) = &self.result {
            lines.push(format!(
                "leaf pairs {}  triangle pairs tested {}  intersecting {}",
                r.caps,
                r.pctps,
                r.pairs.len()
            ));
        }
        lines
    }

    fn timings(&self) -> String {
        format!("frame {:.1} ms (wall)", self.wall_ms)
    }
}
