//! Paper 2 walked (Kang & Han 2006): eight soldiers skinned in a pixel shader, copied into a
//! vertex buffer and drawn from it, each buffer shown and checked.

use super::{buffer_png, Check, Shot, Step, Walk};
use crate::crowd::bone_textures::BoneTextures;
use crate::crowd::character::Instances;
use crate::crowd::cpu_skinning;
use crate::crowd::culling::Camera;
use crate::crowd::pass1_skinning::{Pass1, SkinningTarget};
use crate::crowd::pass2_draw::{CharacterArrays, Pass2, Shading};
use crate::crowd::render_to_vbo::SkinnedVbo;
use crate::crowd::scene;
use crate::crowd::vertex_textures::VertexTextures;
use crate::crowd::{CharacterModel, ModelKind};
use crate::gl::{dump, Buffer, BufferUsage, Context};
use glam::{DAffine3, DVec3, Vec3};
use std::path::Path;

pub const WALK: Walk = Walk {
    id: "paper2",
    title: "Paper 2 walked: a crowd skinned in a pixel shader",
    source: "Kang & Han, \"Real-Time Animation of Large Crowds\", ICEC 2006 (LNCS 4161), \
             section 2.",
    run_is: "8 soldiers of the finest LOD in a row, each at another point of its walk",
    steps: STEPS,
    run,
};

const STEPS: &[Step] = &[
    Step {
        pass: "vertex and bone textures",
        section: "Sec. 2, Fig. 1",
        step: "vertex data and the bone matrices of the frame stored in float textures",
        reads: "the character's mesh (positions, normals, bone indices and weights) and each \
                character's bone matrices, on the CPU",
        writes: "four 1D vertex textures of m texels (uploaded once), and three bone textures \
                 (one row of a 3x4 matrix each; a texel per bone, a texture row per character)",
        code: &[
            ("src/crowd/vertex_textures.rs", "vertex-textures"),
            ("src/crowd/bone_textures.rs", "bone-textures"),
        ],
        lesson: "texture-is-array",
    },
    Step {
        pass: "pass 1: skinning in the pixel shader",
        section: "Sec. 2, Fig. 2",
        step: "a rectangle of n characters x m vertices drawn: each pixel skins one vertex of \
               one character",
        reads: "the vertex textures and the bone textures",
        writes: "two RGBA32F render targets, skinned positions and normals: column c is \
                 character c, row v its vertex v",
        code: &[
            ("src/crowd/pass1_skinning.rs", "pass1"),
            ("glsl/crowd/pass1_skinning.frag", "pass1-main"),
        ],
        lesson: "several-outputs",
    },
    Step {
        pass: "render to vertex buffer",
        section: "Sec. 2",
        step: "the render target copied into a vertex buffer through a pixel buffer object",
        reads: "the two render targets of pass 1",
        writes: "one buffer: all positions, then all normals, in the target's order, copied on \
                 the GPU (glReadPixels into a buffer bound as the pixel pack buffer)",
        code: &[("src/crowd/render_to_vbo.rs", "copy-to-vbo")],
        lesson: "render-to-vertex-buffer",
    },
    Step {
        pass: "pass 2: draw from the vertex buffer",
        section: "Sec. 2",
        step: "every character drawn from the vertex buffer with the shared index buffer",
        reads: "the vertex buffer (one vertex array per character, offset into it) and the \
                index buffer of the mesh",
        writes: "the frame",
        code: &[
            ("src/crowd/pass2_draw.rs", "pass2"),
            ("glsl/crowd/pass2_draw.vert", "pass2-main"),
        ],
        lesson: "render-to-vertex-buffer",
    },
];

/// Characters of the small run.
const N: u32 = 8;
/// Ground spacing between them.
const SPACING: f64 = 2.0;
/// The size of the frame pass 2 draws.
const FRAME: (u32, u32) = (720, 360);

