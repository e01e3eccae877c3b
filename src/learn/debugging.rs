//! Lesson 11, debugging: the classic faults of GPGPU code made on purpose, each found with the
//! project's own tools and then fixed (the tutorial's "development tips"; LearnOpenGL's
//! debugging chapter, on GPGPU's faults). For each fault the run records the symptom, the tool
//! that found it and the fix as a note, a check that the tool did find it, and a check of the
//! fixed program against the CPU:
//!
//! 1. sampling off texel centres: the texel-by-texel comparison names the wrong texels;
//! 2. a format that clamps (RGBA8 for floats): the same comparison, and the `.npy` of `--png`;
//! 3. reading the texture being drawn (a feedback loop): the GL layer's check
//!    [`crate::gl::Pass::feedback_loops`], before anything is drawn;
//! 4. a NaN spreading through a reduction: the non-finite texels of each level (magenta in the
//!    pictures) and [`crate::gl::ensure_finite`], which refuses the result;
//! 5. an incomplete framebuffer: the GL layer refuses it, naming it and the attachment;
//! 6. a shader that does not compile: the error names the file and the line;
//! 7. a varying whose name does not match: the link error names the varying.
//!
//! The lesson's exercise is a hunt ([`super::host::hunt`]): `examples/debug-hunt.rs` plants
//! four faults in host code (two of the above among them, with a time taken before the GPU
//! finished and a uniform set with no program in use) for the learner to find and fix.

use super::feedback::wrong_texels;
use super::ping_pong::{initial_grid, jacobi_cpu};
use super::{Grid, Lesson, LessonInfo, LessonOptions, LessonRun, PaperStep, PassBuffer};
use crate::gl::{
    ensure_finite, Context, Filter, Framebuffer, GlError, Program, ShaderSource, Texture,
    TextureFormat,
};
use crate::shader;

const SAMPLE: &str = "glsl/learn/texel_sample.frag";
const COPY: &str = "glsl/learn/texture_copy.frag";
const JACOBI: &str = "glsl/learn/jacobi.frag";
const REDUCE: &str = "glsl/learn/reduce_2x2.frag";
const UV: &str = "glsl/learn/debugging/uv_ramp.frag";

/// The sampled row's texels, the copied array's side, the Jacobi grid's side.
const ROW: u32 = 8;
const SIDE: u32 = 8;
const GRID: u32 = 16;

pub struct Debugging;

static INFO: LessonInfo = LessonInfo {
    id: "debugging",
    number: 11,
    title: "Debugging: faults made on purpose",
    idea: "GPGPU code fails quietly: a wrong texel is just another number. So each classic \
           fault is made here on purpose and found with the project's tools: the texel-by-texel \
           comparison with the CPU (which names the texel, the GPU's value and the CPU's), the \
           pictures and .npy files of --png, the GL layer's checks (feedback loops, framebuffer \
           completeness, finite results), and compile and link errors that name the file, the \
           line and the varying. Then each is fixed, and the fixed run checked against the CPU.",
    paper_steps: &[
        PaperStep {
            paper: "The tutorial's programme, development tips",
            step: "look at the intermediate buffers: every pass as a picture and an array",
            file: "src/gl/dump.rs",
        },
        PaperStep {
            paper: "All four papers",
            step: "every result read back is checked finite before it is reported",
            file: "src/gl/finite.rs",
        },
    ],
    shaders: &[SAMPLE, COPY, JACOBI, REDUCE, UV],
    exercises: &[],
};

impl Lesson for Debugging {
    fn info(&self) -> &'static LessonInfo {
        &INFO
    }

    fn run(&self, ctx: &Context, opts: &LessonOptions) -> anyhow::Result<LessonRun> {
        super::chosen_exercise(&INFO, opts)?;
        let mut run = LessonRun::new(&INFO, ctx);
        off_centre(ctx, &mut run)?;
        clamping_format(ctx, &mut run)?;
        feedback_loop(ctx, &mut run)?;
        nan_in_reduction(ctx, &mut run)?;
        incomplete_framebuffer(ctx, &mut run)?;
        broken_shader(ctx, &mut run)?;
        varying_mismatch(ctx, &mut run)?;
        run.finish(&INFO, ctx, opts)?;
        Ok(run)
    }
}

