//! `classic-gpgpu crowd`: render a crowd off-screen with either skinning method, report
//! frames per second and the time of each pass, and write a snapshot (paper Fig. 3-5).
//! (`crowd-bench`, the paper's Table 1 and LOD runs, is `report::paper2` through
//! `report::bench_command`.)

use std::path::PathBuf;

use anyhow::{bail, Context as _};
use serde_json::json;

use classic_gpgpu::gl::{dump, Context};

use classic_gpgpu::crowd::character::{CharacterModel, ModelKind};
use classic_gpgpu::crowd::compute::{self, ComputeCrowd};
use classic_gpgpu::crowd::renderer::{CrowdRenderer, Method};
use classic_gpgpu::crowd::scene::{self, RunStats};
use classic_gpgpu::crowd::LodPolicy;
use classic_gpgpu::values::{ranges, Count};

/// Arguments of `crowd`.
#[derive(clap::Args, Debug, Clone)]
pub struct CrowdArgs {
    /// Which character.
    #[arg(long, value_enum, default_value = "soldier")]
    pub model: ModelArg,
    /// How many characters (n).
    #[arg(long, default_value_t = 256, value_parser = CHARACTERS.of::<usize>())]
    pub characters: usize,
    /// Skinning in a pixel shader + render-to-VBO (the paper) or in the vertex shader
    /// [default: two-pass] (classic formulation only).
    #[arg(long, value_enum)]
    pub method: Option<MethodArg>,
    /// The paper's three LOD meshes and view-frustum culling (Fig. 4-5); without it every
    /// character is skinned at full detail, as in Table 1.
    #[arg(long)]
    pub lod: bool,
    /// With --lod, also draw characters beyond 90 m as sprites: this project's extension,
    /// not in the paper.
    #[arg(long, requires = "lod")]
    pub sprites: bool,
    /// Timed frames (after a warm-up frame of a few characters per level).
    #[arg(long, default_value_t = 10, value_parser = ranges::frames_kept(1 << 10).of::<usize>())]
    pub frames: usize,
    /// Image size, WxH.
    #[arg(long, default_value = "800x600", value_parser = ranges::picture(1))]
    pub size: (u32, u32),
    /// Write the last frame here as PNG (an existing file only with --force).
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// Replace the --png file if it exists.
    #[arg(long, requires = "png")]
    pub force: bool,
    /// Characters per draw call of the vertex-shader method (default: as many as the
    /// uniforms hold; 1 is how the paper's hardware generation ran it).
    #[arg(long, value_parser = CHARACTERS.of::<u32>())]
    pub vs_batch: Option<u32>,
    /// Characters per pass-1 draw of the two-pass method (default: as many as one render
    /// target holds, 3,712 soldiers at LOD 0 on 16384-texel targets; the paper skins all
    /// characters in one draw). A smaller value runs the several-batch path.
    #[arg(long, value_parser = CHARACTERS.of::<usize>())]
    pub skin_batch: Option<usize>,
    /// Seed of the crowd's placement and wandering.
    #[arg(long, default_value_t = 1, value_parser = ranges::SEED.of::<u64>())]
    pub seed: u64,
    /// The paper's passes (classic, with --method) or compute skinning into a storage buffer
    /// drawn directly (compute, OpenGL 4.3; no sprites, --method and the batch sizes do not
    /// apply).
    #[arg(long, value_enum, default_value_t)]
    pub formulation: super::Formulation,
    #[command(flatten)]
    pub profile: super::profile::ProfileArg,
    #[command(flatten)]
    pub period: super::period::PeriodArg,
}

/// The library's [`ModelKind`], as the command line names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ModelArg {
    /// The procedural humanoid.
    Soldier,
    /// The procedural quadruped.
    Horse,
}

impl From<ModelArg> for ModelKind {
    fn from(m: ModelArg) -> ModelKind {
        match m {
            ModelArg::Soldier => ModelKind::Soldier,
            ModelArg::Horse => ModelKind::Horse,
        }
    }
}

/// The library's [`Method`], as the command line names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum MethodArg {
    /// The paper's: skinning in a pixel shader, render-to-VBO, a drawing pass.
    TwoPass,
    /// The baseline: skinning in the vertex shader, bone matrices in uniforms.
    VertexShader,
}

impl From<MethodArg> for Method {
    fn from(m: MethodArg) -> Method {
        match m {
            MethodArg::TwoPass => Method::TwoPass,
            MethodArg::VertexShader => Method::VertexShader,
        }
    }
}

