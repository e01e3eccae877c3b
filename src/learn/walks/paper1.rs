//! Paper 1 walked (Zhang & Kim 2007): one frame of two small tori through each other, pass by
//! pass, with the AABB overlap pass (Sec. 5.2) checked against the CPU's interval test.

use super::{buffer_png, Check, Shot, Step, Walk};
use crate::collide::pipeline::{Options, StreamingCollider};
use crate::collide::reduction::Scheme;
use crate::collide::reduction_gpu::ReadbackMode;
use crate::collide::Aabb;
use crate::gl::{Context, Texture};
use crate::mesh::{self, Mesh};
use glam::Vec3;
use std::path::Path;

pub const WALK: Walk = Walk {
    id: "paper1",
    title: "Paper 1 walked: collision detection with streaming AABBs",
    source: "Zhang & Kim, \"Interactive Collision Detection for Deformable Models using \
             Streaming AABBs\", IEEE TVCG 13(2), 2007, sections 5 and 6.",
    run_is: "two tori of about 400 triangles through each other, at most 12 triangles a leaf: \
             the leaves lie at two depths, so the shallower are pulled down and copied into \
             virtual slots",
    steps: STEPS,
    run,
};

const STEPS: &[Step] = &[
    Step {
        pass: "stream update",
        section: "Sec. 6",
        step: "Stream Update (Table II: min/max over each column of the vertex texture)",
        reads: "the vertex texture of a model (one column per leaf, its vertices down the column)",
        writes: "T_min and T_max, one texel per AABB slot, both at once (two render targets)",
        code: &[
            ("src/collide/stream_update.rs", "stream-update"),
            ("cg_ports/collide_table2_stream_update.frag", "table2"),
        ],
        lesson: "several-outputs",
    },
    Step {
        pass: "stream pairing: the stencil of the virtual pairs",
        section: "Sec. 5.2, step 1 (with Sec. 4.2.1)",
        step: "Stream Pairing (the stencil arrays prevent the pairs of virtual nodes, PAPs)",
        reads: "the 1D stencil arrays of X (rows) and Y (columns)",
        writes: "the stencil buffer of P0: 1 where both slots take part, 0 for a PAP",
        code: &[
            ("src/collide/streaming_test.rs", "stencil-arrays"),
            ("glsl/collide/stencil_mask.frag", "stencil-mask"),
        ],
        lesson: "count-and-mask",
    },
    Step {
        pass: "streaming AABB overlap test",
        section: "Sec. 5.2, step 2",
        step: "Elementary AABB Overlap Test (Table I), counted by an occlusion query",
        reads: "T_min, T_max of X (uvA, down the rows) and of Y (uvB, along the columns), and \
                the stencil buffer",
        writes: "P0: 1 at pixel (j, i) when box i of X and box j of Y overlap (a CAP), 0 \
                 elsewhere; the occlusion query counts the CAPs",
        code: &[
            ("src/collide/streaming_test.rs", "overlap-pass"),
            ("glsl/collide/aabb_pairs.vert", "stream-pairing"),
            ("cg_ports/collide_table1_streaming_aabb_test.frag", "table1"),
        ],
        lesson: "count-and-mask",
    },
    Step {
        pass: "stream reduction: hierarchical encoding",
        section: "Sec. 5.3.1",
        step: "Hierarchical Readback (P0 encoded into P1, P2, P3, each texel a 4x4 mask)",
        reads: "P0, then each level the one below",
        writes: "P1, P2, P3: texel value = the bit mask of the set texels of a 4x4 block one \
                 level down; the CPU reads P3 and descends only into set blocks",
        code: &[
            ("src/collide/reduction_gpu.rs", "encode-hierarchical"),
            ("glsl/collide/encode_4x4.frag", "encode-4x4"),
        ],
        lesson: "readback-and-upload",
    },
    Step {
        pass: "primitive-level test (CPU)",
        section: "Sec. 5.4",
        step: "Primitive-Level Intersection Test (Möller's triangle test on the PCTPs of each CAP)",
        reads: "the CAPs read back, and the triangles under each of their leaves",
        writes: "the colliding triangle pairs (CTPs), on the CPU",
        code: &[("src/collide/tri_test.rs", "primitive-test")],
        lesson: "readback-and-upload",
    },
];