/// One fault's record: a check that `tool` found it (`evidence` says how; `None`: missed),
/// and a note with the symptom, the tool's words and the fix.
fn found(
    run: &mut LessonRun,
    (k, fault): (u32, &str),
    tool: &str,
    evidence: Option<String>,
    (symptom, fix): (&str, &str),
) {
    run.check(
        &format!("fault {k}, {fault}: found by {tool} (faults missed)"),
        if evidence.is_some() { 0.0 } else { 1.0 },
        0.0,
    );
    let evidence = evidence.unwrap_or_else(|| "it did not find it on this renderer".into());
    run.note(
        &format!("fault {k}: {fault}"),
        format!("symptom: {symptom}. Found by {tool}: {evidence}. Fix: {fix}."),
    );
}

/// What the texel-by-texel comparison says of a faulty buffer, or `None` when it finds
/// nothing wrong.
fn compared(grid: Grid, gpu: &[f32], cpu: &[f32], tolerance: f64) -> Option<String> {
    let (count, first) = wrong_texels(grid, gpu, cpu, tolerance);
    let w = first.first()?;
    Some(format!(
        "{count} of {} values wrong, the first texel ({}, {}) channel {}: the GPU wrote {}, \
         the CPU expects {}",
        gpu.len(),
        w.x,
        w.y,
        w.channel,
        w.gpu,
        w.cpu
    ))
}

/// Fault 1: a row sampled with linear filtering at i / N (the texel's edge) instead of its
/// centre (i + 0.5) / N.
fn off_centre(ctx: &Context, run: &mut LessonRun) -> anyhow::Result<()> {
    let row: Vec<f32> = (0..ROW).map(|i| (i * i) as f32).collect();
    let input = Texture::from_f32(ctx, ROW, 1, TextureFormat::R32F, &row)?;
    input.set_filter(Filter::Linear);
    let program = Program::rect(ctx, &[shader!("glsl/learn/texel_sample.frag")])?;
    // region: sample-off-centre
    let sample = |offset: f32| -> anyhow::Result<Vec<f32>> {
        let target = Texture::new_2d(ctx, ROW, 1, TextureFormat::R32F)?;
        let fb = Framebuffer::new(ctx, "sampled row", &[&target], None)?;
        fb.pass(&program, "sample")?
            .texture("u_input", &input)
            .uniform("u_size", glam::Vec2::new(ROW as f32, 1.0))
            .uniform("u_offset", offset)
            .draw_full()?;
        Ok(target.download_f32()?)
    };
    // endregion
    let grid = Grid::new(ROW, 1, 1);
    // As in lesson 0: weights 0 and 1/2 are exact, fp32's rounding of the mean is all.
    let tolerance = 1e-6 * (ROW * ROW) as f64;
    let faulty = sample(0.0)?;
    run.pass(
        "fault 1: sampled at i / N",
        SAMPLE,
        "a row holding i*i sampled with GL_LINEAR at each texel's left edge",
        Some(PassBuffer::floats(ROW, 1, 1, faulty.clone()).with_reference(row.clone())),
    );
    found(
        run,
        (1, "sampling off texel centres"),
        "the texel-by-texel comparison with the CPU",
        compared(grid, &faulty, &row, tolerance),
        (
            "each value is the mean of a texel and its left neighbour, a ramp shifted by half \
             a texel",
            "sample at (i + 0.5) / N, or read by index with texelFetch",
        ),
    );
    let fixed = sample(0.5)?;
    run.pass(
        "fault 1 fixed: at (i + 0.5) / N",
        SAMPLE,
        "the same row sampled at each texel's centre",
        Some(PassBuffer::floats(ROW, 1, 1, fixed.clone()).with_reference(row.clone())),
    );
    run.check_texels(
        "fault 1 fixed: centres read each texel's own value",
        grid,
        &fixed,
        &row,
        tolerance,
    );
    Ok(())
}

