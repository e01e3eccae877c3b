//! The GL features of paper 1, where this code uses them, and what differs from the paper.

use crate::report::Fidelity;

pub fn rows() -> Vec<Fidelity> {
    vec![
        Fidelity::new(
            "1D float AABB textures T_min/T_max",
            "Sec. 4.2.1",
            "src/collide/aabb_textures.rs",
            "none: two RGBA32F 1D textures, one texel per slot (alpha unused), wrapped to repeat \
             so that they texture the rectangle periodically; with tiles, one pair per stream \
             segment",
        ),
        Fidelity::new(
            "virtual nodes and the stencil array",
            "Sec. 4.1, 4.2.1",
            "src/collide/stream_setup.rs",
            "the paper states its marking rule for one pulled-down level (first virtual sibling \
             1, second 0), which this follows; a leaf pulled down k > 1 levels marks only the \
             first of its 2^k copies, so no leaf pair is tested twice. The top-down split (median \
             centroid on the longest axis) is this project's reading of the cited SOLID build",
        ),
        Fidelity::new(
            "stencil buffer masking virtual pairs",
            "Sec. 5.2, Fig. 5",
            "glsl/collide/stencil_mask.frag",
            "the paper does not say how the stencil buffer is filled from the two arrays: here a \
             fragment pass over the rectangle writes 1 where both slots are marked; it is written \
             once when the pair fits one tile, and again for every tile otherwise",
        ),
        Fidelity::new(
            "Cg fragment program of Table I",
            "Table I",
            "cg_ports/collide_table1_streaming_aabb_test.frag",
            "Cg ported line for line to GLSL 330: TEXCOORD0/1 become the varyings uvA/uvB, \
             tex1D texture(), COLOR an output; the printed listing's broken operators ('|', a \
             typeset '\\parallel') read as '||'; P0 is R32F, so only the red 1.0 is kept",
        ),
        Fidelity::new(
            "Table I's function, its parameters and its casts",
            "Table I: void streamingAABBTest(...) taking the texture coordinates, the output \
             and the four samplers as parameters; (float3) casts on each tex1D(...).xyz",
            "cg_ports/collide_table1_streaming_aabb_test.frag",
            "GLSL has no parameters on a shader's entry point: the function becomes main(), \
             its uniform samplers become global uniforms, its inputs global in-varyings and \
             its out parameter a global output; the (float3) casts are dropped, since .xyz \
             already gives a vec3 (the casts change nothing in Cg either)",
        ),
        Fidelity::new(
            "vertex texture 2^d_max x n_max, alpha = empty",
            "Sec. 4.2.2",
            "src/collide/vertex_textures.rs",
            "n_max counts a leaf's unique vertices, not its triangles: the paper defines n_max \
             by triangles yet stores one vertex per texel, so a column must hold the vertices; \
             virtual slots hold their leaf's vertices",
        ),
        Fidelity::new(
            "one line into two render targets (MRT), Table II",
            "Sec. 6, Table II",
            "cg_ports/collide_table2_stream_update.frag",
            "our copy of the paper has Table II's caption but not its Cg lines: the port is \
             rebuilt from Sec. 6's account (one line, one fragment per AABB, column-wise min and \
             max over the n_max texels skipping alpha-0 ones, COLOR0 = T_min and COLOR1 = T_max \
             through MRT)",
        ),
        Fidelity::new(
            "hierarchical 4x4 encoding P1..P3, reduced 8x8 P1'",
            "Sec. 5.3",
            "glsl/collide/encode_4x4.frag, encode_8x8.frag",
            "the paper does not say how a pixel encodes its block: here a P_i+1 texel is the \
             16-bit mask of its 4x4 block (an exact integer in a float) and a P1' texel the 64 \
             bits of its 8x8 block, 16 per RGBA channel; decoding reads one rectangle per set \
             parent texel and never P0. A third scheme, full readback of P0, is added for \
             comparison",
        ),
        Fidelity::new(
            "eta switch (measured, not copied)",
            "Sec. 5.3.2, Fig. 7",
            "src/collide/reduction_gpu.rs",
            "the paper's fixed threshold (0.095%, measured on the 7800 for a 2048 x 2048 P0) is \
             offered as the paper-switch readback and used by the tile study; the default, auto, \
             calibrates all three schemes on this renderer at this P0 size and picks per frame \
             the fastest at the nearest calibrated eta, full readback included (the paper has \
             only hierarchical and reduced). The calibration fills P0 with clustered CAPs, \
             blobs fitted to the scenes' own P0s, as Sec. 5.3.1 assumes; Fig. 7 is drawn on \
             clustered and on uniform contents",
        ),
        Fidelity::new(
            "tiles sharing one render target",
            "Sec. 5.5",
            "src/collide/tiles.rs",
            "tiles are at most 4096 slots (the 7800's limit) or the renderer's texture limit; \
             at the automatic leaf sizes every scene fits one tile, so the tile study (Sec. 5.5 \
             table) forces tiles smaller than the limit on the interlocking tori (--max-tile \
             does the same in collide); the stencil is re-filled for every tile, a cost the \
             paper does not discuss",
        ),
        Fidelity::new(
            "occlusion queries (CULLIDE; CAP count)",
            "Sec. 7.4.2",
            "src/collide/cullide.rs",
            "CULLIDE is reimplemented from its own paper (the authors used the CULLIDE library, \
             further optimised): orthographic views along x, y, z over the overlap of the two \
             global boxes, as the manually optimised view directions are not published. The \
             streaming pipeline also counts its CAPs with an occlusion query, which the paper \
             does not describe, so eta is known before the readback",
        ),
        Fidelity::new(
            "leaf size n of the AABB stream",
            "Sec. 4.1 (a user-provided number)",
            "src/collide/stream_setup.rs",
            "the paper does not give n: here it is chosen per model and renderer, 32 doubled \
             until a stream has at most 512 slots on a software renderer (every P0 pixel is CPU \
             time) or 4096 on a GPU, from the leaf-size sweep; --leaf-size sets it",
        ),
        Fidelity::new(
            "benchmark scenes and their deformations",
            "Sec. 7.2, Table III, Fig. 8-9",
            "src/collide/scenes.rs, src/collide/deform.rs",
            "the paper's meshes and motions are not published: tori and the re-tessellated \
             bunny are generated here; the happy buddhas (20K) and intimate animals (50K) are \
             stand-ins of the same triangle counts (two trefoil-knot tubes, two facing bunnies); \
             the wavy and pulsating deformations are closed-form functions of this project",
        ),
        Fidelity::new(
            "Möller's triangle/triangle test on the CPU",
            "Sec. 5.4 [39]",
            "src/collide/tri_test.rs",
            "Möller's interval test without the original code's epsilon snapping, f32 inputs in \
             f64 arithmetic (the paper: 32-bit floats throughout), with an exact-predicate \
             alternative; each triangle's own box is tested first",
        ),
        Fidelity::new(
            "SOLID's AABB-tree refit (CPU baseline)",
            "Sec. 7.4.1 [2]",
            "src/collide/solid.rs",
            "the paper's own implementation of SOLID's scheme is not published: here the same \
             leaves in a CPU tree, every node refitted bottom-up each frame and the tree pair \
             traversed; the triangle test is the pipeline's",
        ),
        Fidelity::new(
            "Cg (vp40/fp40) on OpenGL 2.0, GeForce 7800 GTX",
            "Sec. 7.1",
            "glsl/collide/, cg_ports/",
            "GLSL 330 core on OpenGL 3.3 or later, on the renderer at hand (Mesa's llvmpipe by \
             default, a CPU rasterizer): every time in the tables is this renderer's, never the \
             7800's",
        ),
    ]
}
