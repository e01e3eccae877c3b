//! What the papers and the lectures' sources name and this project does not build: one table
//! per section that has such things (papers 3 and 4, lectures 1 and 3, and the tutorial's
//! lecture 5 under the building blocks), each row with what would be needed to build it.

use super::Table;

/// One thing a source names that the project does not do.
#[derive(Clone, Copy, Debug)]
pub struct NotBuilt {
    /// What is not built.
    pub what: &'static str,
    /// The paper or source that names it.
    pub source: &'static str,
    /// What the project does instead, if anything.
    pub instead: &'static str,
    /// What building it would take.
    pub needed: &'static str,
}

/// The section's "not built" table; `named_by` is who names the rows, with its verb ("the
/// sources of lecture 3 name", "paper 4 names").
pub fn table(named_by: &str, rows: &[NotBuilt]) -> Table {
    Table {
        caption: format!(
            "Not built: what {named_by} that this project does not do, what it does instead, \
             and what building it would need"
        ),
        header: ["not built", "named by", "instead", "what it would need"]
            .map(String::from)
            .to_vec(),
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    r.what.into(),
                    r.source.into(),
                    r.instead.into(),
                    r.needed.into(),
                ]
            })
            .collect(),
    }
}

/// Lecture 1 (`lecture1-sources.md`).
pub const LECTURE1: &[NotBuilt] = &[
    NotBuilt {
        what: "penetration depth: hierarchical refinement over bounding volume hierarchies, \
               and object- and image-space culling beyond one bound",
        source: "Kim, Otaduy, Lin & Manocha, SCA 2002 (abstract)",
        instead: "every pair of convex pieces summed; sums farther than a box bound dropped; \
                  the estimate refined on the CPU from the planes of the sums near the bound",
        needed: "a BVH over each model's convex pieces, traversed pair by pair with the \
                 current upper bound as the cull distance, and the cube-map pass run per \
                 surviving node; the paper's refinement rule (not public) or a stated one",
    },
    NotBuilt {
        what: "penetration depth: model simplification and tolerance verification",
        source: "tech report TR02-014 (listed; text not public)",
        instead: "the full models; the error against the exact depth reported by resolution",
        needed: "a simplification with a distance bound (e.g. edge collapses with a Hausdorff \
                 bound) and a check that the depth on the simplified pair is within the bound \
                 of the depth on the originals",
    },
    NotBuilt {
        what: "automatic convex decomposition of non-convex models",
        source: "SCA 2002 abstract (both models decomposed into convex pieces)",
        instead: "each OBJ object or group is a convex piece; a non-convex piece is refused",
        needed: "an exact decomposition (e.g. Chazelle's cuts) to keep the depth exact; parry3d's \
                 VHACD is approximate, so the depth would carry its concavity error, to be \
                 stated and measured",
    },
    NotBuilt {
        what: "swept volumes: classification by fast-marching front propagation",
        source: "Kim, Varadhan, Lin & Manocha, SM 2003 / CAD 2004 (stage 3)",
        instead: "a flood fill from the grid's border through voxels farther than the clamp",
        needed: "a fast-marching solver on the grid (a heap of trial voxels, the eikonal \
                 update); the same inside/outside answer, plus a signed distance away from the \
                 surface",
    },
    NotBuilt {
        what: "swept volumes: topological refinement of the extracted surface",
        source: "SM 2003 / CAD 2004 (stage 5)",
        instead: "the Euler characteristic and genus of the extracted surface are reported",
        needed: "the paper's refinement rule (not public) or adaptive subdivision where the \
                 grid's topology and the primitives' disagree, with a Hausdorff bound \
                 (Varadhan & Manocha 2004)",
    },
    NotBuilt {
        what: "avatar CCD: swept surfaces generated at run time and queried on the GPU",
        source: "Kim, Redon, Lin, Manocha & Templeman, Presence 2007 (abstract)",
        instead: "a swept capsule bound per link and sub-interval, drawn for CULLIDE-style \
                  occlusion-query culling; exact distances on the CPU",
        needed: "each link's swept surface as triangles (its ruled and developable patches \
                 between poses), drawn against the environment for the interference query",
    },
    NotBuilt {
        what: "avatar CCD: interval arithmetic bounding each link's swept space",
        source: "Presence 2007 (abstract)",
        instead: "a speed bound per link from its chain, giving a capsule per sub-interval",
        needed: "interval versions of the forward kinematics (sine and cosine of interval \
                 angles), giving an interval box per link and sub-interval",
    },
    NotBuilt {
        what: "avatar CCD on the paper's own models",
        source: "Presence 2007 (abstract: a 16-link avatar, hundreds of thousands of polygons)",
        instead: "the published scale with generated models (`avatar-ccd --scale published`: \
                  16 links, 102,438 triangles), run in the full report",
        needed: "the paper's avatar and environment meshes, which are not public",
    },
    NotBuilt {
        what: "general arrangements of surfaces (the lecture's 'arrangement computation')",
        source: "lecture 1 programme; SM 2003 / CAD 2004; Varadhan & Manocha 2004",
        instead: "only the outer boundary of the swept primitives' arrangement, by a grid field",
        needed: "every cell of the arrangement (inner boundaries too), e.g. by labelling each \
                 connected region of the grid field and extracting each region's boundary",
    },
    NotBuilt {
        what: "DiFi's Voronoi-region bounds for the distance field",
        source: "Sud, Otaduy & Manocha, EG 2004",
        instead: "each triangle's rectangle (exact method) or each feature's mesh (Hoff's \
                  method, `--method mesh`) grown by the clamp, or over the whole slice without \
                  one",
        needed: "the region of each primitive bounded by its Voronoi region (the distance \
                 beyond which a neighbour is surely nearer), culled per slice",
    },
];