fn run(ctx: &Context, dir: &Path) -> anyhow::Result<Vec<Shot>> {
    let model = CharacterModel::build(ModelKind::Soldier)?;
    let mesh = &model.lods[0];
    let m = mesh.vertex_count() as u32;
    let bone_count = model.bone_count();
    let models: Vec<DAffine3> = (0..N)
        .map(|c| DAffine3::from_translation(DVec3::new((c as f64 - 3.5) * SPACING, 0.0, 0.0)))
        .collect();
    let phases: Vec<f64> = (0..N).map(|c| c as f64 / N as f64).collect();
    let instances = Instances {
        models: &models,
        phases: &phases,
    };
    let ids: Vec<usize> = (0..N as usize).collect();
    let matrices = instances.bone_matrices(&model, &ids);
    let mut shots = Vec::new();

    // The textures.
    let vertices = VertexTextures::upload(ctx, mesh)?;
    let bones = BoneTextures::new(ctx, bone_count as u32, N)?;
    bones.upload(&matrices)?;
    let position = vertices.position.download_f32()?;
    let row0 = bones.rows[0].download_f32()?;
    shots.push(Shot {
        pictures: vec![
            buffer_png(
                dir,
                "vertex_positions.png",
                "vertex texture: position",
                &position,
                4,
                &["x", "y", "z"],
                (m, 1),
            )?,
            buffer_png(
                dir,
                "bone_row0.png",
                "bone texture, matrix row 0",
                &row0,
                4,
                &["m00", "m01", "m02", "m03"],
                (bones.rows[0].width(), bones.rows[0].height()),
            )?,
        ],
        key: format!(
            "the vertex texture: one texel per vertex ({m}, a 1D texture stretched upward to be \
             seen), the bind pose; the bone texture: a texel per bone ({bone_count} across), a \
             row per character ({N} up, row 0 at the bottom), the first row of each 3x4 \
             matrix; blue below zero, red to yellow above"
        ),
        check: None,
    });

    // Pass 1.
    let target = SkinningTarget::new(ctx, N, m)?;
    Pass1::new(ctx)?.run(&target, &vertices, &bones, N)?;
    let texture = target.framebuffer.color(0);
    let dims = (texture.width(), texture.height());
    let skinned = texture.download_f32()?;
    let mut worst = 0.0f64;
    for c in 0..N as usize {
        let cpu = cpu_skinning::skin(mesh, &matrices[c * bone_count..(c + 1) * bone_count]);
        for (v, p) in cpu.positions.iter().enumerate() {
            let k = 4 * (v * dims.0 as usize + c);
            for axis in 0..3 {
                let d = (skinned[k + axis] as f64 - p[axis]).abs();
                worst = if d.is_nan() {
                    f64::INFINITY
                } else {
                    worst.max(d)
                };
            }
        }
    }
    shots.push(Shot {
        pictures: vec![buffer_png(
            dir,
            "pass1_positions.png",
            "pass 1 positions",
            &skinned,
            4,
            &["x", "y", "z"],
            dims,
        )?],
        key: format!(
            "column c is character c ({N} across), row v its vertex v ({m} up, row 0 at the \
             bottom); x grows along the row of soldiers, y is the height, z the walk's sway"
        ),
        check: Some(Check {
            what: format!(
                "the skinned positions against the CPU's linear blend skinning in f64: largest \
                 difference {worst:.1e} (tolerance 1e-4, fp32 coordinates of a few units)"
            ),
            passed: worst <= 1e-4,
        }),
    });

    // Render to vertex buffer.
    let vbo = SkinnedVbo::new(ctx, &target)?;
    vbo.copy_from(&target, N)?;
    let all: Vec<[f32; 4]> = vbo.buffer.read()?;
    let in_buffer: Vec<f32> = all[..skinned.len() / 4].iter().flatten().copied().collect();
    let differ = in_buffer
        .iter()
        .zip(&skinned)
        .filter(|(a, b)| a != b)
        .count();
    shots.push(Shot {
        pictures: vec![buffer_png(
            dir,
            "vbo_positions.png",
            "vertex buffer positions",
            &in_buffer,
            4,
            &["x", "y", "z"],
            dims,
        )?],
        key: "the vertex buffer's first half read back and laid out as the render target it was \
              copied from (the same picture as pass 1's, as it should be)"
            .into(),
        check: Some(Check {
            what: format!(
                "the buffer against pass 1's target, value by value: {differ} of {} differ \
                 (tolerance: none, a copy)",
                skinned.len()
            ),
            passed: differ == 0 && in_buffer.len() == skinned.len(),
        }),
    });

    // Pass 2.
    let frame = scene::scene_target(ctx, FRAME.0, FRAME.1)?;
    scene::clear(&frame)?;
    let indices = Buffer::from_slice(ctx, &mesh.mesh.triangles, BufferUsage::Static)?;
    let arrays = CharacterArrays::new(ctx, &vbo, &indices)?;
    let camera = Camera {
        eye: Vec3::new(2.0, 4.0, 13.0),
        target: Vec3::new(0.0, 0.9, 0.0),
        fov_y: 45f32.to_radians(),
        aspect: FRAME.0 as f32 / FRAME.1 as f32,
        near: 0.1,
        far: 100.0,
    };
    let shading = Shading {
        view_projection: camera.projection() * camera.view(),
        colour: Vec3::new(0.55, 0.6, 0.45),
        light: Vec3::new(0.4, 0.8, 0.45).normalize(),
    };
    Pass2::new(ctx)?.draw(
        &frame,
        &shading,
        &arrays,
        N as usize,
        mesh.triangle_count() * 3,
    )?;
    dump::texture_png(
        frame.color(0),
        &dir.join("frame.png"),
        dump::DumpRange::Auto,
    )?;
    shots.push(Shot {
        pictures: vec!["frame.png".into()],
        key: format!(
            "the frame ({} x {} pixels), the {N} soldiers lit by one light, each drawn by one \
             call from its columns of the vertex buffer",
            FRAME.0, FRAME.1
        ),
        check: None,
    });
    Ok(shots)
}
