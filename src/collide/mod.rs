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
//! Baselines: [`solid`] (CPU AABB tree refit, Sec. 7.4.1) and [`brute_force`] (all pairs,
//! the reference answer).

pub mod aabb;
pub mod aabb_textures;
pub mod brute_force;
pub mod cli;
pub mod cullide;
pub mod deform;
pub mod global_test;
pub mod pipeline;
pub mod reduction;
pub mod reduction_gpu;
pub mod scenes;
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