/// Lecture 3 (`lecture3-sources.md`, and the programme's three references).
pub const LECTURE3: &[NotBuilt] = &[
    NotBuilt {
        what: "adaptive screen interpolation for translucent objects",
        source: "Ki & Oh, Korea Game Society summer conference 2006, pp. 217-224 (the \
                 lecture's third reference; its title only, the text is not public)",
        instead: "the subsurface term is gathered over the light hierarchy for every receiver \
                  texel (`lecture3 light --mode sss`); nothing is interpolated on the screen",
        needed: "the paper's rule, or a stated one: shade a coarse grid of pixels, interpolate \
                 between neighbours whose results differ by less than a threshold and shade \
                 the rest, with the error against shading every pixel measured",
    },
    NotBuilt {
        what: "pyramidal displacement mapping on a general mesh",
        source: "Oh, Ki & Lee, VRST 2006 (abstract: per-pixel ray tracing of a displacement map)",
        instead: "the height field lies on one box, traced in the box's frame",
        needed: "per-vertex tangent frames and the ray carried into each triangle's texture \
                 space, with the pyramid traversal unchanged",
    },
    NotBuilt {
        what: "the sources' own traversal and clustering rules",
        source: "VRST 2006 and Ki & Oh 2008 (abstracts only)",
        instead: "reconstructions (see the fidelity table): climb one level after each node \
                  left; a cluster is one light when its radius is under theta times its distance",
        needed: "the papers' full texts",
    },
    NotBuilt {
        what: "occlusion in the light hierarchy's gather",
        source: "Ki & Oh 2008 (abstract: occlusion ignored)",
        instead: "no occlusion, as in the source",
        needed: "a visibility term per light group (shadow maps per cluster, or a depth test \
                 against the group's representative), which the source does not have",
    },
    NotBuilt {
        what: "octrees as textures for painting or sparse storage, updated on the GPU",
        source: "lecture 3 programme ('octrees and quadtrees on the GPU')",
        instead: "an occupancy octree of a point set built by reduction passes and ray cast",
        needed: "an indirection-pool layout (nodes as texel blocks) and passes that insert and \
                 remove nodes",
    },
];

/// Paper 3 (Oh & Jung 2004).
pub const PAPER3: &[NotBuilt] = &[NotBuilt {
    what: "learning on the GPU",
    source: "paper 3, abstract ('GPU-aware learning algorithms' named as further research)",
    instead: "the detector is trained on the CPU by online backpropagation (`mlp train`, \
              src/mlp/train.rs); only the forward pass, the paper's subject, runs on the GPU",
    needed: "backpropagation as render passes: the output error and each layer's deltas as \
             textures (the transposed weights times the deltas by the same rectangle product), \
             and a pass adding the outer product of deltas and inputs to the weights, over a \
             batch of accumulated input vectors",
}];

/// Paper 4 (Kim, Kim, Ko & Terzopoulos 2006).
pub const PAPER4: &[NotBuilt] = &[NotBuilt {
    what: "a fluid surface that is not a plane (waves, a height field)",
    source: "paper 4, section 5.2: pass 0 draws 'the surface of the fluid' into T_dw, assumed \
             only to keep the sign of its normals' z",
    instead: "the water is the plane z = h in pass 0 and in the fluid patch of pass n + 1 \
              (the fidelity table's n + 2 passes row)",
    needed: "a height field drawn in pass 0 and as the patch of pass n + 1, a fluid simulation \
             or a prescribed wave to move it (the paper leaves fluid motion out), and a CPU \
             reference that clips each body against that surface",
}];

/// The tutorial's lecture 5, NVIDIA's G80 and CUDA (the programme, item 4).
pub const LECTURE5: &[NotBuilt] = &[NotBuilt {
    what: "CUDA on NVIDIA's G80: the architecture and its programming model",
    source: "the tutorial programme, item 4 (G80 architecture, CUDA technology)",
    instead: "OpenGL 4.3 compute shaders stand in: each paper's kernels as compute dispatches \
              (threads in groups, shared memory, storage buffers, atomics: CUDA's model), on \
              any GL 4.3 renderer, beside the classic passes in each section's 'then and now' \
              table, and the course's compute reduction (`learn compute-reduction`)",
    needed: "an NVIDIA GPU and the CUDA toolkit (a G80 for the period's numbers), the kernels \
             written in CUDA C, and CUDA-OpenGL interop to share buffers with the classic \
             passes",
}];