/// Fault 2: floats outside [0, 1] drawn into an RGBA8 target, which clamps them.
fn clamping_format(ctx: &Context, run: &mut LessonRun) -> anyhow::Result<()> {
    let n = SIDE * SIDE;
    let values: Vec<f32> = (0..n)
        .map(|k| -1.5 + 4.0 * k as f32 / (n - 1) as f32)
        .collect();
    let input = Texture::from_f32(ctx, SIDE, SIDE, TextureFormat::R32F, &values)?;
    let program = Program::rect(ctx, &[shader!("glsl/learn/texture_copy.frag")])?;
    let grid = Grid::new(SIDE, SIDE, 1);
    let copy = |format: TextureFormat| -> anyhow::Result<Vec<f32>> {
        let target = Texture::new_2d(ctx, SIDE, SIDE, format)?;
        let fb = Framebuffer::new(ctx, format.name(), &[&target], None)?;
        fb.pass(&program, "copy")?
            .texture("u_input", &input)
            .draw_full()?;
        Ok(match format {
            TextureFormat::Rgba8 => {
                let bytes = target.download_u8()?;
                bytes.chunks_exact(4).map(|t| t[0] as f32 / 255.0).collect()
            }
            _ => target.download_f32()?,
        })
    };
    let faulty = copy(TextureFormat::Rgba8)?;
    run.pass(
        "fault 2: floats into RGBA8",
        COPY,
        "values from -1.5 to 2.5 copied into an RGBA8 target and read back",
        Some(PassBuffer::floats(SIDE, SIDE, 1, faulty.clone()).with_reference(values.clone())),
    );
    // Inside [0, 1] RGBA8 is only rounded (half a step, 0.5 / 255): beyond that, it clamped.
    found(
        run,
        (2, "a format that clamps"),
        "the texel-by-texel comparison (and the .npy that --png writes)",
        compared(grid, &faulty, &values, 0.5 / 255.0 + 1e-6),
        (
            "values below 0 come back as 0, above 1 as 1, the rest in steps of 1/255",
            "draw into a float format (R32F, RGBA32F) and read back floats",
        ),
    );
    let fixed = copy(TextureFormat::R32F)?;
    run.pass(
        "fault 2 fixed: floats into R32F",
        COPY,
        "the same copy into an R32F target",
        Some(PassBuffer::floats(SIDE, SIDE, 1, fixed.clone()).with_reference(values.clone())),
    );
    run.check_texels(
        "fault 2 fixed: R32F keeps every value (exact)",
        grid,
        &fixed,
        &values,
        0.0,
    );
    Ok(())
}

/// Fault 3: a Jacobi step reading the texture it draws into (a rendering feedback loop).
fn feedback_loop(ctx: &Context, run: &mut LessonRun) -> anyhow::Result<()> {
    let start = initial_grid(GRID);
    let program = Program::rect(ctx, &[shader!("glsl/learn/jacobi.frag")])?;
    let size = glam::IVec2::new(GRID as i32, GRID as i32);
    let one = Texture::from_f32(ctx, GRID, GRID, TextureFormat::R32F, &start)?;
    let fb = Framebuffer::new(ctx, "one texture", &[&one], None)?;
    // region: feedback-loop-found
    let mut pass = fb.pass(&program, "jacobi in place")?;
    pass.texture("u_current", &one).uniform("u_size", size);
    let loops = pass.feedback_loops();
    // endregion
    // Found before drawing: GL leaves the result undefined, so it is not drawn at all.
    drop(pass);
    found(
        run,
        (3, "reading the texture being drawn"),
        "the GL layer's check Pass::feedback_loops",
        (!loops.is_empty()).then(|| {
            format!(
                "pass 'jacobi in place' samples {} from the texture it draws into",
                loops.join(", ")
            )
        }),
        (
            "GL leaves the result undefined: a renderer may give the right grid, a mix of old \
             and new values, or anything, and another renderer something else",
            "ping-pong: read one texture, draw into another, swap them after each step",
        ),
    );
    let (a, b) = (
        Texture::from_f32(ctx, GRID, GRID, TextureFormat::R32F, &start)?,
        Texture::new_2d(ctx, GRID, GRID, TextureFormat::R32F)?,
    );
    // region: ping-pong-fix
    let fb = Framebuffer::new(ctx, "ping-pong target", &[&b], None)?;
    let mut pass = fb.pass(&program, "jacobi, ping-pong")?;
    pass.texture("u_current", &a).uniform("u_size", size);
    anyhow::ensure!(
        pass.feedback_loops().is_empty(),
        "the ping-pong pass reads the texture it draws into"
    );
    pass.draw_full()?;
    // endregion
    let gpu = b.download_f32()?;
    let cpu = jacobi_cpu(&start, GRID, 1);
    run.pass(
        "fault 3 fixed: ping-pong",
        JACOBI,
        "one Jacobi step read from one texture and drawn into another",
        Some(PassBuffer::floats(GRID, GRID, 1, gpu.clone()).with_reference(cpu.clone())),
    );
    run.check_texels(
        "fault 3 fixed: one step = the CPU's Jacobi step (1e-5, as lesson 2)",
        Grid::new(GRID, GRID, 1),
        &gpu,
        &cpu,
        1e-5,
    );
    Ok(())
}

