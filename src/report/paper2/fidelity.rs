//! The GL features of paper 2, where this code uses them, and what differs from the paper.

use super::bench::Paper2Results;
use crate::report::Fidelity;

pub fn rows(results: &Paper2Results) -> Vec<Fidelity> {
    vec![
        Fidelity::new(
            "Vertex data in 1D float textures",
            "Fig. 1-(a): position, normal, bone indices, weights",
            "src/crowd/vertex_textures.rs",
            "none: four RGBA32F 1D textures of m texels (position w = 1, normal w = 0, up to 4 \
             bone indices stored as floats, their weights), read with texelFetch",
        ),
        Fidelity::new(
            "Bone matrices as three row textures",
            "Fig. 1-(b): 3x4 matrices computed on the CPU each frame",
            "src/crowd/bone_textures.rs",
            "none in substance: three RGBA32F 2D textures, texel (bone, character), rewritten \
             every frame; the matrices are computed in f64 and rounded to f32 on upload",
        ),
        Fidelity::new(
            "Skinning in a pixel shader, one draw over n x m",
            "Fig. 2: a row per vertex index",
            "glsl/crowd/pass1_skinning.frag, src/crowd/pass1_skinning.rs",
            "GLSL 330 instead of Cg; positions and normals are two render targets of the one \
             draw; a row holds at most 128 characters (OpenGL 4.4+ caps a vertex attribute's \
             stride at 2048 bytes, which the paper's OpenGL 2 did not), further characters \
             continue in blocks of m rows below; a crowd larger than one render target holds \
             is split into batches, one pass-1 draw each",
        ),
        Fidelity::new(
            "Render target to VBO through a PBO, RGBA32F",
            "Section 2 [7, 8]",
            "src/crowd/render_to_vbo.rs",
            "none: glReadPixels into a buffer bound as the pixel pack buffer, the same buffer \
             then bound as the vertex buffer; the normals are copied too (the paper lists them \
             among the skinning data without saying how pass 2 gets them)",
        ),
        Fidelity::new(
            "Pass 2 with a shared index buffer",
            "Section 2",
            "glsl/crowd/pass2_draw.vert, src/crowd/pass2_draw.rs",
            "the paper does not say how a character's vertices are addressed in the VBO: here \
             one vertex array per render-target column (offset = the column, stride = one row) \
             and one indexed draw per character",
        ),
        Fidelity::new(
            "Vertex-shader skinning baseline, matrices in uniforms",
            "Table 1 'VS' [4]",
            "glsl/crowd/vs_skinning.vert, src/crowd/vertex_shader_skinning.rs",
            &format!(
                "measured two ways: as many characters per instanced draw as the uniform space \
                 holds ({} here), and one character per draw ('VS 1/draw'), as the paper's \
                 hardware had to (a few hundred constant registers, no instancing in OpenGL 2)",
                results.vertex_shader_batch()
            ),
        ),
        Fidelity::new(
            "3 LODs (1,084 / 544 / 312 polygons), view-frustum culling",
            "Section 3, Fig. 4-5",
            "src/crowd/lod.rs, src/crowd/culling.rs",
            "the polygon counts are met exactly by tessellating this project's procedural \
             models to budget; the distances at which the LOD changes are this project's (the \
             paper gives none); culling tests each character's animated bounding sphere against \
             the six frustum planes on the CPU (the paper does not say how it culls)",
        ),
        Fidelity::new(
            "Sprites in the far field",
            "Tutorial lecture 2 (sprite LOD)",
            "src/crowd/sprites.rs, glsl/crowd/sprite.vert, glsl/crowd/sprite.frag",
            "not in the paper (the tutorial's lecture 2 mentions sprites for larger crowds): \
             an impostor atlas of the coarsest mesh, 8 views x 8 animation phases, drawn as \
             camera-facing quads beyond the last LOD distance; the Fig. 4-5 runs here use it",
        ),
        Fidelity::new(
            "Behaviour control",
            "Tutorial lecture 2",
            "src/crowd/steering.rs",
            "not in the paper (the tutorial says the method combines with behaviour control): \
             seek + separation steering after Reynolds gives each character its own position, \
             heading and animation phase; it runs between frames and is not timed",
        ),
    ]
}
