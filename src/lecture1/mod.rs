//! The tutorial's lecture 1 (Young J. Kim, proximity computation on the GPU) beyond paper 1's
//! streaming AABBs (module [`crate::collide`]): self-collision of a deforming mesh, pairwise
//! triangle tests with the triangles in textures, distance fields and 2D generalized Voronoi
//! diagrams, swept volumes, penetration depth and continuous collision for an avatar.
//!
//! Only the abstracts and introductions of the lecture's other sources are public
//! (`lecture1-sources.md`), so these are reconstructions:
//! - [`self_collision`]: paper 1's pipeline with one model against itself. That paper 1's
//!   group did self-collision is confirmed; how is not: the diagonal-free self test and the
//!   neighbour exclusion here are ours.
//! - [`pairwise`]: Choi, Kim & Kim, "Rapid pairwise intersection tests using programmable
//!   GPUs", The Visual Computer 22(2), 2006. Inferred from paper 1's description of its
//!   reference 38 (triangles mapped into textures, a hierarchical readback); the layout of
//!   the textures, the pair quad, its tiling and the fragment test are a reconstruction.
//!
//! - [`pairwise_compute`]: the same pair test as one OpenGL 4.3 compute dispatch with an
//!   atomic-append pair list (then and now; not a part of the sources).
//! - [`distance_field`]: the unsigned distance field of a mesh slice by slice, exact
//!   per-fragment distances kept by GL_MIN blending (DiFi's style, the default) or Hoff's
//!   distance meshes kept by the depth test (`--method mesh`), and
//!   [`voronoi`]: Hoff et al.'s 2D generalized Voronoi diagram, by exact distances as depth
//!   (the default) or by Hoff's distance meshes.
//! - [`swept_volume`]: Kim, Varadhan, Lin & Manocha 2003: ruled surfaces, their distance
//!   field, a flood fill (not fast marching), marching tetrahedra (no topological
//!   refinement).
//! - [`penetration`]: Kim, Otaduy, Lin & Manocha 2002: convex pieces' Minkowski sums on a
//!   cube map, refined on the CPU.
//! - [`avatar_ccd`]: Kim, Redon et al. 2007: swept capsule bounds, a BVH, occlusion-query
//!   culling, conservative advancement; a 13-link walker in a small room, or the published
//!   scale (16 links, 102,438 generated triangles).
//!
//! Each part has its own CPU reference, not all of the same kind: self-collision and the
//! pairwise tests against [`mod@reference`], brute force with paper 1's exact predicate; the
//! distance field against the same point-triangle distance in f64 and against parry3d's
//! closest points; Voronoi diagrams against brute force per pixel; swept volumes against
//! volumes in closed form; penetration depth against the exact depth; avatar CCD against
//! dense sampling with parry3d's distances. [`weld`] decides which triangles are neighbours;
//! [`knotted_tube`] is a scene that folds onto itself. Shaders: `glsl/lecture1/`.

pub mod avatar_ccd;
pub mod distance_field;
pub mod knotted_tube;
pub mod pairwise;
pub mod pairwise_compute;
pub mod penetration;
pub mod pictures;
pub mod reference;
pub mod self_collision;
pub mod swept_volume;
pub mod voronoi;
pub mod weld;