/// The 2x2 reduction of `values` (`SIDE x SIDE`) down to one texel: each level's sums (red).
fn reduce_levels(
    ctx: &Context,
    program: &Program,
    values: &[f32],
) -> anyhow::Result<Vec<Vec<f32>>> {
    let rg: Vec<f32> = values.iter().flat_map(|&v| [v, v, 0.0, 0.0]).collect();
    let mut level = Texture::from_f32(ctx, SIDE, SIDE, TextureFormat::Rgba32F, &rg)?;
    let mut sums = Vec::new();
    while level.width() > 1 {
        let side = level.width().div_ceil(2);
        let next = Texture::new_2d(ctx, side, side, TextureFormat::Rgba32F)?;
        let fb = Framebuffer::new(ctx, "reduction level", &[&next], None)?;
        let size = glam::IVec2::new(level.width() as i32, level.height() as i32);
        fb.pass(program, "reduce")?
            .texture("u_level", &level)
            .uniform("u_size", size)
            .draw_full()?;
        sums.push(next.download_f32()?.chunks_exact(4).map(|t| t[0]).collect());
        level = next;
    }
    Ok(sums)
}

/// Fault 4: one NaN among the values (0/0 left by an earlier step) reaches the sum.
fn nan_in_reduction(ctx: &Context, run: &mut LessonRun) -> anyhow::Result<()> {
    let program = Program::rect(ctx, &[shader!("glsl/learn/reduce_2x2.frag")])?;
    let clean = super::kit::values((SIDE * SIDE) as usize, 11);
    let mut faulty = clean.clone();
    let bad = (2 * SIDE + 5) as usize;
    faulty[bad] = f32::NAN;
    let levels = reduce_levels(ctx, &program, &faulty)?;
    for (k, sums) in levels.iter().enumerate() {
        let side = SIDE >> (k + 1);
        run.pass(
            &format!("fault 4: level {}", k + 1),
            REDUCE,
            "the sums of each 2x2 block; the NaN's block is NaN, and so is every block above it",
            Some(PassBuffer::floats(side, side, 1, sums.clone()).in_set("nan")),
        );
    }
    let non_finite: Vec<String> = levels
        .iter()
        .map(|l| l.iter().filter(|v| !v.is_finite()).count().to_string())
        .collect();
    let top = levels.last().map_or(0.0, |l| l[0]);
    let refused = ensure_finite([top], "the sum of the values", "reduce").err();
    found(
        run,
        (4, "a NaN spreading through a reduction"),
        "the non-finite texels of each level (magenta in the pictures) and ensure_finite",
        refused.map(|e| {
            format!(
                "non-finite texels per level: {} (one at texel ({}, {}) of the input); {e}",
                non_finite.join(", "),
                bad as u32 % SIDE,
                bad as u32 / SIDE
            )
        }),
        (
            "one NaN makes its block's sum NaN, and every level above it, up to the result",
            "find the pass that made it (the first level whose picture has magenta) and keep \
             its inputs in its domain; check every result read back with ensure_finite",
        ),
    );
    let levels = reduce_levels(ctx, &program, &clean)?;
    let sum = levels.last().map_or(f32::NAN, |l| l[0]);
    let cpu: f64 = clean.iter().map(|&v| v as f64).sum();
    // Each value goes through one addition per level (three of 2x2 blocks: 3 each).
    let tolerance = 9.0 / 16_777_216.0 * cpu;
    run.check(
        "fault 4 fixed: without the NaN the sum = the CPU's (f64) sum (9 additions' rounding)",
        (sum as f64 - cpu).abs(),
        tolerance,
    );
    Ok(())
}

