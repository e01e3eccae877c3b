//! Octrees on the GPU, as the lecture's techniques name them ("octrees and quadtrees on the
//! GPU"): an octree of a voxelized point set built in textures by render passes and traversed
//! per pixel in a fragment shader, answering a query faster than a flat search.
//!
//! Reconstruction: the lecture's text is not available (`lecture3-sources.md` names the topic
//! only). Ours is the quadtree of technique 2 lifted to three dimensions:
//! - the octree is a pyramid of occupancy levels, every level a full grid (a node of level
//!   k + 1 is occupied when any of its eight children is), not a node pool with child
//!   pointers. A render pass writes each texel at a fixed place (gather, no scatter), so a
//!   complete pyramid is what fragment passes build level by level without a prefix sum to
//!   allocate nodes; its price is memory for empty nodes (8/7 of the leaf grid);
//! - each 3D level lives in a 2D texture, its z slices tiled side by side ([`grid`]);
//! - the query is ray casting: the first occupied voxel along each pixel's ray, found by a
//!   top-down traversal that skips empty nodes whole (climbing one level after leaving a
//!   node, descending into occupied ones), against a flat 3D DDA that visits every voxel the
//!   ray crosses.
//!
//! Steps, one file each: [`grid`] (points to a voxel grid, the tiled layout), [`levels`] (the
//! occupancy pyramid on the CPU and by reduction passes on the GPU), [`cast`] (the GPU ray
//! casts, octree and flat), [`reference`](mod@reference) (the CPU octree traversal and flat DDA in f64, and the
//! per-pixel comparison).

pub mod cast;
pub mod grid;
pub mod levels;
pub mod reference;

pub use cast::{CastFrame, OctreeCaster, Search};
pub use grid::VoxelGrid;
