//! Technique 3, hierarchical quadtree search of a light hierarchy (Ki & Oh, "A GPU-based
//! light hierarchy for real-time approximate illumination", The Visual Computer 2008, and
//! the lecture's "hierarchical search of a quadtree on the GPU" for indirect illumination):
//! virtual point lights (VPLs) are stored in an image, clustered into an image pyramid, and
//! each pixel's fragment shader walks that quadtree from the root, taking a cluster as one
//! light when it looks small from the receiver, instead of summing every VPL. Occlusion is
//! ignored, as in the paper.
//!
//! Reconstruction: the text is not available; the abstract gives the idea (VPLs in images,
//! a view-independent hierarchy built as image pyramids by simple clustering, a GPU tree
//! traversal that gathers a few light groups). Ours: the VPLs of a reflective shadow map
//! ([`vpl_image`]), the 2x2 flux-weighted clustering with bounding radii ([`clusters`]), the
//! criterion radius < theta x distance and the stackless Morton-order traversal
//! (`vpl_gather_tree.frag`), the irradiance formula with distances clamped to
//! [`gather::MIN_DISTANCE`] ([`light`]), and the scene ([`scene`]).
//!
//! Steps, one file each: [`scene`], [`vpl_image`], [`clusters`], [`gbuffer`], [`gather`],
//! [`shade`]; [`pipeline`] runs them in order; [`light`] is the CPU reference (f64).
//!
//! The hierarchy's other uses, all reconstructions (the abstract names them without saying
//! how): [`normal_cone`], a criterion that also looks at the spread of a cluster's normals;
//! [`subsurface`], the lecture's translucency demo with the dipole of Jensen et al. 2001
//! summed over irradiance samples; [`environment`], a procedural sky as directional lights
//! clustered on direction; [`uses`] says what each puts in level 0 and gathers; [`model`] makes
//! a scene from an OBJ file.

pub mod clusters;
pub mod environment;
pub mod gather;
pub mod gbuffer;
pub mod light;
pub mod model;
pub mod normal_cone;
pub mod pipeline;
pub mod scene;
pub mod shade;
pub mod subsurface;
pub mod uses;
pub mod vpl_image;

pub use gather::Gather;
pub use pipeline::IndirectLighting;
pub use scene::Scene;
pub use uses::LightUse;