/// Fault 5: a depth texture given as a colour attachment, which GL calls incomplete.
fn incomplete_framebuffer(ctx: &Context, run: &mut LessonRun) -> anyhow::Result<()> {
    let values = super::kit::values((SIDE * SIDE) as usize, 5);
    let input = Texture::from_f32(ctx, SIDE, SIDE, TextureFormat::R32F, &values)?;
    let depth = Texture::new_2d(ctx, SIDE, SIDE, TextureFormat::Depth32F)?;
    // region: incomplete-refused
    let refused = Framebuffer::new(ctx, "depth as colour", &[&depth], None).err();
    // endregion
    found(
        run,
        (5, "an incomplete framebuffer"),
        "the GL layer's framebuffer checks",
        refused
            .map(|e| e.to_string())
            .filter(|e| e.contains("depth as colour")),
        (
            "GL would refuse to draw (GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT) and every pass \
             would fail with GL_INVALID_FRAMEBUFFER_OPERATION, or leave the target untouched",
            "attach colour formats as colour and the depth texture as depth; every framebuffer \
             made here is also checked with glCheckFramebufferStatus",
        ),
    );
    let colour = Texture::new_2d(ctx, SIDE, SIDE, TextureFormat::R32F)?;
    // region: complete-framebuffer
    let fb = Framebuffer::new(ctx, "colour and depth", &[&colour], Some(&depth))?;
    let program = Program::rect(ctx, &[shader!("glsl/learn/texture_copy.frag")])?;
    fb.pass(&program, "copy")?
        .texture("u_input", &input)
        .draw_full()?;
    // endregion
    let gpu = colour.download_f32()?;
    run.check_texels(
        "fault 5 fixed: the copy through the complete framebuffer = the values (exact)",
        Grid::new(SIDE, SIDE, 1),
        &gpu,
        &values,
        0.0,
    );
    Ok(())
}

/// Build a program from a text made on purpose, out of the reach of `--glsl-dir` (which would
/// replace it by name).
fn program_from(ctx: &Context, source: ShaderSource) -> Result<Program, GlError> {
    let given = ctx.glsl_dir();
    ctx.set_glsl_dir(None);
    let program = Program::rect(ctx, &[source]);
    ctx.set_glsl_dir(given);
    program
}