/// Memory per character, measured: 46 KiB (soldier, two-pass, llvmpipe: 512 against 4096
/// characters), rounded up.
const CHARACTER_BYTES: u64 = 64 << 10;

/// `--characters` (and the batches, which never need more): what fits in memory.
pub const CHARACTERS: Count = Count::in_memory(
    "a number of characters",
    1,
    CHARACTER_BYTES,
    "character's skinned vertices and instance data",
);

/// Refuses a batch size of the method that does not run: `--vs-batch` is the vertex-shader
/// method's, `--skin-batch` the two-pass method's pass 1.
fn check_batches(args: &CrowdArgs) -> anyhow::Result<()> {
    let method = args.method.unwrap_or(MethodArg::TwoPass);
    if method == MethodArg::TwoPass && args.vs_batch.is_some() {
        bail!(
            "--vs-batch sets the characters per draw of the vertex-shader method, which is not \
             running (the method is two-pass{}): add --method vertex-shader, or leave out \
             --vs-batch (--skin-batch is two-pass's batch)",
            if args.method.is_none() {
                ", the default"
            } else {
                ""
            }
        );
    }
    if method == MethodArg::VertexShader && args.skin_batch.is_some() {
        bail!(
            "--skin-batch sets the characters per pass-1 draw of the two-pass method, which is \
             not running (--method vertex-shader has no pass 1): leave out --skin-batch, or use \
             --vs-batch for the vertex-shader method's draws"
        );
    }
    Ok(())
}

/// Runs `crowd`.
pub fn run(args: &CrowdArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    args.period.apply(ctx, 2);
    if let Some(png) = &args.png {
        classic_gpgpu::files::check_output("--png", png, &[], args.force, &["png"])?;
    }
    let (w, h) = args.size;
    let [max_w, max_h] = ctx.info().limits.max_viewport_dims;
    if w > max_w || h > max_h {
        bail!("--size {w}x{h} exceeds this renderer's largest viewport {max_w}x{max_h}");
    }
    if args.formulation == super::Formulation::Classic {
        check_batches(args)?;
    }
    let (kind, method) = (
        ModelKind::from(args.model),
        Method::from(args.method.unwrap_or(MethodArg::TwoPass)),
    );
    let model = CharacterModel::build(kind).context("building the character model")?;
    if args.formulation == super::Formulation::Compute {
        return run_compute(args, ctx, model, json);
    }
    let mut renderer = CrowdRenderer::new(ctx, model).context("setting up the crowd renderer")?;
    if let Some(batch) = args.vs_batch {
        if batch == 0 {
            bail!("--vs-batch must be at least 1");
        }
        renderer.set_vertex_shader_batch(batch);
    }
    if let Some(batch) = args.skin_batch {
        if batch == 0 {
            bail!("--skin-batch must be at least 1");
        }
        renderer.set_batch_limit(Some(batch));
    }
    let target = scene::scene_target(ctx, w, h)?;
    let aspect = w as f32 / h as f32;
    let mut scene = if args.lod {
        let policy = if args.sprites {
            LodPolicy::with_sprites()
        } else {
            LodPolicy::default()
        };
        scene::lod_scene(kind, args.characters, aspect, args.seed, policy)
    } else {
        scene::table1_scene(kind, args.characters, aspect, args.seed)
    };
    args.profile.start(ctx);
    let stats = scene::run(
        ctx,
        &mut renderer,
        &target,
        &mut scene,
        method,
        args.frames,
        1.0 / 30.0,
    )?;
    super::profile::print(ctx);
    if let Some(path) = &args.png {
        dump::texture_png(target.color(0), path, dump::DumpRange::Auto)
            .with_context(|| format!("writing the snapshot {}", path.display()))?;
    }
    if json {
        let value = json!({
            "renderer": ctx.info().renderer,
            "formulation": "classic",
            "size": [w, h],
            "vertex_shader_batch": renderer.vertex_shader_batch(),
            "pass1_characters_per_draw": (0..renderer.model.lods.len())
                .map(|lod| renderer.batch_limit(lod))
                .collect::<Vec<_>>(),
            "run": stats,
            "png": args.png,
        });
        println!("{}", serde_json::to_string_pretty(&value)?);
    } else {
        print_text(ctx, &stats, &args.png, renderer.vertex_shader_batch());
    }
    Ok(())
}

