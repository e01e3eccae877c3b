//! The GL features of paper 2, where this code uses them, and what differs from the paper.

use super::bench::Paper2Results;
use crate::crowd::ModelKind;
use crate::report::Fidelity;

pub fn rows(results: &Paper2Results) -> Vec<Fidelity> {
    let setup = &results.setup;
    let [lod0_until, lod1_until] = setup.lod_policy.mesh_until;
    let sprites_beyond = setup
        .sprite_policy
        .sprites_beyond
        .map_or("-".to_string(), |d| format!("{d:.0} m"));
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
            &format!(
                "not one draw for all: a row holds at most {} characters (OpenGL 4.4+ caps a \
                 vertex attribute's stride at 2048 bytes, which the paper's OpenGL 2 did not) \
                 and further characters continue in blocks of m rows, up to the largest \
                 texture ({} texels here), so one draw skins at most {} at LOD 0; a larger \
                 crowd is skinned in batches, each with its own pass 1, copy and pass 2; GLSL \
                 330 instead of Cg; positions and normals are two render targets of each draw",
                setup.row_characters,
                setup.max_texture_size,
                lod0_limits(results)
            ),
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
            &format!(
                "the polygon counts are the paper's, met exactly by tessellating this project's \
                 models to budget; the distances at which the LOD changes, {lod0_until:.0} m and \
                 {lod1_until:.0} m, are this project's (the paper gives none), as are the \
                 scenes' cameras and spacing; LOD 2 reaches to the far plane, as the paper has \
                 no further level; culling tests each character's animated bounding sphere \
                 against the six frustum planes on the CPU (the paper does not say how it culls)"
            ),
        ),
        Fidelity::new(
            "Sprites in the far field",
            "Tutorial lecture 2 (sprite LOD)",
            "src/crowd/sprites.rs, glsl/crowd/sprite.vert, glsl/crowd/sprite.frag",
            &format!(
                "an extension, not in the paper (the tutorial's lecture 2 mentions sprites for \
                 larger crowds): an impostor atlas of the coarsest mesh, 8 views x 8 animation \
                 phases, drawn as camera-facing quads beyond {sprites_beyond} (this project's \
                 distance); measured only in the Fig. 4-5 rows marked 'extension', on the same \
                 crowds as the paper's setup, never in the comparison with the paper"
            ),
        ),
        Fidelity::new(
            "Character models: skeletons, props, clips",
            "Table 1, Fig. 3-5: a rigged soldier and horse, up to 4 bones per vertex; bone \
             counts, props and animations not given",
            "src/crowd/soldier.rs, src/crowd/horse.rs, src/crowd/character.rs",
            &models_deviation(results),
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

/// "3712 soldiers or 3712 horses": what one pass-1 draw holds at LOD 0, per model.
fn lod0_limits(results: &Paper2Results) -> String {
    results
        .models
        .iter()
        .filter_map(|m| {
            let lod0 = m.lods.first()?;
            Some(format!("{} {}s", lod0.characters_per_draw, m.model.name()))
        })
        .collect::<Vec<_>>()
        .join(" or ")
}

/// The models' bone counts and the soldier's spear, as built, declared as this project's.
fn models_deviation(results: &Paper2Results) -> String {
    let bones = |kind: ModelKind| {
        results
            .model(kind)
            .map_or("?".to_string(), |m| m.bones.to_string())
    };
    let spear = results.model(ModelKind::Soldier).is_some_and(|m| m.spear);
    format!(
        "procedural stand-ins, as the paper's meshes are not published: the soldier's {} bones{}, \
         the horse's {} bones, their proportions and the walk and gallop clips are this \
         project's choices; only the LOD polygon counts and the 4 bones per vertex are the \
         paper's",
        bones(ModelKind::Soldier),
        if spear {
            " (one of them a spear in the right hand)"
        } else {
            ""
        },
        bones(ModelKind::Horse)
    )
}
