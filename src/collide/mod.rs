//! Paper 1: Zhang & Kim, "Interactive Collision Detection for Deformable Models using
//! Streaming AABBs", IEEE TVCG 13(2), 2007.
//!
//! Every intersecting triangle pair between two deforming meshes, found in three stages:
//! stream setup (a preprocess, Sec. 4), stream calculation on the GPU (Sec. 5: global
//! AABB test, streaming AABB test, stream reduction, then Möller's test on the CPU) and
//! stream update on the GPU (Sec. 6). One file per pipeline step. The code keeps the
//! paper's notation: `S^X` the AABB stream of model X, `T_min`/`T_max` its AABB textures,
//! `d_max` the height of the complete binary tree, `n_max` the rows of the vertex texture,
//! `P0..P3` the reduction levels, `eta` the ratio of CAPs (colliding AABB pairs) to all
//! AABB pairs; PCTPs / CTPs are potentially colliding / colliding triangle pairs.
//!
//! Files, in pipeline order: [`stream_setup`] (AABB tree, virtual nodes, stencil array),
//! [`aabb_textures`], [`vertex_textures`], [`global_test`], [`streaming_test`] (paper
//! Table I, `cg_ports/`), [`reduction`] and [`reduction_gpu`] (hierarchical, reduced, full,
//! auto), [`tri_test`] (Möller 1997, exact predicates), [`tiles`], [`stream_update`] (paper
//! Table II, `cg_ports/`), [`deform`], and the driver [`pipeline`].
//!
//! Then and now (OpenGL 4.3): [`compute_update`] and [`compute_overlap`] are the stream
//! update and the overlap test with reduction as compute passes (atomic-counter compaction),
//! driven by [`compute_pipeline`].
//!
//! Baselines: [`solid`] (CPU AABB tree refit, Sec. 7.4.1), [`cullide`] (image-space culling
//! with occlusion queries, Sec. 7.4.2) and [`brute_force`] (all pairs, the reference
//! answer). [`scenes`] builds the deforming scenes of Table III; `report::paper1` measures
//! them.
//!
//! ```no_run
//! use classic_gpgpu::collide::pipeline::{Options, StreamingCollider};
//! use classic_gpgpu::gl::Context;
//! use classic_gpgpu::mesh;
//!
//! let ctx = Context::from_env()?;
//! let x = mesh::torus_with_triangles(1.0, 1.0 / 3.0, 15_000);
//! let y = x.translated(glam::Vec3::new(1.2, 0.0, 0.2));
//! let mut collider = StreamingCollider::new(&ctx, &x, &y, Options::default())?;
//! // Each frame: the deformed vertices in, every intersecting triangle pair out.
//! let frame = collider.frame(&x.positions, &y.positions)?;
//! println!("{} CAPs, {} colliding triangle pairs", frame.caps, frame.pairs.len());
//! # Ok::<(), anyhow::Error>(())
//! ```

pub mod aabb;
pub mod aabb_textures;
pub mod brute_force;
pub mod compute_overlap;
pub mod compute_pipeline;
pub mod compute_update;
pub mod cullide;
pub mod deform;
pub mod global_test;
pub mod pipeline;
pub mod reduction;
pub mod reduction_gpu;
pub mod scenes;
pub mod snapshot;
pub mod solid;
pub mod stream_setup;
pub mod stream_update;
pub mod streaming_test;
pub mod tiles;
pub mod tri_test;
pub mod vertex_textures;

pub use aabb::Aabb;
pub use stream_setup::{AabbStream, Leaf};
pub use tri_test::{triangles_intersect, Predicate};

/// What can go wrong in this module; every message names the input and the problem.
#[derive(Debug, thiserror::Error)]
pub enum CollideError {
    #[error("bad input: {0}")]
    BadInput(String),
}