/// Fault 6: a type misspelt in the copy shader.
fn broken_shader(ctx: &Context, run: &mut LessonRun) -> anyhow::Result<()> {
    let shipped = shader!("glsl/learn/texture_copy.frag");
    let broken = shipped.source.replace("float value =", "flot value =");
    anyhow::ensure!(
        broken != shipped.source,
        "{COPY} changed: the fault is not made"
    );
    let line = broken
        .lines()
        .position(|l| l.contains("flot value"))
        .map(|i| i as u32 + 1);
    let error = program_from(
        ctx,
        ShaderSource {
            name: COPY,
            source: &broken,
        },
    )
    .err();
    let evidence = match &error {
        Some(GlError::Shader(e)) if e.file == COPY && e.line == line => {
            let place = format!("{}:{}:", e.file, e.line.unwrap_or(0));
            let first = e.log.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
            Some(format!(
                "{place} {}",
                first.trim().trim_start_matches(&place).trim()
            ))
        }
        _ => None,
    };
    found(
        run,
        (6, "a shader that does not compile"),
        "the compile error, with the file and the line",
        evidence,
        (
            "no program: the pass cannot run at all",
            "read the line the error names; `--glsl-dir` and the viewer's reload show the same \
             error for a file being edited",
        ),
    );
    let program = program_from(ctx, shipped)?;
    let values = super::kit::values((SIDE * SIDE) as usize, 6);
    let input = Texture::from_f32(ctx, SIDE, SIDE, TextureFormat::R32F, &values)?;
    let target = Texture::new_2d(ctx, SIDE, SIDE, TextureFormat::R32F)?;
    let fb = Framebuffer::new(ctx, "copy", &[&target], None)?;
    fb.pass(&program, "copy")?
        .texture("u_input", &input)
        .draw_full()?;
    run.check_texels(
        "fault 6 fixed: the shipped file compiles, and its copy = the values (exact)",
        Grid::new(SIDE, SIDE, 1),
        &target.download_f32()?,
        &values,
        0.0,
    );
    Ok(())
}

/// Fault 7: the fragment stage reads a varying the vertex stage does not write.
fn varying_mismatch(ctx: &Context, run: &mut LessonRun) -> anyhow::Result<()> {
    let shipped = shader!("glsl/learn/debugging/uv_ramp.frag");
    let renamed = shipped.source.replace("v_uv", "v_texcoord");
    let (w, h) = (SIDE, SIDE / 2);
    let draw = |program: &Program| -> anyhow::Result<Vec<f32>> {
        let target = Texture::new_2d(ctx, w, h, TextureFormat::Rgba32F)?;
        let fb = Framebuffer::new(ctx, "uv", &[&target], None)?;
        fb.pass(program, "uv")?.draw_full()?;
        Ok(target.download_f32()?)
    };
    let cpu: Vec<f32> = (0..h)
        .flat_map(|j| {
            (0..w).flat_map(move |i| {
                let u = (i as f32 + 0.5) / w as f32;
                let v = (j as f32 + 0.5) / h as f32;
                [u, v, 0.0, 0.0]
            })
        })
        .collect();
    let grid = Grid::new(w, h, 4);
    // Interpolated in fp32 across the rectangle: within 1e-5 of the exact centre.
    let tolerance = 1e-5;
    // A desktop GL linker may refuse the program (naming the varying) or only warn and leave
    // the input undefined; then the comparison with the CPU finds it.
    let evidence = match program_from(
        ctx,
        ShaderSource {
            name: UV,
            source: &renamed,
        },
    ) {
        Err(GlError::Link { log, .. }) => log
            .lines()
            .find(|l| l.contains("v_texcoord"))
            .map(|l| format!("the link error: {}", l.trim())),
        Ok(program) => compared(grid, &draw(&program)?, &cpu, tolerance).map(|c| {
            format!("it linked here (the input is left undefined), and the comparison: {c}")
        }),
        Err(_) => None,
    };
    found(
        run,
        (7, "a varying whose name does not match"),
        "the link error that names the varying, or the texel-by-texel comparison",
        evidence,
        (
            "each stage compiles on its own; the program does not link, or links and reads \
             an input nothing writes",
            "give the fragment stage's input the name and type of the vertex stage's output \
             (v_uv, written by glsl/gl/rect.vert)",
        ),
    );
    let program = program_from(ctx, shipped)?;
    let gpu = draw(&program)?;
    run.pass(
        "fault 7 fixed: v_uv",
        UV,
        "the rectangle's coordinate at each fragment's centre, (i + 0.5) / W and (j + 0.5) / H",
        Some(
            PassBuffer::floats(w, h, 4, gpu.clone())
                .with_reference(cpu.clone())
                .named(&["u", "v", "0", "0"]),
        ),
    );
    run.check_texels(
        "fault 7 fixed: v_uv = the fragment centre's coordinate (1e-5)",
        grid,
        &gpu,
        &cpu,
        tolerance,
    );
    Ok(())
}
