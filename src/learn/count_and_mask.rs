//! Lesson 6, counting and masking: an occlusion query counts the fragments that survive a
//! pass (a `discard` is a "no"), the depth test removes an `if` from a shader (a cheap pass
//! writes the condition as depth, the work pass is rejected by the test where it fails), and
//! the stencil test selects the pixels a pass runs on. Paper 1 counts its colliding pairs with
//! a query and masks the virtual pairs with the stencil (section 5.2); lecture 3 removes
//! `if`s with the depth buffer.

use super::kit;
use super::{Exercise, Grid, Lesson, LessonInfo, LessonOptions, LessonRun, PaperStep, PassBuffer};
use crate::gl::{
    AtomicCounters, Buffer, BufferUsage, Compare, ComputeProgram, Context, DepthTest, DrawState,
    Framebuffer, OcclusionQuery, Program, StencilTest, Texture, TextureFormat,
};
use crate::shader;

/// The lesson's array: `SIDE x SIDE` slots, of which the first `REAL_W x REAL_H` hold data
/// and the rest is padding (the virtual slots of a power-of-two stream).
const SIDE: u32 = 64;
const REAL_W: u32 = 50;
const REAL_H: u32 = 41;
const THRESHOLD: f32 = 0.6;
/// What the work pass's target holds where the work did not run.
const UNTOUCHED: f32 = -1.0;

static INFO: LessonInfo = LessonInfo {
    id: "count-and-mask",
    number: 6,
    title: "Counting with an occlusion query; conditions with the depth and stencil buffers",
    idea: "A fragment that is discarded, or rejected by the depth or stencil test, is not \
           drawn, and an occlusion query counts the ones that were. So a pass can count (how \
           many values are above a threshold: one query, one number read back), and a \
           condition can be taken out of the shader: a cheap pass writes it into the depth or \
           stencil buffer, and the expensive pass, with no `if`, is rejected by the test where \
           the condition fails, before its shader runs.",
    paper_steps: &[
        PaperStep {
            paper: "Paper 1, section 5.2",
            step: "the stencil mask keeps the overlap test off the virtual pairs; an occlusion \
                   query counts the colliding pairs",
            file: "src/collide/streaming_test.rs",
        },
        PaperStep {
            paper: "Lecture 3, debugging and coding tips",
            step: "remove an if with the depth buffer",
            file: "src/lecture3/depth_mask.rs",
        },
    ],
    shaders: &[
        "glsl/learn/count-and-mask/count_above.frag",
        "glsl/learn/count-and-mask/mask_depth.frag",
        "glsl/learn/count-and-mask/stencil_mark.frag",
        "glsl/learn/count-and-mask/work.frag",
        "glsl/learn/count-and-mask/count_and_mask.comp",
    ],
    exercises: &[Exercise {
        number: 1,
        task: "Write the condition into the depth buffer: 1.0 (open) where the value is above \
               the threshold, 0.0 (closed) elsewhere.",
        shader: "glsl/learn/count-and-mask/mask_depth.frag",
        hints: [
            "The mask pass writes a depth per pixel that the work pass (drawn at \
             depth 0.5 with the test LESS) is compared with: it runs only where the \
             stored depth is greater than 0.5.",
            "Open (depth 1.0) where value > u_threshold, closed (depth 0.0) where it \
             is not.",
            "gl_FragDepth = value > u_threshold ? 1.0 : 0.0;",
        ],
    }],
};

pub struct CountAndMask;

