//! What the lecture-1 code does, where, and how far it is a reconstruction
//! (`lecture1-sources.md`: [C] confirmed, [I] inferred, [R] reconstruction).

use super::paths;
use crate::report::Fidelity;

pub fn rows() -> Vec<Fidelity> {
    let mut rows = vec![
        Fidelity::new(
            "self-collision between deformable bodies",
            "lecture 1 programme; attributed to Choi, Kim & Kim 2006 (inferred)",
            "src/lecture1/self_collision.rs, glsl/lecture1/diagonal_mask.frag",
            "reconstruction: paper 1's streaming AABB pipeline with one stream against itself; \
             tiles on and above the diagonal only, a stencil pass clearing the diagonal tile's \
             lower half, each leaf against itself sent straight to the triangle test, \
             triangles sharing a (position-welded) vertex skipped. How the lecture's sources \
             did it is not public",
        )
        .covers(&[paths::SELF_COLLISION]),
        Fidelity::new(
            "triangles mapped into textures, tested pair by pair on the GPU",
            "paper 1 on its reference 38 (Sec. 2.2.2, 5.4); Choi, Kim & Kim 2006 (record only)",
            "src/lecture1/pairwise.rs, glsl/lecture1/pair_test.frag, glsl/lecture1/pair_filter.glsl",
            "reconstruction: three RGBA32F texels per triangle, a quad whose fragment (j, i) \
             tests pair (i, j) (the i < j half for one model), tiles of at most 1024 x 1024; \
             box reject, then paper 1's exact test with each sign filtered in fp32 (a pair is \
             dropped only when certainly disjoint) and the CPU's exact predicate on what is \
             reported",
        )
        .covers(&[paths::PAIRWISE]),
        Fidelity::new(
            "hierarchical en/decoding readback of the pair results",
            "paper 1 Sec. 5.3 (it says reference 38 introduced it)",
            "src/collide/reduction_gpu.rs",
            "paper 1's 4x4 hierarchical encoding reused as it is; an occlusion query per tile \
             skips the readback of tiles without pairs (ours)",
        ),
        Fidelity::new(
            "pairwise tests as a compute pass (then and now)",
            "not in the sources",
            "src/lecture1/pairwise_compute.rs, glsl/lecture1/compute/pair_test.comp",
            "ours: the same filter over all pairs in one OpenGL 4.3 dispatch, pairs appended \
             to a list by an atomic counter (no pair texture, tiles or hierarchical readback)",
        )
        .covers(&[paths::PAIRWISE_COMPUTE]),
        Fidelity::new(
            "a scene that folds onto itself",
            "lecture 1 (self-collision of deformable bodies)",
            "src/lecture1/knotted_tube.rs",
            "ours: a tube around a trefoil knot whose radius swells until its strands press \
             through each other; paper 1's wavy and pulsating deformations on a flattened torus",
        )
        .covers(&[paths::SELF_COLLISION, paths::PAIRWISE]),
    ];
    rows.extend(later_rows());
    rows
}

