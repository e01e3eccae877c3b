//! Technique 2, pyramidal displacement mapping (Oh, Ki & Lee, VRST 2006): a height map laid
//! on a box is rendered by tracing each pixel's ray through the map's max pyramid, top down,
//! so that empty space is skipped in large steps yet no step can jump over the surface, and
//! intersecting the bilinearly interpolated map exactly at the finest level.
//!
//! Reconstruction: the paper's text is not available. From its abstract come the idea (a
//! ray traced through a quadtree image pyramid of the displacement map, visited top down,
//! empty regions skipped safely) and the bilinear intersection at magnification. Ours: the
//! pyramid over patch bounds ([`bounds`]), the traversal rule (descend where the ray reaches
//! a node's bound, climb one level after leaving a node, in `displace_pyramid.frag`), the
//! closed-form patch intersection ([`patch`]), the box the map is laid on and its side walls
//! ([`surface`]), and the minification prefilter ([`prefilter`]: the footprint rule and the
//! nodes it covers, the prefiltered surface from the mean pyramid, shaded as the facets facing
//! the eye, [`visible_shading`]).
//!
//! Steps, one file each: [`surface`] (the box and grid space), [`camera`] (the orbiting
//! camera and pixel rays), [`bounds`] (the bound pyramid), [`patch`] (the finest step),
//! [`tracer`] (the GPU pass: pyramid traversal or relief mapping's linear + binary search),
//! [`exact`] (the CPU reference: an exact f64 tracer of the same field), [`shading`] (what a
//! hit shows: surface or wall, normal, colour), [`compare`] (a GPU frame against it, with the
//! tolerance stated).

pub mod bounds;
pub mod camera;
pub mod compare;
pub mod exact;
pub mod patch;
pub mod prefilter;
pub mod shading;
pub mod surface;
pub mod tracer;
pub mod visible_shading;

pub use camera::Camera;
pub use surface::Surface;
pub use tracer::{DisplacementRenderer, Frame, FrameTarget, Method, Pixel};
