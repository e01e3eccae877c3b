//! `classic-gpgpu crowd`: render a crowd off-screen with either skinning method, report
//! frames per second and the time of each pass, and write a snapshot (paper Fig. 3-5).
//! (`crowd-bench`, the paper's Table 1 and LOD runs, is `report::paper2` through
//! `report::bench_command`.)

use std::path::PathBuf;

use anyhow::{bail, Context as _};
use serde_json::json;

use classic_gpgpu::gl::{dump, Context};

use classic_gpgpu::crowd::character::{CharacterModel, ModelKind};
use classic_gpgpu::crowd::renderer::{CrowdRenderer, Method};
use classic_gpgpu::crowd::scene::{self, RunStats};
use classic_gpgpu::crowd::LodPolicy;

/// Arguments of `crowd`.
#[derive(clap::Args, Debug, Clone)]
pub struct CrowdArgs {
    /// Which character.
    #[arg(long, value_enum, default_value = "soldier")]
    pub model: ModelArg,
    /// How many characters (n).
    #[arg(long, default_value_t = 256)]
    pub characters: usize,
    /// Skinning in a pixel shader + render-to-VBO (the paper) or in the vertex shader.
    #[arg(long, value_enum, default_value = "two-pass")]
    pub method: MethodArg,
    /// The paper's three LOD meshes and view-frustum culling (Fig. 4-5); without it every
    /// character is skinned at full detail, as in Table 1.
    #[arg(long)]
    pub lod: bool,
    /// With --lod, also draw characters beyond 90 m as sprites: this project's extension,
    /// not in the paper.
    #[arg(long, requires = "lod")]
    pub sprites: bool,
    /// Timed frames (after one warm-up frame).
    #[arg(long, default_value_t = 10)]
    pub frames: usize,
    /// Image size, WxH.
    #[arg(long, default_value = "800x600", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Write the last frame here as PNG.
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// Characters per draw call of the vertex-shader method (default: as many as the
    /// uniforms hold; 1 is how the paper's hardware generation ran it).
    #[arg(long)]
    pub vs_batch: Option<u32>,
    /// Characters per pass-1 draw of the two-pass method (default: as many as one render
    /// target holds, 3,712 soldiers at LOD 0 on 16384-texel targets; the paper skins all
    /// characters in one draw). A smaller value runs the several-batch path.
    #[arg(long)]
    pub skin_batch: Option<usize>,
    /// Seed of the crowd's placement and wandering.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    #[command(flatten)]
    pub profile: super::profile::ProfileArg,
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

/// Parses `WxH`.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("size '{text}' is not WxH with positive integers (e.g. 800x600)");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if w == 0 || h == 0 {
        return Err(bad());
    }
    Ok((w, h))
}

/// Runs `crowd`.
pub fn run(args: &CrowdArgs, ctx: &Context, json: bool) -> anyhow::Result<()> {
    if args.characters == 0 {
        bail!("--characters must be at least 1");
    }
    if args.frames == 0 {
        bail!("--frames must be at least 1");
    }
    let (w, h) = args.size;
    let [max_w, max_h] = ctx.info().limits.max_viewport_dims;
    if w > max_w || h > max_h {
        bail!("--size {w}x{h} exceeds this renderer's largest viewport {max_w}x{max_h}");
    }
    let (kind, method) = (ModelKind::from(args.model), Method::from(args.method));
    let model = CharacterModel::build(kind).context("building the character model")?;
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
