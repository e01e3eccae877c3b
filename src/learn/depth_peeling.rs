//! Lesson 7, depth peeling (Everitt 2001): the layers of a closed mesh, front to back, one
//! pass each. A peel keeps the fragments strictly behind the depth the previous peel left,
//! and the depth test keeps the nearest of them; an occlusion query says when a peel found
//! nothing. Every layer is compared with a CPU ray cast through the pixel centres, pixel by
//! pixel: a wrong peel is named by the pixels whose layer count differs. Paper 4
//! peels a body this way to integrate over its surface (section 3.2).

use super::kit;
use super::{Exercise, Grid, Lesson, LessonInfo, LessonOptions, LessonRun, PaperStep, PassBuffer};
use crate::gl::peel::ortho_box;
use crate::gl::{
    Buffer, BufferUsage, Compare, ComputeProgram, Context, DepthTest, DrawState, Framebuffer,
    MeshBuffers, OcclusionQuery, Program, Texture, TextureFormat,
};
use crate::mesh::Mesh;
use crate::shader;
use glam::{Mat3, Vec3};

const SIZE: u32 = 48;
/// A peel that goes on past this many layers is stopped (an unfilled exercise never ends).
const MAX_LAYERS: usize = 12;
/// What a layer's picture holds where the layer has no fragment.
const EMPTY: f32 = 2.0;
/// A pixel whose centre lies this close to a triangle's edge (in barycentric terms) is left
/// out of the per-pixel comparison: the rasterizer's tie rule, not the peel, decides there.
const EDGE: f64 = 1e-4;
/// fp32 depth interpolated across a triangle: values in [0, 1] off by a few ulp (1e-7);
/// layers of this mesh lie more than 1e-2 apart, so 1e-5 separates right from wrong.
const DEPTH_TOLERANCE: f64 = 1e-5;

static INFO: LessonInfo = LessonInfo {
    id: "depth-peeling",
    number: 7,
    title: "Depth peeling: every layer of a closed mesh",
    idea: "The depth test keeps only the nearest fragment of each pixel. To see what lies \
           behind it, draw again and discard every fragment at or in front of the depth the \
           last pass kept: the depth test now keeps the second nearest, and so on. Each pass \
           peels one layer; an occlusion query that counts zero fragments says the last layer \
           was found. A closed mesh has an even number of layers at every pixel.",
    paper_steps: &[
        PaperStep {
            paper: "Paper 4, section 3.2",
            step: "depth peeling finds every layer of the body's surface, one pass each",
            file: "src/mass/peel.rs",
        },
        PaperStep {
            paper: "Paper 4, section 3.2 (the GL layer)",
            step: "the peel loop with its two depth textures and its occlusion query",
            file: "src/gl/peel.rs",
        },
    ],
    shaders: &[
        "glsl/learn/depth-peeling/mesh.vert",
        "glsl/learn/depth-peeling/peel.frag",
        "glsl/learn/depth-peeling/ray_cast.comp",
    ],
    exercises: &[Exercise {
        number: 1,
        task: "Peel: from layer 1 on, discard each fragment at or in front of the depth the \
               previous layer left at its pixel.",
        shader: "glsl/learn/depth-peeling/peel.frag",
        hints: [
            "Layer k + 1 is what lies behind layer k: from layer 1 on, a fragment at \
             or in front of the depth the previous layer left at its pixel has been \
             taken already.",
            "Discard when u_layer > 0 and gl_FragCoord.z <= previous; with < instead \
             of <= the layer just found comes back.",
            "if (u_layer > 0 && gl_FragCoord.z <= previous) { discard; }",
        ],
    }],
};

pub struct DepthPeeling;