/// Two tori through each other, about 400 triangles each, their tubes crossing.
pub fn scene() -> (Mesh, Mesh) {
    let x = mesh::torus_with_triangles(1.0, 0.3, 400);
    let turn = glam::Affine3A::from_rotation_x(std::f32::consts::FRAC_PI_2);
    let y = x.transformed(&turn).translated(Vec3::new(0.5, 0.0, 0.0));
    (x, y)
}

/// The leaf size of the small run.
pub const LEAF_SIZE: usize = 12;

fn run(ctx: &Context, dir: &Path) -> anyhow::Result<Vec<Shot>> {
    let (x, y) = scene();
    let options = Options {
        leaf_size: LEAF_SIZE,
        readback: ReadbackMode::Hierarchical,
        ..Options::default()
    };
    let mut collider = StreamingCollider::new(ctx, &x, &y, options)?;
    let frame = collider.frame(&x.positions, &y.positions)?;
    let mut shots = Vec::new();

    // Stream update: T_min and T_max of X.
    let (aabb_x, _) = &collider.x.segments[0];
    let mut pictures = Vec::new();
    for (name, texture) in [("T_min", &aabb_x.t_min), ("T_max", &aabb_x.t_max)] {
        pictures.push(texture_png(
            dir,
            &format!("{name}_X.png"),
            &format!("{name} of X"),
            texture,
            &["x", "y", "z"],
        )?);
    }
    shots.push(Shot {
        pictures,
        key: "one row of texels, one per AABB slot of X (a 1D texture, stretched upward to be \
              seen); each panel one coordinate, blue below zero, red to yellow above"
            .into(),
        check: Some(boxes_check(&collider, &x, &y)?),
    });

    // Stream pairing: the stencil buffer (the low 8 bits of DEPTH24_STENCIL8).
    let target = &collider.target;
    let dims = (target.p0.width(), target.p0.height());
    let stencil: Vec<f32> = target
        .depth_stencil
        .download_u32()?
        .into_iter()
        .map(|v| (v & 0xff) as f32)
        .collect();
    shots.push(Shot {
        pictures: vec![buffer_png(
            dir,
            "stencil.png",
            "stencil of P0",
            &stencil,
            1,
            &["value"],
            dims,
        )?],
        key: format!(
            "rows: slots of X, columns: slots of Y, row 0 at the bottom; 1 (pale) where both \
             slots take part, 0 (grey) for a pair with a virtual node (a PAP): {} of {} pairs \
             masked",
            stencil.iter().filter(|&&s| s == 0.0).count(),
            stencil.len()
        ),
        check: None,
    });

    // The overlap pass: P0 against the CPU's interval test on the same boxes and stencils.
    let p0 = target.p0.download_f32()?;
    let cpu = cpu_p0(&collider, &x, &y);
    let wrong = p0_differences(&p0, &cpu);
    shots.push(Shot {
        pictures: vec![buffer_png(dir, "P0.png", "P0", &p0, 1, &["value"], dims)?],
        key: format!(
            "rows: slots of X, columns: slots of Y; 1 (pale yellow) for a CAP, 0 (grey) for a \
             pair whose boxes are apart or that the stencil masked; {} CAPs of {} pairs \
             (eta = {:.4})",
            frame.caps,
            dims.0 * dims.1,
            frame.eta
        ),
        check: Some(Check {
            what: format!(
                "P0 texel by texel against the CPU's interval test (Aabb::overlaps, the test of \
                 Table I) of the CPU's slot boxes under the same stencil arrays: {} of {} \
                 texels differ (tolerance: none; both are exact min/max of the same floats)",
                wrong.len(),
                p0.len()
            ),
            passed: wrong.is_empty(),
        }),
    });

    // The hierarchical encoding: P1, P2, P3.
    collider
        .reduction
        .read(ctx, &collider.target, Scheme::Hierarchical)?;
    let mut pictures = Vec::new();
    for (i, level) in collider.reduction.level_textures().into_iter().enumerate() {
        let name = format!("P{}", i + 1);
        pictures.push(texture_png(
            dir,
            &format!("{name}.png"),
            &name,
            level,
            &["mask"],
        )?);
    }
    shots.push(Shot {
        pictures,
        key: "each texel's value is a 16-bit mask (0 to 65535) of the set texels in the 4x4 \
              block below it; grey 0 means the whole block is empty and is never read"
            .into(),
        check: None,
    });

    // The primitive test on the CPU: the frame as paper Fig. 1 draws it.
    crate::collide::snapshot::frame_png(&collider, &frame, (&x, &y), &dir.join("frame.png"))?;
    shots.push(Shot {
        pictures: vec!["frame.png".into()],
        key: format!(
            "model X blue, model Y cyan, the triangles in a colliding pair red, the boxes of \
             the CAPs orange (X) and yellow (Y): {} PCTPs tested, {} CTPs found",
            frame.pctps, frame.ctps
        ),
        check: None,
    });
    Ok(shots)
}