/// The rows of the parts added after self-collision and the pairwise tests.
fn later_rows() -> Vec<Fidelity> {
    vec![
        Fidelity::new(
            "distance field of a mesh on a grid, slice by slice",
            "Kim et al. 2003 stage 2 (an unsigned field on a uniform grid); DiFi (slice by \
             slice, bounded regions, hardware minimum); Hoff et al. 1999 (distance meshes)",
            "src/lecture1/distance_field/slices.rs, glsl/lecture1/point_triangle.glsl",
            "reconstruction: each triangle draws its rectangle in a slice grown by the clamp \
             (the whole slice without one) and every fragment writes the exact \
             point-triangle distance, kept by GL_MIN blending in an R32F target, one readback \
             per slice; the default method (`exact`), as it is one shader in OpenGL 3.3 and \
             has no tessellation error. Hoff's distance meshes are the method `mesh` (next \
             row); DiFi's Voronoi-region bounds are not used (not public in detail)",
        )
        .covers(&[paths::FIELD_SLICES]),
        Fidelity::new(
            "distance field by Hoff's distance meshes, slice by slice (`--method mesh`)",
            "Hoff et al. 1999: each feature's distance function as a bounded-error mesh, the \
             depth test keeping the nearest; 3D done one slice at a time",
            "src/lecture1/distance_field/meshes.rs, mesh_slices.rs, glsl/lecture1/distance_mesh.*",
            "as the source, with our tessellation: every vertex draws its hyperboloid over the \
             slice, every edge its cone over its slab, every face its two planes over its \
             prism; the curved ones as polar meshes (sectors of the polygon inscribed in the \
             circle, rings on the chord error), never below the distance and at most the \
             asked error above it; cut to the slice on the CPU, drawn with a 32-bit float \
             depth buffer, the distance read from an R32F colour target",
        )
        .covers(&[paths::FIELD_MESHES]),
        Fidelity::new(
            "distance field as a compute pass (then and now)",
            "not in the sources",
            "src/lecture1/distance_field/compute.rs",
            "ours: one OpenGL 4.3 invocation per voxel over every triangle, no culling",
        )
        .covers(&[paths::FIELD_COMPUTE]),
        Fidelity::new(
            "the distance field's independent reference",
            "not in the sources",
            "src/lecture1/distance_field/independent.rs",
            "ours: parry3d's closest-point query on the mesh (another library's code, fp32), \
             beside brute force with this project's point-triangle distance in f64, which is \
             the GPU's algorithm again and so checks the GPU, not the method",
        )
        .covers(&[paths::FIELD_PARRY3D]),
        Fidelity::new(
            "generalized Voronoi diagram, exact distances as depth (the default, `exact`)",
            "Hoff et al. 1999: distance meshes, the depth test keeping the nearest site",
            "src/lecture1/voronoi/raster.rs, glsl/lecture1/voronoi_site.*",
            "ours, the default: each site draws one rectangle over the domain and every \
             fragment writes its exact distance to gl_FragDepth (no tessellation error, \
             OpenGL 3.3); the depth test keeps the nearest site as in Hoff's method",
        )
        .covers(&[paths::VORONOI_EXACT]),
        Fidelity::new(
            "generalized Voronoi diagram by Hoff's distance meshes (`--method mesh`)",
            "Hoff et al. 1999",
            "src/lecture1/voronoi/mesh.rs, glsl/lecture1/voronoi_mesh.*",
            "as the source: cones for points, tents for segments, flat tops for triangles, \
             their sides chosen from the asked error; the depth interpolated across each \
             mesh; 2D only",
        )
        .covers(&[paths::VORONOI_MESH]),
        Fidelity::new(
            "swept volume: primitives, distance field, classification, isosurface",
            "Kim, Varadhan, Lin & Manocha, SM 2003 / CAD 2004 (abstract: five stages)",
            "src/lecture1/swept_volume/",
            "reconstruction: K poses sampled from keyframes (linear translation, slerp), each \
             edge's bilinear ruled quad between poses split within epsilon, the model's faces \
             at each pose; the field of stage 2 by the slices above, clamped near the \
             surface; stage 3 by a flood fill from the grid's border, not fast marching \
             (same inside/outside answer on a grid, far simpler); stage 4 by marching \
             tetrahedra with sharp edges kept (Kobbelt et al. 2001); stage 5, topological \
             refinement, not built: the Euler characteristic and genus are reported instead",
        )
        .covers(&[paths::SWEPT_VOLUME]),
        Fidelity::new(
            "penetration depth by rasterized Minkowski sums",
            "Kim, Otaduy, Lin & Manocha, SCA 2002 (abstract and introduction only)",
            "src/lecture1/penetration/, glsl/lecture1/penetration_*",
            "reconstruction: convex pieces (a non-convex one refused), pairwise sums by \
             parry3d's hull, a cube map around the origin whose passes raise each ray's exit \
             from the union by MAX blending until an occlusion query counts no raise, a \
             min-reduction read back; refined on the CPU from the planes of the sums near \
             the bound (the paper's refinement is not public)",
        )
        .covers(&[paths::PENETRATION]),
        Fidelity::new(
            "continuous collision for an avatar by swept volumes",
            "Kim, Redon, Lin, Manocha & Templeman, Presence 16(2) 2007 (abstract only)",
            "src/lecture1/avatar_ccd/, glsl/lecture1/avatar_visibility.*",
            "reconstruction: capsule links, joint angles interpolated linearly; a speed bound \
             per link from its chain instead of the paper's interval arithmetic, giving a \
             swept capsule per sub-interval; parry3d's BVH over the environment; the GPU query \
             is CULLIDE's visibility culling with occlusion queries (chosen: a co-author's \
             method of the same years, within a GeForce 6800's features), both sets grown by a \
             pixel as in R-CULLIDE so no contact is culled; exact segment-triangle distances; \
             conservative advancement instead of an unstated search",
        )
        .covers(&[paths::AVATAR_CCD]),
        Fidelity::new(
            "the avatar's scene",
            "Presence 2007: a 16-link avatar among hundreds of thousands of polygons",
            "src/lecture1/avatar_ccd/body.rs, src/lecture1/avatar_ccd/environment.rs",
            "ours: a 13-link walking figure in a room of 38 triangles (floor, wall, bench, \
             pillar), small enough for the CPU reference's dense sampling in a test",
        )
        .covers(&[paths::AVATAR_SCENE]),
        Fidelity::new(
            "the avatar's scene at the published scale (`avatar-ccd --scale published`)",
            "Presence 2007: a 16-link avatar among hundreds of thousands of polygons (the \
             paper's models are not public)",
            "src/lecture1/avatar_ccd/body.rs (avatar16), environment.rs (published_room)",
            "ours, generated: the walker with a neck and two hands (16 links) in the room with \
             eight upright tori of 12,800 triangles each beside the walk (102,438 triangles); \
             the reference's brute force runs on the triangles within 0.25 of the motion's \
             box (a farther one cannot come within the tolerance). Run once in the full \
             report (under a second on llvmpipe), not in the quick one",
        )
        .covers(&[paths::AVATAR_PUBLISHED]),
    ]
}