impl Lesson for CountAndMask {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        kit::exercise_asked(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        let data = Data::new();
        let n = (SIDE * SIDE) as usize;
        let values = Texture::from_f32(ctx, SIDE, SIDE, TextureFormat::R32F, &data.values)?;
        let valid = Texture::from_f32(ctx, SIDE, SIDE, TextureFormat::R32F, &data.valid)?;
        let picture = Some(kit::buffer(&values)?);
        run.pass(
            "upload",
            "",
            "the CPU's values, one float per texel",
            picture,
        );

        // Counting: discard what is not counted, one query around the pass.
        let count_program = Program::rect(
            ctx,
            &[shader!("glsl/learn/count-and-mask/count_above.frag")],
        )?;
        // region: count-pass
        let counted = Texture::new_2d(ctx, SIDE, SIDE, TextureFormat::R32F)?;
        let count_target = Framebuffer::new(ctx, "count", &[&counted], None)?;
        count_target.clear_colors([0.0; 4])?;
        let query = OcclusionQuery::new(ctx)?;
        query.begin();
        count_target
            .pass(&count_program, "count above the threshold")?
            .texture("u_values", &values)
            .uniform("u_threshold", THRESHOLD)
            .draw_full()?;
        query.end();
        let gpu_count = query.samples()?;
        // endregion
        let picture = Some(kit::buffer(&counted)?);
        run.pass(
            "count",
            "glsl/learn/count-and-mask/count_above.frag",
            "discards the values at or below the threshold; the occlusion query counts the rest",
            picture,
        );
        run.notes.push((
            "values above the threshold (query)".into(),
            gpu_count.to_string(),
        ));
        run.check(
            "occlusion-query count of values above the threshold (exact: an integer)",
            (gpu_count as f64 - data.above as f64).abs(),
            0.0,
        );

        // The same work pass, first masked by depth alone, then by depth and stencil.
        let masks = Masks::new(ctx, &values, &valid)?;
        masks.write_depth()?;
        let picture = Some(kit::buffer(&masks.depth)?);
        run.pass(
            "depth mask",
            "glsl/learn/count-and-mask/mask_depth.frag",
            "writes 1.0 (open) where the value is above the threshold, 0.0 elsewhere",
            picture,
        );
        let (result, ran) = masks.work(false)?;
        let picture = Some(kit::buffer(&masks.result)?);
        run.pass(
            "work (depth test)",
            "glsl/learn/count-and-mask/work.frag",
            "the square root with no if, drawn at depth 0.5 with LESS: runs where the mask is open",
            picture,
        );
        run.check_texels(
            "work behind the depth mask vs the CPU's if (fp32 sqrt, correctly rounded: 1e-6)",
            Grid::new(SIDE, SIDE, 1),
            &result,
            &data.expected(false),
            1e-6,
        );
        run.check(
            "pixels the work ran on (query) vs values above the threshold (exact)",
            (ran as f64 - data.above as f64).abs(),
            0.0,
        );

        masks.write_stencil()?;
        let (result, ran) = masks.work(true)?;
        let stencil: Vec<f32> = masks
            .target
            .read_stencil(masks.target.rect())?
            .into_iter()
            .map(f32::from)
            .collect();
        let picture = Some(PassBuffer::floats(SIDE, SIDE, 1, stencil.clone()));
        run.pass(
            "stencil mark",
            "glsl/learn/count-and-mask/stencil_mark.frag",
            "no colour: writes stencil 1 on the real slots, leaves 0 on the padding",
            picture,
        );
        let picture = Some(kit::buffer(&masks.result)?);
        run.pass(
            "work (depth and stencil tests)",
            "glsl/learn/count-and-mask/work.frag",
            "the same pass, now also where the stencil equals 1: real slots above the threshold",
            picture,
        );
        run.check_texels(
            "work behind the depth and stencil masks vs the CPU (1e-6, as above)",
            Grid::new(SIDE, SIDE, 1),
            &result,
            &data.expected(true),
            1e-6,
        );
        run.check(
            "pixels the masked work ran on (query) vs the CPU's count (exact)",
            (ran as f64 - data.both as f64).abs(),
            0.0,
        );

        run.compute = Some(match kit::compute_missing(ctx, "the compute counterpart") {
            Some(why) => why,
            None => {
                let (result, above, ran) = compute(ctx, &data, n)?;
                run.pass(
                    "compute",
                    "glsl/learn/count-and-mask/count_and_mask.comp",
                    "one invocation per element: the condition an if, both counts atomic",
                    None,
                );
                run.check(
                    "compute: atomic count above the threshold (exact)",
                    (above as f64 - data.above as f64).abs(),
                    0.0,
                );
                run.check(
                    "compute: the work under an if, both conditions (1e-6)",
                    kit::max_abs_diff(&result, &data.expected(true)),
                    1e-6,
                );
                run.check(
                    "compute: elements the work ran on (exact)",
                    (ran as f64 - data.both as f64).abs(),
                    0.0,
                );
                "ran: one invocation per element, the condition an if, the counts atomic \
                 counters"
                    .into()
            }
        });
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// The CPU side: the values, which slots are real, and the counts.
struct Data {
    values: Vec<f32>,
    valid: Vec<f32>,
    above: usize,
    both: usize,
}

impl Data {
    fn new() -> Data {
        let values = kit::values((SIDE * SIDE) as usize, 6);
        let valid: Vec<f32> = (0..SIDE * SIDE)
            .map(|i| ((i % SIDE) < REAL_W && (i / SIDE) < REAL_H) as u32 as f32)
            .collect();
        let above = values.iter().filter(|&&v| v > THRESHOLD).count();
        let both = values
            .iter()
            .zip(&valid)
            .filter(|(&v, &ok)| v > THRESHOLD && ok > 0.5)
            .count();
        Data {
            values,
            valid,
            above,
            both,
        }
    }

    /// The CPU's work with its `if`: sqrt where it runs, [`UNTOUCHED`] elsewhere.
    fn expected(&self, stencil: bool) -> Vec<f32> {
        self.values
            .iter()
            .zip(&self.valid)
            .map(|(&v, &ok)| {
                let runs = v > THRESHOLD && (!stencil || ok > 0.5);
                if runs {
                    v.sqrt()
                } else {
                    UNTOUCHED
                }
            })
            .collect()
    }
}

/// The work target with its depth-stencil buffer, and the three programs drawing into it.
struct Masks<'a> {
    values: &'a Texture,
    valid: &'a Texture,
    result: Texture,
    depth: Texture,
    target: Framebuffer,
    mask_depth: Program,
    mark: Program,
    work: Program,
}

impl<'a> Masks<'a> {
    fn new(ctx: &Context, values: &'a Texture, valid: &'a Texture) -> anyhow::Result<Masks<'a>> {
        let result = Texture::new_2d(ctx, SIDE, SIDE, TextureFormat::R32F)?;
        let depth = Texture::new_2d(ctx, SIDE, SIDE, TextureFormat::Depth24Stencil8)?;
        let target = Framebuffer::new(ctx, "masked work", &[&result], Some(&depth))?;
        Ok(Masks {
            values,
            valid,
            mask_depth: Program::rect(
                ctx,
                &[shader!("glsl/learn/count-and-mask/mask_depth.frag")],
            )?,
            mark: Program::rect(
                ctx,
                &[shader!("glsl/learn/count-and-mask/stencil_mark.frag")],
            )?,
            work: Program::rect(ctx, &[shader!("glsl/learn/count-and-mask/work.frag")])?,
            result,
            depth,
            target,
        })
    }