/// A float texture as a picture of the channels `names`.
fn texture_png(
    dir: &Path,
    file: &str,
    title: &str,
    texture: &Texture,
    names: &[&str],
) -> anyhow::Result<String> {
    let values = texture.download_f32()?;
    let dims = (texture.width(), texture.height());
    buffer_png(
        dir,
        file,
        title,
        &values,
        texture.format().components(),
        names,
        dims,
    )
}

/// The GPU's slot boxes of X and Y against the CPU's (the stream update's output).
fn boxes_check(collider: &StreamingCollider, x: &Mesh, y: &Mesh) -> anyhow::Result<Check> {
    let mut differ = 0;
    let mut total = 0;
    for (model_y, mesh) in [(false, x), (true, y)] {
        let stream = if model_y {
            &collider.y.stream
        } else {
            &collider.x.stream
        };
        let gpu = collider.gpu_slot_boxes(model_y)?;
        let cpu = stream.slot_boxes(&mesh.positions);
        total += cpu.len();
        differ += gpu.iter().zip(&cpu).filter(|(g, c)| g != c).count();
        differ += gpu.len().abs_diff(cpu.len());
    }
    Ok(Check {
        what: format!(
            "T_min/T_max of both models against the CPU's min/max of each leaf's vertices \
             (Eq. 1): {differ} of {total} slot boxes differ (tolerance: none)"
        ),
        passed: differ == 0,
    })
}

/// P0 as the CPU's AABB overlap test gives it for a one-tile collider: texel (j, i) (index
/// `i * width + j`) is 1 when slot i of X and slot j of Y both take part (their stencil arrays)
/// and their boxes (the CPU's, from the vertices) overlap.
pub fn cpu_p0(collider: &StreamingCollider, x: &Mesh, y: &Mesh) -> Vec<f32> {
    let (sx, sy) = (&collider.x.stream, &collider.y.stream);
    cpu_overlaps(
        &sx.slot_boxes(&x.positions),
        &sx.stencil,
        &sy.slot_boxes(&y.positions),
        &sy.stencil,
    )
}

/// The interval test of every pair of `rows` x `columns` boxes, masked by their stencil arrays:
/// 1 where both are marked and the boxes overlap, row by row.
pub fn cpu_overlaps(
    rows: &[Aabb],
    row_marks: &[u8],
    columns: &[Aabb],
    column_marks: &[u8],
) -> Vec<f32> {
    let mut out = Vec::with_capacity(rows.len() * columns.len());
    for (a, &ma) in rows.iter().zip(row_marks) {
        for (b, &mb) in columns.iter().zip(column_marks) {
            out.push(if ma != 0 && mb != 0 && a.overlaps(b) {
                1.0
            } else {
                0.0
            });
        }
    }
    out
}

/// The indices where two P0s differ (any difference: P0 holds exactly 0 or 1), all of them
/// when the sizes differ.
pub fn p0_differences(gpu: &[f32], cpu: &[f32]) -> Vec<usize> {
    if gpu.len() != cpu.len() {
        return (0..gpu.len().max(cpu.len())).collect();
    }
    (0..gpu.len()).filter(|&k| gpu[k] != cpu[k]).collect()
}
