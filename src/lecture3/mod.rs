//! The tutorial's lecture 3 (Kyoung-Su Oh), beside paper 3's network (module [`crate::mlp`]):
//! the image pyramid and pyramidal displacement mapping (Oh, Ki & Lee, "Pyramidal displacement
//! mapping: a GPU based artifacts-free ray tracing through an image pyramid", ACM VRST 2006),
//! hierarchical quadtree search of a light hierarchy (Ki & Oh, "A GPU-based light hierarchy
//! for real-time approximate illumination", The Visual Computer 2008), and the lecture's basic
//! techniques and debugging tips.
//!
//! The texts of these sources are not in the project: only the tutorial's programme and the
//! published abstracts are (`lecture3-sources.md`). Every technique here is therefore a
//! reconstruction from the abstract and the standard formulation of the idea; each module doc
//! says which parts are.
//!
//! One module per technique, each with its CPU reference:
//! 1. [`pyramid`]: a max/min (and mean) quadtree image pyramid built by render passes
//!    ([`pyramid_atlas`]: the same pyramid in one image, for per-pixel levels);
//! 2. [`displacement`]: pyramidal displacement mapping, against an exact CPU tracer and
//!    relief mapping;
//! 3. [`light_hierarchy`]: VPLs in an image, clustered into a pyramid, gathered by a
//!    quadtree search in the fragment shader, against the brute-force sum;
//! 4. [`function_texture`]: a costly function in a 1D lookup texture, against computing it;
//! 5. [`random_texture`]: a generator per texel advanced by ping-pong passes, bit-exact with
//!    the CPU;
//! 6. [`depth_mask`]: an `if` removed with the depth buffer (early depth test; the expensive
//!    shader's runs counted by a pipeline statistics query or an atomic counter);
//! 7. [`blend_histogram`]: a histogram by additive blending of points, equal to the CPU's.
//!
//! The other two debugging tips live in the GL layer: drawing the intermediate data
//! ([`crate::gl::dump`], used for every picture of the report section) and coping with shader
//! compile errors ([`crate::gl::Program`] names the file and line, with the source around it).
//! [`octree`]: an occupancy octree of a point set built by reduction passes and ray cast in
//! the fragment shader, against a flat voxel walk and the CPU.
//! The light hierarchy serves the three uses its abstract names: indirect light from VPLs,
//! subsurface scattering (irradiance samples and Jensen's dipole) and environment light (a
//! sky of directional lights), each against the brute-force sum. What the sources name and
//! this module does not build is the report's "not built" table
//! (`crate::report::not_built::LECTURE3`).
//!
//! Renderer notes found on the way (Mesa 22.3): softpipe takes `texelFetch`'s level of detail
//! from the first pixel of each 2x2 quad (hence [`pyramid_atlas`]) and read row 0 for row 1 of
//! a 2D texture in the vertex stage (hence vertex buffers in [`blend_histogram`]); llvmpipe
//! stops a shader's loops after 65535 iterations in all, silently (hence the limits on loop
//! counts in [`light_hierarchy`], [`function_texture`], [`depth_mask`] and the gather
//! histogram).
//!
//! Shared: [`height_map`] (any greyscale image as a height field; the shipped map), [`error`].
//! Shaders: `glsl/lecture3/`.

pub mod blend_histogram;
pub mod depth_mask;
pub mod displacement;
pub mod error;
pub mod function_texture;
pub mod height_map;
pub mod light_hierarchy;
pub mod octree;
pub mod pyramid;
pub mod pyramid_atlas;
pub mod random_texture;

pub use error::Error;
pub use height_map::HeightMap;

/// `f` of every item, in the items' order, on every core of the machine (scoped threads;
/// item k goes to thread k mod n, so that costly and cheap stretches of the input are shared
/// out evenly): for the CPU references, whose items are independent and which nothing times
/// as one core's work. Returns the results and the number of threads.
pub fn map_on_all_cores<T: Sync, R: Send>(
    items: &[T],
    f: impl Fn(&T) -> R + Sync,
) -> (Vec<R>, usize) {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .clamp(1, items.len().max(1));
    let f = &f;
    let parts: Vec<Vec<R>> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|t| scope.spawn(move || items.iter().skip(t).step_by(threads).map(f).collect()))
            .collect();
        workers
            .into_iter()
            .map(|w| {
                w.join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
            })
            .collect()
    });
    let mut parts: Vec<_> = parts.into_iter().map(Vec::into_iter).collect();
    let results = (0..items.len())
        .map(|k| parts[k % threads].next().expect("one result per item"))
        .collect();
    (results, threads)
}