    /// The depth pass: always passes, writes the condition as depth, no colour.
    fn write_depth(&self) -> anyhow::Result<()> {
        // region: depth-pass
        self.target.clear_depth_stencil(1.0, 0)?;
        self.target
            .pass(&self.mask_depth, "depth mask")?
            .state(DrawState {
                depth: Some(DepthTest {
                    func: Compare::Always,
                    write: true,
                }),
                color_write: false,
                ..DrawState::default()
            })
            .texture("u_values", self.values)
            .uniform("u_threshold", THRESHOLD)
            .draw_full()?;
        // endregion
        Ok(())
    }

    /// The stencil pass: 1 where the slot is real; depth kept as the depth pass left it.
    fn write_stencil(&self) -> anyhow::Result<()> {
        // region: stencil-pass
        self.target
            .pass(&self.mark, "stencil mark")?
            .state(DrawState {
                stencil: Some(StencilTest::write(1)),
                color_write: false,
                ..DrawState::default()
            })
            .texture("u_valid", self.valid)
            .draw_full()?;
        // endregion
        Ok(())
    }

    /// The work pass at depth 0.5 with LESS (and stencil == 1 when `stencil`), counted by a
    /// query: the result read back and how many pixels it ran on.
    fn work(&self, stencil: bool) -> anyhow::Result<(Vec<f32>, u64)> {
        // region: work-pass
        self.target.clear_color(0, [UNTOUCHED; 4])?;
        let query = OcclusionQuery::new(self.target.context())?;
        let mut pass = self.target.pass(&self.work, "work")?;
        pass.state(DrawState {
            depth: Some(DepthTest {
                func: Compare::Less,
                write: false,
            }),
            stencil: stencil.then(|| StencilTest::equal(1)),
            ..DrawState::default()
        })
        .texture("u_values", self.values);
        query.begin();
        let drawn = pass.draw_full();
        query.end();
        drawn?;
        let result = self.target.read_f32(0, self.target.rect())?;
        // endregion
        Ok((result, query.samples()?))
    }
}

/// The compute counterpart: results, the count above the threshold, the count that ran.
fn compute(ctx: &Context, data: &Data, n: usize) -> anyhow::Result<(Vec<f32>, u32, u32)> {
    let program = ComputeProgram::new(
        ctx,
        &[shader!("glsl/learn/count-and-mask/count_and_mask.comp")],
    )?;
    // region: count-and-mask-compute
    let values = Buffer::from_slice(ctx, &data.values, BufferUsage::Static)?;
    let valid = Buffer::from_slice(ctx, &data.valid, BufferUsage::Static)?;
    let result = Buffer::new(ctx, n * 4, BufferUsage::GpuCopy)?;
    let counters = AtomicCounters::new(ctx, 2)?;
    counters.reset()?;
    program
        .dispatch("count and mask")
        .storage(0, &values)
        .storage(1, &valid)
        .storage(2, &result)
        .counters(0, counters.buffer())
        .uniform("u_count", n as u32)
        .uniform("u_threshold", THRESHOLD)
        .run_over(n as u32)?;
    // endregion
    crate::gl::memory_barrier(
        ctx,
        &[
            crate::gl::Barrier::BufferUpdate,
            crate::gl::Barrier::AtomicCounter,
        ],
    );
    let counts = counters.read()?;
    Ok((result.read::<f32>()?, counts[0], counts[1]))
}
