//! The pipeline driver in its compute formulation (OpenGL 4.3): the same frame as
//! [`super::pipeline`] (global test, download, stream update, overlap test, primitive test)
//! with the two GPU stages as compute passes ([`super::compute_update`],
//! [`super::compute_overlap`]). The stream setup keeps the paper's top-down tree and leaves;
//! only their layout as a complete binary tree of textures is dropped.

use super::compute_overlap::ComputeOverlap;
use super::compute_update::{ComputeUpdate, LeafBoxes};
use super::global_test::global_boxes_overlap;
use super::pipeline::{FrameResult, Options};
use super::stream_setup::{validate_mesh, AabbStream};
use super::tri_test::{test_caps, ModelView};
use crate::gl::{memory_barrier, time_finished, Barrier, Context};
use crate::mesh::Mesh;
use glam::Vec3;
use std::time::Instant;

/// Collision detection between two deforming meshes with compute passes.
pub struct ComputeCollider {
    ctx: Context,
    pub options: Options,
    pub stream_x: AabbStream,
    pub stream_y: AabbStream,
    pub x: LeafBoxes,
    pub y: LeafBoxes,
    triangles_x: Vec<[u32; 3]>,
    triangles_y: Vec<[u32; 3]>,
    update: ComputeUpdate,
    overlap: ComputeOverlap,
}

impl ComputeCollider {
    /// Stream setup for X and Y; on a context below OpenGL 4.3, the error naming it.
    pub fn new(
        ctx: &Context,
        x: &Mesh,
        y: &Mesh,
        options: Options,
    ) -> anyhow::Result<ComputeCollider> {
        ctx.require_compute("the compute formulation of paper 1")?;
        for (name, mesh) in [("X", x), ("Y", y)] {
            validate_mesh(mesh).map_err(|e| anyhow::anyhow!("model {name}: {e}"))?;
        }
        let stream_x = AabbStream::build(x, options.leaf_size)?;
        let stream_y = AabbStream::build(y, options.leaf_size)?;
        Ok(ComputeCollider {
            ctx: ctx.clone(),
            options,
            x: LeafBoxes::new(ctx, &stream_x, x.positions.len())?,
            y: LeafBoxes::new(ctx, &stream_y, y.positions.len())?,
            stream_x,
            stream_y,
            triangles_x: x.triangles.clone(),
            triangles_y: y.triangles.clone(),
            update: ComputeUpdate::new(ctx)?,
            overlap: ComputeOverlap::new(ctx)?,
        })
    }

    /// One frame: deformed vertices in, every intersecting triangle pair out. The GPU stages
    /// are timed by wall clock between `glFinish` calls ([`time_finished`]); the timings
    /// use the classic names: `update` the leaf-box pass, `overlap` the pair test with its
    /// compaction, `readback` the count and the list; `stencil` and `encode` stay zero.
    pub fn frame(
        &mut self,
        positions_x: &[Vec3],
        positions_y: &[Vec3],
    ) -> anyhow::Result<FrameResult> {
        let start = Instant::now();
        for (name, positions, mesh_vertices) in [
            ("X", positions_x, self.x.bytes() / 16),
            ("Y", positions_y, self.y.bytes() / 16),
        ] {
            anyhow::ensure!(
                positions.len() == mesh_vertices,
                "model {name}: {} positions given, the mesh has {mesh_vertices}",
                positions.len()
            );
            if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
                anyhow::bail!(
                    "model {name}: vertex {i} is not finite ({:?})",
                    positions[i]
                );
            }
        }
        let mut out = FrameResult {
            tiles: 1,
            ..FrameResult::default()
        };
        // Global AABB overlap test: trivial rejection.
        out.global_overlap = global_boxes_overlap(positions_x, positions_y);
        if !out.global_overlap {
            out.timings.total = start.elapsed().as_secs_f64() * 1e3;
            return Ok(out);
        }
        // Download, then the leaf boxes.
        let t = Instant::now();
        self.x.upload(positions_x)?;
        self.y.upload(positions_y)?;
        self.ctx.finish_all();
        out.timings.download = t.elapsed().as_secs_f64() * 1e3;
        let ((), update_ms) = time_finished(&self.ctx, || {
            self.update.run(&self.x)?;
            self.update.run(&self.y)?;
            memory_barrier(&self.ctx, &[Barrier::Storage]);
            Ok(())
        })?;
        out.timings.update = update_ms;
        // Every leaf pair tested, overlapping ones appended to the list.
        let ((), overlap_ms) =
            time_finished(&self.ctx, || self.overlap.dispatch(&self.x, &self.y))?;
        out.timings.overlap = overlap_ms;
        let t = Instant::now();
        let found = self.overlap.read(&self.x, &self.y)?;
        out.timings.readback = t.elapsed().as_secs_f64() * 1e3;
        out.readback_bytes = found.bytes;
        out.readback_reads = if found.reran { 4 } else { 2 };
        out.caps = found.caps.len();
        out.eta = out.caps as f64 / (self.x.leaves as f64 * self.y.leaves as f64);
        // Primitive-level intersection test, as in the classic pipeline.
        let t = Instant::now();
        let result = test_caps(
            ModelView {
                triangles: &self.triangles_x,
                positions: positions_x,
                stream: &self.stream_x,
            },
            ModelView {
                triangles: &self.triangles_y,
                positions: positions_y,
                stream: &self.stream_y,
            },
            &found.caps,
            self.options.predicate,
        );
        out.timings.tri_test = t.elapsed().as_secs_f64() * 1e3;
        out.pctps = result.pctps;
        out.ctps = result.pairs.len();
        out.pairs = result.pairs;
        out.cap_leaves = found.caps;
        out.timings.total = start.elapsed().as_secs_f64() * 1e3;
        Ok(out)
    }

    pub fn context(&self) -> &Context {
        &self.ctx
    }
}