/// `crowd --formulation compute`.
fn run_compute(
    args: &CrowdArgs,
    ctx: &Context,
    model: CharacterModel,
    json: bool,
) -> anyhow::Result<()> {
    if let Some(method) = args.method {
        bail!(
            "--method {}: the compute formulation has one method of its own (compute skinning \
             into a storage buffer); --method chooses between the classic formulation's two",
            clap::ValueEnum::to_possible_value(&method)
                .map_or_else(String::new, |v| v.get_name().to_string())
        );
    }
    if args.sprites || args.vs_batch.is_some() || args.skin_batch.is_some() {
        bail!(
            "--sprites, --vs-batch and --skin-batch belong to the classic formulation; the \
             compute formulation skins each LOD in one dispatch and draws it in one call"
        );
    }
    let kind = model.kind;
    let mut crowd = ComputeCrowd::new(ctx, model).context("setting up the compute crowd")?;
    let (w, h) = args.size;
    let target = scene::scene_target(ctx, w, h)?;
    let aspect = w as f32 / h as f32;
    let mut scene = if args.lod {
        scene::lod_scene(
            kind,
            args.characters,
            aspect,
            args.seed,
            LodPolicy::default(),
        )
    } else {
        scene::table1_scene(kind, args.characters, aspect, args.seed)
    };
    let stats = compute::run(
        ctx,
        &mut crowd,
        &target,
        &mut scene,
        args.frames,
        1.0 / 30.0,
    )?;
    if let Some(path) = &args.png {
        dump::texture_png(target.color(0), path, dump::DumpRange::Auto)
            .with_context(|| format!("writing the snapshot {}", path.display()))?;
    }
    if json {
        let value = json!({
            "renderer": ctx.info().renderer,
            "formulation": "compute",
            "size": [w, h],
            "run": stats,
            "png": args.png,
        });
        println!("{}", serde_json::to_string_pretty(&value)?);
    } else {
        let p = &stats.passes;
        println!(
            "renderer        {} (compute formulation)",
            ctx.info().renderer
        );
        println!("crowd           {} x {}", stats.characters, stats.model);
        println!(
            "frame           {:.2} ms wall clock, {:.1} FPS over {} frames",
            stats.frame_ms, stats.fps, stats.frames
        );
        println!(
            "bone matrices   {:.2} ms (CPU), upload {:.2} ms",
            p.bones_ms, p.upload_ms
        );
        println!(
            "skinning        {:.2} ms wall clock with glFinish, {:.2} ms GL timer query",
            p.wall.pass1, p.gl_timer.pass1
        );
        println!(
            "drawing         {:.2} ms wall clock with glFinish, {:.2} ms GL timer query",
            p.wall.pass2, p.gl_timer.pass2
        );
    }
    Ok(())
}

fn print_text(ctx: &Context, s: &RunStats, png: &Option<PathBuf>, batch: u32) {
    let p = &s.passes;
    println!("renderer        {}", ctx.info().renderer);
    println!(
        "crowd           {} x {} ({}), {}",
        s.characters,
        s.model,
        s.method,
        match (s.lod_and_culling, s.sprites_enabled) {
            (true, true) => "3 LOD meshes + culling + sprites (extension)",
            (true, false) => "3 LOD meshes + culling",
            _ => "full detail, no culling",
        }
    );
    println!(
        "frame           {:.2} ms wall clock, {:.1} FPS over {} frames",
        s.frame_ms, s.fps, s.frames
    );
    println!(
        "drawn           {} skinned (LOD {} / {} / {}), {} sprites, {} culled, {} triangles",
        p.skinned, s.per_lod[0], s.per_lod[1], s.per_lod[2], p.sprites, s.culled, p.triangles
    );
    println!("bone matrices   {:.2} ms (CPU)", p.bones_ms);
    let (g, w) = (&p.gl_timer, &p.wall);
    let line = |name: &str, gl: f64, wall: f64| {
        println!("{name:<15} {wall:.2} ms wall clock with glFinish, {gl:.2} ms GL timer query");
    };
    if s.method == Method::TwoPass.name() {
        println!("bone upload     {:.2} ms (CPU)", p.upload_ms);
        println!("pass-1 draws    {}", p.pass1_draws);
        line("pass 1 skinning", g.pass1, w.pass1);
        line("render-to-VBO", g.copy, w.copy);
        line("pass 2 drawing", g.pass2, w.pass2);
    } else {
        line("VS skinning", g.vertex_shader, w.vertex_shader);
        println!("                ({batch} characters per draw call)");
    }
    if p.sprites > 0 {
        line("sprites", g.sprites, w.sprites);
    }
    if let Some(path) = png {
        println!("snapshot        {}", path.display());
    }
}