impl Lesson for DepthPeeling {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        kit::exercise_asked(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        let view = View::new(lesson_mesh());
        let reference = view.ray_cast();

        let layers = peel(ctx, &view)?;
        let cpu_layers = reference.hits.iter().copied().max().unwrap_or(0) as usize;
        run.notes.push((
            "mesh".into(),
            format!(
                "a tilted torus, {} triangles, seen from above at {SIZE}x{SIZE}",
                view.mesh.triangles.len()
            ),
        ));
        run.notes.push((
            "layers peeled (the query found none after)".into(),
            layers.len().to_string(),
        ));
        for (k, layer) in layers.iter().enumerate() {
            let picture = Some(PassBuffer::floats(SIZE, SIZE, 1, layer.to_vec()).in_set("layers"));
            run.pass(
                &format!("peel {k}"),
                "glsl/learn/depth-peeling/peel.frag",
                if k == 0 {
                    "the nearest layer: the plain depth test"
                } else {
                    "the fragments behind the last layer's depth; the nearest of them kept"
                },
                picture,
            );
        }
        run.check(
            "layers peeled vs the most hits of a CPU ray (exact)",
            (layers.len() as f64 - cpu_layers as f64).abs(),
            0.0,
        );
        let peeled =
            reference.compare(|pixel, k| layers.get(k).map(|l| l[pixel]).filter(|&d| d < 1.5));
        run.pass(
            "layers per pixel",
            "",
            "how many peels drew at each pixel (the viewer's probe shows the CPU ray's hits \
             beside it)",
            Some(
                PassBuffer::floats(SIZE, SIZE, 1, peeled.gpu_counts.clone())
                    .with_reference(reference.hit_counts()),
            ),
        );
        run.check_texels(
            "pixels whose layer count differs from the ray's hits (exact; edge pixels left out)",
            Grid::new(SIZE, SIZE, 1).of("pixel"),
            &peeled.gpu_counts,
            &peeled.cpu_counts,
            0.0,
        );
        run.check(
            "each layer's depth vs the ray's k-th hit (fp32 depth: 1e-5)",
            peeled.depth_error,
            DEPTH_TOLERANCE,
        );
        run.notes.push((
            "pixels left out (centre on a triangle edge)".into(),
            reference
                .ambiguous
                .iter()
                .filter(|&&a| a)
                .count()
                .to_string(),
        ));

        run.compute = Some(match kit::compute_missing(ctx, "the compute ray cast") {
            Some(why) => why,
            None => {
                let (counts, depths) = ray_cast_compute(ctx, &view)?;
                run.pass(
                    "compute ray cast",
                    "glsl/learn/depth-peeling/ray_cast.comp",
                    "one invocation per pixel: every triangle, the hit depths sorted",
                    None,
                );
                let cast = reference.compare(|pixel, k| {
                    (k < RAY_LAYERS && counts[pixel] as usize > k)
                        .then(|| depths[pixel * RAY_LAYERS + k])
                });
                run.check_texels(
                    "compute: pixels whose hit count differs from the CPU's (exact)",
                    Grid::new(SIZE, SIZE, 1).of("pixel"),
                    &cast.gpu_counts,
                    &cast.cpu_counts,
                    0.0,
                );
                run.check(
                    "compute: k-th hit depth vs the CPU's (1e-5)",
                    cast.depth_error,
                    DEPTH_TOLERANCE,
                );
                "ran: every layer in one pass, one ray per pixel".into()
            }
        });
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// The depths the compute ray cast keeps per pixel (as in `ray_cast.comp`).
const RAY_LAYERS: usize = 8;

/// A torus tilted so that a vertical ray meets up to four layers.
fn lesson_mesh() -> Mesh {
    let torus = crate::mesh::generate::torus_closed(1.0, 0.35, 20, 10);
    let tilt = Mat3::from_rotation_x(0.9) * Mat3::from_rotation_z(0.3);
    Mesh::new(
        torus.positions.iter().map(|&p| tilt * p).collect(),
        torus.triangles,
    )
}

/// The mesh and the box it is seen through.
struct View {
    mesh: Mesh,
    min: Vec3,
    max: Vec3,
}

impl View {
    fn new(mesh: Mesh) -> View {
        let b = mesh.bounds();
        let margin = b.size() * 0.05;
        View {
            mesh,
            min: b.min - margin,
            max: b.max + margin,
        }
    }

    /// A position in window coordinates: x, y in pixels, z the depth in [0, 1] (top 0).
    fn window(&self, p: Vec3) -> [f64; 3] {
        let (p, min, max) = (p.as_dvec3(), self.min.as_dvec3(), self.max.as_dvec3());
        [
            (p.x - min.x) / (max.x - min.x) * SIZE as f64,
            (p.y - min.y) / (max.y - min.y) * SIZE as f64,
            (max.z - p.z) / (max.z - min.z),
        ]
    }

    /// The CPU reference: a ray through every pixel centre, straight down.
    fn ray_cast(&self) -> RayCast {
        let n = (SIZE * SIZE) as usize;
        let mut depths = vec![Vec::new(); n];
        let mut ambiguous = vec![false; n];
        let corners: Vec<[[f64; 3]; 3]> = (0..self.mesh.triangles.len())
            .map(|t| self.mesh.triangle(t).map(|p| self.window(p)))
            .collect();
        for (pixel, (hits, edge)) in depths.iter_mut().zip(&mut ambiguous).enumerate() {
            let px = (pixel % SIZE as usize) as f64 + 0.5;
            let py = (pixel / SIZE as usize) as f64 + 0.5;
            for [a, b, c] in &corners {
                let area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
                if area == 0.0 {
                    continue;
                }
                let wa = ((b[0] - px) * (c[1] - py) - (c[0] - px) * (b[1] - py)) / area;
                let wb = ((c[0] - px) * (a[1] - py) - (a[0] - px) * (c[1] - py)) / area;
                let wc = 1.0 - wa - wb;
                let nearest = wa.min(wb).min(wc);
                if nearest.abs() < EDGE {
                    *edge = true;
                }
                if nearest >= 0.0 {
                    hits.push(wa * a[2] + wb * b[2] + wc * c[2]);
                }
            }
            hits.sort_by(f64::total_cmp);
        }
        RayCast {
            hits: depths.iter().map(|d| d.len() as u32).collect(),
            depths,
            ambiguous,
        }
    }
}

/// Each pixel's hit depths, sorted, and whether its centre lies on an edge.
struct RayCast {
    hits: Vec<u32>,
    depths: Vec<Vec<f64>>,
    ambiguous: Vec<bool>,
}

/// A GPU answer beside the ray cast, pixel by pixel.
struct Compared {
    /// How many layers the GPU found at each pixel, rows from the bottom.
    gpu_counts: Vec<f32>,
    /// The ray's hits at each pixel; at an edge pixel the GPU's count, so that it is left out.
    cpu_counts: Vec<f32>,
    /// The largest depth error over the pixels whose counts agree.
    depth_error: f64,
}

impl RayCast {
    /// The ray's hits at each pixel, rows from the bottom.
    fn hit_counts(&self) -> Vec<f32> {
        self.hits.iter().map(|&h| h as f32).collect()
    }

    /// Compare a GPU answer, `layer(pixel, k)` the k-th depth or `None`, pixel by pixel: its
    /// layer counts beside the ray's (edge pixels left out), and the largest depth error.
    fn compare(&self, layer: impl Fn(usize, usize) -> Option<f32>) -> Compared {
        let mut out = Compared {
            gpu_counts: Vec::with_capacity(self.depths.len()),
            cpu_counts: Vec::with_capacity(self.depths.len()),
            depth_error: 0.0,
        };
        for (pixel, depths) in self.depths.iter().enumerate() {
            let gpu: Vec<f32> = (0..MAX_LAYERS).map_while(|k| layer(pixel, k)).collect();
            out.gpu_counts.push(gpu.len() as f32);
            if self.ambiguous[pixel] {
                out.cpu_counts.push(gpu.len() as f32);
                continue;
            }
            out.cpu_counts.push(depths.len() as f32);
            if gpu.len() != depths.len() {
                continue;
            }
            for (&g, &c) in gpu.iter().zip(depths) {
                let d = (g as f64 - c).abs();
                out.depth_error = if d.is_finite() {
                    out.depth_error.max(d)
                } else {
                    f64::INFINITY
                };
            }
        }
        out
    }
}

/// Peel until a layer draws nothing (or [`MAX_LAYERS`]): each layer's depth picture, rows
/// from the bottom, [`EMPTY`] where it has no fragment.
fn peel(ctx: &Context, view: &View) -> anyhow::Result<Vec<Vec<f32>>> {
    let program = Program::new(
        ctx,
        &[shader!("glsl/learn/depth-peeling/mesh.vert")],
        &[shader!("glsl/learn/depth-peeling/peel.frag")],
    )?;
    let mesh = MeshBuffers::new(ctx, view.mesh.positions_f32(), &view.mesh.triangles)?;
    let picture = Texture::new_2d(ctx, SIZE, SIZE, TextureFormat::R32F)?;
    // region: peel-targets
    let depth = [
        Texture::new_2d(ctx, SIZE, SIZE, TextureFormat::Depth32F)?,
        Texture::new_2d(ctx, SIZE, SIZE, TextureFormat::Depth32F)?,
    ];
    // Two targets sharing the picture: layer k writes depth[k % 2] and reads the other.
    let targets = [
        Framebuffer::new(ctx, "peel (even layers)", &[&picture], Some(&depth[0]))?,
        Framebuffer::new(ctx, "peel (odd layers)", &[&picture], Some(&depth[1]))?,
    ];
    let query = OcclusionQuery::new(ctx)?;
    // endregion
    let mvp = ortho_box(view.min, view.max);
    let mut layers = Vec::new();
    // region: peel-pass
    for k in 0..MAX_LAYERS {
        let target = &targets[k % 2];
        target.clear_colors([EMPTY; 4])?;
        target.clear_depth_stencil(1.0, 0)?;
        let mut pass = target.pass(&program, "peel")?;
        pass.state(DrawState {
            depth: Some(DepthTest {
                func: Compare::Less,
                write: true,
            }),
            ..DrawState::default()
        })
        .texture("u_previous_depth", &depth[(k + 1) % 2])
        .uniform("u_layer", k as i32)
        .uniform("u_mvp", mvp);
        query.begin();
        let drawn = pass.draw_mesh(&mesh);
        query.end();
        drawn?;
        if query.samples()? == 0 {
            break;
        }
        layers.push(target.read_f32(0, target.rect())?);
        // endregion
    }
    Ok(layers)
}

/// The compute counterpart: hits per pixel, and [`RAY_LAYERS`] sorted depths per pixel.
fn ray_cast_compute(ctx: &Context, view: &View) -> anyhow::Result<(Vec<u32>, Vec<f32>)> {
    let program = ComputeProgram::new(ctx, &[shader!("glsl/learn/depth-peeling/ray_cast.comp")])?;
    let corners: Vec<[f32; 4]> = (0..view.mesh.triangles.len())
        .flat_map(|t| view.mesh.triangle(t))
        .map(|p| {
            let [x, y, z] = view.window(p);
            [x as f32, y as f32, z as f32, 1.0]
        })
        .collect();
    let n = (SIZE * SIZE) as usize;
    // region: ray-cast
    let corners = Buffer::from_slice(ctx, &corners, BufferUsage::Static)?;
    let layers = Buffer::new(ctx, n * RAY_LAYERS * 4, BufferUsage::GpuCopy)?;
    let counts = Buffer::new(ctx, n * 4, BufferUsage::GpuCopy)?;
    program
        .dispatch("ray cast")
        .storage(0, &corners)
        .storage(1, &layers)
        .storage(2, &counts)
        .uniform("u_triangles", view.mesh.triangles.len() as u32)
        .uniform("u_size", glam::IVec2::splat(SIZE as i32))
        .run([SIZE.div_ceil(8), SIZE.div_ceil(8), 1])?;
    // endregion
    crate::gl::memory_barrier(ctx, &[crate::gl::Barrier::BufferUpdate]);
    Ok((counts.read()?, layers.read()?))
}
