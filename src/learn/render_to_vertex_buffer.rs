//! Lesson 9, render to vertex buffer: a fragment pass computes vertex positions into an
//! RGBA32F target; glReadPixels into a pixel pack buffer (PBO) copies them on the GPU; the
//! buffer, copied to a vertex buffer (VBO), feeds the draw of pass 2. Paper 2 skins its crowd
//! so (pass 1 -> pass 2, section 2). Then the same vertices by transform feedback, the later
//! way: a vertex shader's outputs captured into a buffer. Both checked against the CPU.

use super::kit;
use super::{Exercise, Grid, Lesson, LessonInfo, LessonOptions, LessonRun, PaperStep};
use crate::gl::{
    feedback, Barrier, Buffer, BufferUsage, ComputeProgram, Context, Framebuffer, Primitive,
    Program, Texture, TextureFormat, VertexArray,
};
use crate::shader;

/// Grid side: N x N vertices.
const N: u32 = 16;
/// GLSL leaves sin and cos accuracy to the implementation; Mesa's are within about 1e-6 of
/// the CPU's here, and heights are at most 0.25, so 1e-4 is a margin a wrong surface (off by
/// 1e-2 or more) cannot hide in. Grid x, y are exact in fp32.
const TOLERANCE: f64 = 1e-4;
const NOTHING: f32 = -1.0;

static INFO: LessonInfo = LessonInfo {
    id: "render-to-vertex-buffer",
    number: 9,
    title: "Render to vertex buffer: a fragment pass makes the vertices of the next draw",
    idea: "A render target holds four floats per texel, a vertex position holds four floats: \
           a fragment pass can compute vertices. Read the target into a pixel pack buffer and \
           the data is already in a GL buffer, which a draw can read as its vertex buffer: the \
           vertices never leave the GPU. Later GL added transform feedback, which captures a \
           vertex shader's outputs into a buffer directly.",
    paper_steps: &[
        PaperStep {
            paper: "Paper 2, section 2",
            step: "pass 1 skins one vertex per texel; the target goes through a PBO into the \
                   VBO of pass 2",
            file: "src/crowd/render_to_vbo.rs",
        },
        PaperStep {
            paper: "Paper 2, section 2 (pass 1)",
            step: "the skinning pass into the render target",
            file: "src/crowd/pass1_skinning.rs",
        },
    ],
    shaders: &[
        "glsl/learn/render-to-vertex-buffer/grid.frag",
        "glsl/learn/render-to-vertex-buffer/draw_points.vert",
        "glsl/learn/render-to-vertex-buffer/draw_points.frag",
        "glsl/learn/render-to-vertex-buffer/feedback.vert",
        "glsl/learn/render-to-vertex-buffer/positions.comp",
    ],
    exercises: &[Exercise {
        number: 1,
        task: "Compute the height of each vertex in pass 1: z = 0.25 sin(6u) cos(4v).",
        shader: "glsl/learn/render-to-vertex-buffer/grid.frag",
        hints: [
            "Each texel of the target is one vertex of the grid: the fragment shader \
             computes its position, and the buffer it lands in is drawn as vertices \
             next.",
            "The surface's height over the texel's grid coordinate uv (in [0, 1]) is \
             z = 0.25 sin(6 u) cos(4 v).",
            "float height = 0.25 * sin(6.0 * uv.x) * cos(4.0 * uv.y);",
        ],
    }],
};

pub struct RenderToVertexBuffer;

