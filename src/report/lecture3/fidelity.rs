//! The lecture's techniques, where this code does them, and what differs from the sources.
//! Every row is a reconstruction from an abstract or a one-line mention in the programme.

use super::paths;
use crate::report::Fidelity;

pub fn rows() -> Vec<Fidelity> {
    vec![
        Fidelity::new(
            "image pyramid, each level rendered from the one below",
            "lecture 3 (programme); VRST 2006 abstract",
            "src/lecture3/pyramid.rs, glsl/lecture3/pyramid_level.frag",
            "reconstruction: a max/min mipmap drawn level by level (base/max level narrowed to \
             avoid a feedback loop); odd sizes padded to a power of two with the identity",
        )
        .covers(&[paths::PYRAMID]),
        Fidelity::new(
            "pyramid read at a per-pixel level",
            "VRST 2006 abstract (traversal of the pyramid)",
            "src/lecture3/pyramid_atlas.rs, glsl/lecture3/atlas_copy.frag",
            "the levels are copied into one atlas image: Mesa's softpipe takes texelFetch's \
             level per 2x2 quad, so a per-pixel level reads wrong texels there",
        )
        .covers(&[paths::PYRAMID]),
        Fidelity::new(
            "top-down traversal of the max pyramid, safe empty-space skipping",
            "VRST 2006 abstract",
            "glsl/lecture3/displace_pyramid.frag, src/lecture3/displacement/bounds.rs",
            "reconstruction: level 0 bounds each bilinear patch by its corners; a node is \
             skipped when the ray stays above its bound; the ray climbs one level after each \
             node it leaves (the paper's exact rule is not known)",
        )
        .covers(&[paths::PYRAMID_TRACE]),
        Fidelity::new(
            "intersection with the bilinearly interpolated map at the finest level",
            "VRST 2006 abstract (magnification)",
            "src/lecture3/displacement/patch.rs, glsl/lecture3/displace_common.glsl",
            "reconstruction: the ray against each patch's height as a closed-form quadratic; the \
             map lies on a box whose side walls are hit too",
        )
        .covers(&[paths::PYRAMID_TRACE]),
        Fidelity::new(
            "a mipmap-like prefilter at minification",
            "VRST 2006 abstract (minification)",
            "src/lecture3/displacement/{prefilter,visible_shading}.rs, \
             glsl/lecture3/displace_prefilter.glsl",
            "reconstruction (the construction is not given): the descent stops at the nodes \
             the pixel's footprint (where the ray enters the box) covers, the node's height \
             range seen from the side included (min and max pyramids); there a bilinear patch \
             per node from the mean pyramid of the heights, clamped under the node's bound; \
             every hit of the pixel shaded at its footprint's level as the facets about the hit \
             that face the eye, each weighted by its area projected toward the eye (a mean \
             pyramid of those weights and weighted lit cosines, drawn for each view; \
             self-occlusion ignored)",
        )
        .covers(&[paths::PREFILTER]),
        Fidelity::new(
            "linear + binary search (relief mapping) as the artifact-prone comparison",
            "VRST 2006 abstract (\"unlike linear search\"); Policarpo et al. 2005",
            "glsl/lecture3/displace_relief.frag",
            "budgets 16+6 and 32+8 steps are ours; bilinear interpolation in the shader instead \
             of the texture unit, so that both methods see the same field",
        )
        .covers(&[paths::RELIEF]),
        Fidelity::new(
            "VPLs stored in images, clustered into image pyramids",
            "Ki & Oh 2008 abstract",
            "src/lecture3/light_hierarchy/{vpl_image,clusters}.rs",
            "reconstruction: VPLs from a reflective shadow map of one spot light; 2x2 clusters \
             with flux-weighted position and normal and a bounding radius (the paper's \
             clustering is described only as simple and fast)",
        )
        .covers(&[paths::LIGHT_TREE]),
        Fidelity::new(
            "tree traversal on the GPU gathering light groups",
            "Ki & Oh 2008 abstract; lecture 3 (quadtree search)",
            "glsl/lecture3/vpl_gather_tree.frag",
            "reconstruction: criterion radius < theta x distance, a stackless Morton-order walk, \
             distances clamped to 0.1; occlusion ignored as in the paper",
        )
        .covers(&[paths::LIGHT_TREE]),
        Fidelity::new(
            "normal-aware clustering",
            "Ki & Oh 2008 abstract (clustering unspecified)",
            "src/lecture3/light_hierarchy/normal_cone.rs",
            "ours: a cluster is one light only when its mean unit normal is at least 0.9 long as \
             well as small from the receiver; the pyramid itself is unchanged",
        )
        .covers(&[paths::LIGHT_TREE]),
        Fidelity::new(
            "subsurface scattering from the light hierarchy (the lecture's demo)",
            "Ki & Oh 2008 abstract; Ki & Oh, hierarchical translucent rendering (text not \
             available); Jensen et al. 2001",
            "src/lecture3/light_hierarchy/subsurface.rs, glsl/lecture3/subsurface_dipole.glsl",
            "reconstruction: irradiance samples from the spot light's image, Jensen's dipole \
             (skin 1, 1 unit = 20 mm) summed by the same tree search; Fresnel transmission \
             left out; no single scattering",
        )
        .covers(&[paths::SUBSURFACE]),
        Fidelity::new(
            "environment light from the light hierarchy",
            "Ki & Oh 2008 abstract",
            "src/lecture3/light_hierarchy/environment.rs, glsl/lecture3/environment_kernel.glsl",
            "reconstruction: a procedural sky on a lat-long grid as directional lights, \
             clustered on direction; criterion radius < theta |n . c|; visibility ignored",
        )
        .covers(&[paths::ENVIRONMENT]),
        Fidelity::new(
            "octrees on the GPU: an occupancy octree built by reduction passes, ray cast",
            "lecture 3 (programme: 'octrees and quadtrees on the GPU'; the text is not \
             available)",
            "src/lecture3/octree/, glsl/lecture3/octree_*",
            "reconstruction: the displacement pyramid's quadtree lifted to 3D; every level a full \
             occupancy grid (no node pool or child pointers: fragment passes gather, they \
             cannot scatter or allocate), its z slices tiled in a 2D texture; rays descend into \
             occupied nodes and climb one level after leaving a node, against a flat 3D DDA; \
             the query (first voxel hit per pixel) is ours",
        )
        .covers(&[paths::OCTREE]),
        Fidelity::new(
            "a function stored in a texture",
            "lecture 3 (programme)",
            "src/lecture3/function_texture.rs, glsl/lecture3/function_lookup.frag",
            "the functions (paper 3's sigmoid, a 16-harmonic square wave), the table layout and \
             the linear filtering are our choices",
        )
        .covers(&[paths::FUNCTION]),
        Fidelity::new(
            "random numbers generated into a texture",
            "lecture 3 (programme)",
            "src/lecture3/random_texture.rs, glsl/lecture3/random_step.frag",
            "the generator is Howes & Thomas's hybrid Tausworthe (GPU Gems 3, 2007) in integer \
             textures (GL 3.0), not a float-only generator of 2006-era hardware",
        )
        .covers(&[paths::RANDOM]),
        Fidelity::new(
            "removing an if with the depth buffer",
            "lecture 3, debugging tips",
            "src/lecture3/depth_mask.rs, glsl/lecture3/depth_mask_*.frag",
            "the expensive function and masks are ours; the early depth test is left to the \
             driver for the timed shaders; the shader's runs are counted by an atomic counter \
             the shader increments (GL 4.2 atomic counters in 4.3 buffers; that variant asks \
             for the early test with early_fragment_tests, as a shader with a side effect \
             must), preferred wherever the context has one, since llvmpipe's pipeline \
             statistics count the fragments its early test then drops; else by a pipeline \
             statistics query (GL 4.6 or the ARB extension), judged at 2x2-quad granularity; \
             on a context with neither (softpipe) the runs are not counted; the table's \
             caption names the counter the run used",
        )
        .covers(&[paths::DEPTH_MASK]),
        Fidelity::new(
            "simplifying code with alpha blending",
            "lecture 3, debugging tips",
            "src/lecture3/blend_histogram.rs, glsl/lecture3/histogram_*.{vert,frag}",
            "a histogram as the example is ours; values come from a vertex buffer (softpipe's \
             vertex-stage texelFetch read the wrong row of a 2D texture)",
        )
        .covers(&[paths::HISTOGRAM]),
        Fidelity::new(
            "drawing the intermediate data; coping with shader compile errors",
            "lecture 3, debugging tips",
            "src/gl/dump.rs, src/gl/program.rs",
            "every intermediate buffer can be dumped to PNG (this section's pictures); compile \
             errors name the file and line with the source around it",
        ),
    ]
}