impl Lesson for RenderToVertexBuffer {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        kit::exercise_asked(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        let expected = cpu_positions();
        let expected_heights: Vec<f32> = expected.chunks_exact(4).map(|p| p[2]).collect();
        let count = (N * N) as usize;
        let bytes = count * 16;

        // Pass 1: one vertex per texel.
        let program = Program::rect(
            ctx,
            &[shader!("glsl/learn/render-to-vertex-buffer/grid.frag")],
        )?;
        // region: pass-1
        let positions = Texture::new_2d(ctx, N, N, TextureFormat::Rgba32F)?;
        let target = Framebuffer::new(ctx, "pass 1 positions", &[&positions], None)?;
        target
            .pass(&program, "pass 1")?
            .uniform("u_n", N as i32)
            .draw_full()?;
        // endregion
        let picture = Some(kit::buffer(&positions)?.named(&["x", "y", "z (height)", "w"]));
        run.pass(
            "pass 1",
            "glsl/learn/render-to-vertex-buffer/grid.frag",
            "one vertex per texel: x, y on the grid, z the height (RGBA32F)",
            picture,
        );

        // Target -> PBO -> VBO, all on the GPU.
        // region: pbo-to-vbo
        let pbo = Buffer::new(ctx, bytes, BufferUsage::GpuCopy)?;
        target.read_into_buffer(0, target.rect(), &pbo, 0)?;
        let vbo = Buffer::new(ctx, bytes, BufferUsage::GpuCopy)?;
        vbo.copy_from(&pbo, 0, 0, bytes)?;
        // endregion
        run.pass(
            "PBO -> VBO",
            "",
            "glReadPixels into a pixel pack buffer, then a buffer copy into the vertex buffer",
            None,
        );
        run.check_texels(
            "vertex buffer after PBO -> VBO vs CPU positions (sin, cos: 1e-4)",
            Grid::new(N, N, 4),
            &vbo.read::<f32>()?,
            &expected,
            TOLERANCE,
        );

        // Pass 2: draw the vertex buffer as points.
        let drawer = PointDrawer::new(ctx)?;
        let heights = drawer.draw(&vbo, count)?;
        let picture = Some(kit::buffer(&drawer.picture)?);
        run.pass(
            "pass 2",
            "glsl/learn/render-to-vertex-buffer/draw_points.vert",
            "the buffer drawn as points: each lands on its pixel and writes its height",
            picture,
        );
        run.shaders
            .push("glsl/learn/render-to-vertex-buffer/draw_points.frag".into());
        run.check(
            "pass 2's picture (points from the VBO) vs CPU heights (1e-4)",
            kit::max_abs_diff(&heights, &expected_heights),
            TOLERANCE,
        );

        // Transform feedback: the vertex shader's outputs captured.
        // region: transform-feedback
        let capture = Program::feedback(
            ctx,
            &[shader!("glsl/learn/render-to-vertex-buffer/feedback.vert")],
            &["v_position"],
        )?;
        capture.set("u_n", N as i32)?;
        let captured = Buffer::new(ctx, bytes, BufferUsage::GpuCopy)?;
        let written = feedback::capture_points(ctx, &capture, &captured, count)?;
        // endregion
        run.pass(
            "transform feedback",
            "glsl/learn/render-to-vertex-buffer/feedback.vert",
            "the vertex shader computes each vertex from gl_VertexID; the outputs are captured",
            None,
        );
        run.check(
            "transform feedback: vertices written vs N x N (exact)",
            (written as f64 - count as f64).abs(),
            0.0,
        );
        run.check(
            "transform feedback: captured positions vs CPU (1e-4)",
            kit::max_abs_diff(&captured.read::<f32>()?, &expected),
            TOLERANCE,
        );

        run.compute = Some(match kit::compute_missing(ctx, "the compute counterpart") {
            Some(why) => why,
            None => {
                let program = ComputeProgram::new(
                    ctx,
                    &[shader!("glsl/learn/render-to-vertex-buffer/positions.comp")],
                )?;
                // region: positions-compute
                let storage = Buffer::new(ctx, bytes, BufferUsage::GpuCopy)?;
                program
                    .dispatch("positions")
                    .storage(0, &storage)
                    .uniform("u_n", N as i32)
                    .run_over(count as u32)?;
                crate::gl::memory_barrier(ctx, &[Barrier::VertexAttrib, Barrier::BufferUpdate]);
                // endregion
                run.pass(
                    "compute positions",
                    "glsl/learn/render-to-vertex-buffer/positions.comp",
                    "the vertices written into a storage buffer, then drawn from it",
                    None,
                );
                run.check(
                    "compute: storage buffer positions vs CPU (1e-4)",
                    kit::max_abs_diff(&storage.read::<f32>()?, &expected),
                    TOLERANCE,
                );
                let heights = drawer.draw(&storage, count)?;
                run.check(
                    "compute: points drawn from the storage buffer vs CPU heights (1e-4)",
                    kit::max_abs_diff(&heights, &expected_heights),
                    TOLERANCE,
                );
                "ran: positions into a storage buffer, drawn as the vertex buffer".into()
            }
        });
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// The CPU's vertices, in pass 1's layout: row by row, xyzw.
fn cpu_positions() -> Vec<f32> {
    (0..N * N)
        .flat_map(|k| {
            let u = ((k % N) as f32 + 0.5) / N as f32;
            let v = ((k / N) as f32 + 0.5) / N as f32;
            let height = 0.25 * (6.0 * u).sin() * (4.0 * v).cos();
            [u * 2.0 - 1.0, v * 2.0 - 1.0, height, 1.0]
        })
        .collect()
}

/// Pass 2: points from a vertex buffer onto an N x N picture of their heights.
struct PointDrawer {
    program: Program,
    picture: Texture,
    target: Framebuffer,
}

impl PointDrawer {
    fn new(ctx: &Context) -> anyhow::Result<PointDrawer> {
        let picture = Texture::new_2d(ctx, N, N, TextureFormat::R32F)?;
        Ok(PointDrawer {
            program: Program::new(
                ctx,
                &[shader!(
                    "glsl/learn/render-to-vertex-buffer/draw_points.vert"
                )],
                &[shader!(
                    "glsl/learn/render-to-vertex-buffer/draw_points.frag"
                )],
            )?,
            target: Framebuffer::new(ctx, "pass 2 points", &[&picture], None)?,
            picture,
        })
    }

    /// Draw `count` xyzw vertices of `vertices`; the picture read back.
    fn draw(&self, vertices: &Buffer, count: usize) -> anyhow::Result<Vec<f32>> {
        // region: pass-2
        let mut array = VertexArray::new(self.target.context())?;
        array.float_attribute(0, vertices, 4, 16, 0, 0)?;
        self.target.clear_colors([NOTHING; 4])?;
        self.target.pass(&self.program, "pass 2")?.draw_arrays(
            &array,
            Primitive::Points,
            0,
            count,
        )?;
        Ok(self.target.read_f32(0, self.target.rect())?)
        // endregion
    }
}
